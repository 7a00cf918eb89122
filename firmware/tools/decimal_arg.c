/* Plain decimal numbers for the host tools, see decimal_arg.h. */
#include "decimal_arg.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>

/* Digits from *s on: how many, *s moved past them. */
static int decimal_digits(const char **s)
{
    int n = 0;
    while (isdigit((unsigned char)**s)) {
        (*s)++;
        n++;
    }
    return n;
}

int decimal_is_plain(const char *s, int integer_only)
{
    const char *int_part;
    int digits;
    if (!s) {
        return 0;
    }
    if (*s == '+' || *s == '-') {
        s++;
    }
    int_part = s;
    digits = decimal_digits(&s);
    if (digits > 1 && int_part[0] == '0') {
        return 0; /* 010: a C reader takes it for octal */
    }
    if (!integer_only && *s == '.') {
        s++;
        digits += decimal_digits(&s);
    }
    if (digits == 0) {
        return 0;
    }
    if (!integer_only && (*s == 'e' || *s == 'E')) {
        s++;
        if (*s == '+' || *s == '-') {
            s++;
        }
        if (decimal_digits(&s) == 0) {
            return 0;
        }
    }
    return *s == '\0';
}

int decimal_parse(const char *s, int integer_only, double lo, double hi, double *out)
{
    char *end = NULL;
    double v;
    if (!decimal_is_plain(s, integer_only)) {
        return -1;
    }
    errno = 0;
    v = strtod(s, &end);
    if (errno != 0 || *end != '\0' || !isfinite(v) || !(v >= lo && v <= hi)) {
        return -1;
    }
    *out = v;
    return 0;
}
