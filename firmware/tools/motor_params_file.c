/* The motor parameter file, see motor_params_file.h. */
#include "motor_params_file.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "decimal_arg.h"

#define MP_NAME(id, name, text, unit, lo, hi, integer) name,
#define MP_TEXT(id, name, text, unit, lo, hi, integer) text,
#define MP_UNIT(id, name, text, unit, lo, hi, integer) unit,
#define MP_LO(id, name, text, unit, lo, hi, integer) lo,
#define MP_HI(id, name, text, unit, lo, hi, integer) hi,
#define MP_INT(id, name, text, unit, lo, hi, integer) integer,
static const char *const mp_name[] = {MOTOR_PARAM_LIST(MP_NAME)};
static const char *const mp_text[] = {MOTOR_PARAM_LIST(MP_TEXT)};
static const char *const mp_unit[] = {MOTOR_PARAM_LIST(MP_UNIT)};
static const double mp_lo[] = {MOTOR_PARAM_LIST(MP_LO)};
static const double mp_hi[] = {MOTOR_PARAM_LIST(MP_HI)};
static const int mp_integer[] = {MOTOR_PARAM_LIST(MP_INT)};
#undef MP_NAME
#undef MP_TEXT
#undef MP_UNIT
#undef MP_LO
#undef MP_HI
#undef MP_INT

#define MP_LINE_MAX 512

void motor_params_clear(motor_params_t *m) { memset(m, 0, sizeof *m); }

void motor_params_set(motor_params_t *m, motor_param_t id, double value, double sigma,
                      const char *note)
{
    m->have |= 1u << id;
    m->value[id] = value;
    m->sigma[id] = sigma;
    m->note[id] = note;
}

/* A plain decimal without a sign (decimal_arg.h: no leading zero, no hexadecimal) with an
 * optional f suffix, or for an integer entry digits with an optional u suffix; nothing else. */
static int mp_parse_value(const char *s, int integer, double *out)
{
    char buf[64];
    const size_t n = strlen(s);
    if (n == 0u || n >= sizeof buf || s[0] == '+' || s[0] == '-') {
        return -1;
    }
    memcpy(buf, s, n + 1u);
    if (buf[n - 1u] == (integer ? 'u' : 'f')) {
        buf[n - 1u] = '\0';
    }
    return decimal_parse(buf, integer, -HUGE_VAL, HUGE_VAL, out);
}

/* Whether v is a valid value of entry id: within its range and, for an integer entry, whole. */
static int mp_in_range(int id, double v)
{
    return v >= mp_lo[id] && v <= mp_hi[id] && (!mp_integer[id] || v == floor(v));
}

int motor_params_check(const motor_params_t *m, char *err, size_t err_len)
{
    int id;
    for (id = 0; id < (int)MOTOR_PARAM_COUNT; id++) {
        if ((m->have & (1u << id)) != 0u && !mp_in_range(id, m->value[id])) {
            (void)snprintf(err, err_len, "%s %s %.6g%s%s is outside %g..%g%s%s%s", mp_text[id],
                           mp_name[id], m->value[id], mp_unit[id][0] ? " " : "", mp_unit[id],
                           mp_lo[id], mp_hi[id], mp_unit[id][0] ? " " : "", mp_unit[id],
                           mp_integer[id] ? " (a whole number)" : "");
            return -1;
        }
    }
    return 0;
}

static int mp_fail(char *err, size_t len, const char *path, int line, const char *why)
{
    (void)snprintf(err, len, "%s line %d: %s", path, line, why);
    return -1;
}

/* One "#define NAME VALUE" line. */
static int mp_define(motor_params_t *m, char *text, const char *path, int line, char *err,
                     size_t len)
{
    char name[80], value[80], rest[8];
    int id;
    double v;
    if (sscanf(text, "#define %79s %79s %7s", name, value, rest) != 2) {
        return mp_fail(err, len, path, line, "expected #define NAME VALUE");
    }
    if (strncmp(name, MOTOR_PARAM_PREFIX, strlen(MOTOR_PARAM_PREFIX)) != 0) {
        return mp_fail(err, len, path, line, "not a " MOTOR_PARAM_PREFIX "* name");
    }
    for (id = 0; id < (int)MOTOR_PARAM_COUNT; id++) {
        if (strcmp(name + strlen(MOTOR_PARAM_PREFIX), mp_name[id]) == 0) {
            break;
        }
    }
    if (id == (int)MOTOR_PARAM_COUNT) {
        return mp_fail(err, len, path, line, "unknown name");
    }
    if ((m->have & (1u << id)) != 0u) {
        return mp_fail(err, len, path, line, "name given twice");
    }
    if (mp_parse_value(value, mp_integer[id], &v) != 0 || !mp_in_range(id, v)) {
        return mp_fail(err, len, path, line, "value not a plain number in range");
    }
    motor_params_set(m, (motor_param_t)id, v, 0.0, NULL);
    return 0;
}

/* A full-line comment or a blank line. */
static int mp_ignorable(const char *t)
{
    const size_t n = strlen(t);
    if (n == 0u || (t[0] == '/' && t[1] == '/')) {
        return 1;
    }
    return n >= 4u && strncmp(t, "/*", 2) == 0 && strcmp(t + n - 2u, "*/") == 0 &&
           strstr(t + 2, "*/") == t + n - 2u;
}

/* One line into buf (its newline kept); 1, 0 at the end of the file, -1 too long, -2 when it
 * holds a NUL byte (which would hide the rest of the line from this reader but not from the C
 * compiler: a comment opened after it would swallow the defines below). */
static int mp_read_line(FILE *f, char *buf, size_t cap)
{
    size_t n = 0u;
    int c;
    while ((c = getc(f)) != EOF) {
        if (c == '\0') {
            return -2;
        }
        if (n + 1u == cap) {
            return -1;
        }
        buf[n++] = (char)c;
        if (c == '\n') {
            break;
        }
    }
    buf[n] = '\0';
    return n > 0u ? 1 : 0;
}

int motor_params_read(const char *path, motor_params_t *m, char *err, size_t err_len)
{
    char buf[MP_LINE_MAX];
    int line = 0;
    int rc = 0;
    int got;
    FILE *f = fopen(path, "r");
    motor_params_clear(m);
    if (!f) {
        (void)snprintf(err, err_len, "cannot read %s: %s", path, strerror(errno));
        return -1;
    }
    while (rc == 0 && (got = mp_read_line(f, buf, sizeof buf)) != 0) {
        char *t = buf;
        size_t n;
        line++;
        if (got < 0) {
            rc = mp_fail(err, err_len, path, line, got == -1 ? "line too long" : "a NUL byte");
            break;
        }
        n = strlen(t);
        while (n > 0u && isspace((unsigned char)t[n - 1u])) {
            t[--n] = '\0';
        }
        while (isspace((unsigned char)*t)) {
            t++;
        }
        if (!mp_ignorable(t)) {
            rc = (strncmp(t, "#define", 7) == 0 && isspace((unsigned char)t[7]))
                     ? mp_define(m, t, path, line, err, err_len)
                     : mp_fail(err, err_len, path, line, "only #define lines and comments");
        }
    }
    if (rc == 0 && ferror(f)) { /* a directory, an I/O error: not an empty file */
        rc = -1;
        (void)snprintf(err, err_len, "cannot read %s: %s", path, strerror(errno));
    }
    if (rc == 0 && m->have == 0u) { /* a set of nothing is a wrong or truncated file */
        rc = -1;
        (void)snprintf(err, err_len, "%s: no " MOTOR_PARAM_PREFIX "* entry", path);
    }
    (void)fclose(f);
    return rc;
}

/* v as a C float literal: 7 significant digits, always with a point or an exponent. */
static void mp_float_literal(char *out, size_t len, double v)
{
    (void)snprintf(out, len, "%.7g", v);
    if (!strpbrk(out, ".eEn")) {
        const size_t n = strlen(out);
        if (n + 3u < len) {
            memcpy(out + n, ".0", 3u);
        }
    }
}

int motor_params_write(FILE *f, const motor_params_t *m, const char *origin)
{
    char lit[48], why[200];
    int id;
    if (motor_params_check(m, why, sizeof why) != 0) {
        return -1; /* a value the reader and the control core would refuse is not written */
    }
    fprintf(f, "/* Motor parameters of this drive's machine: %s. */\n", origin);
    fprintf(f, "/* The firmware takes it with -DSIXPHASE_MOTOR_PARAMS_FILE=<path> "
               "(docs/porting.md). */\n");
    for (id = 0; id < (int)MOTOR_PARAM_COUNT; id++) {
        if ((m->have & (1u << id)) == 0u) {
            continue;
        }
        if (id == (int)MOTOR_PARAM_ENCODER_OFFSET) {
            fprintf(f, "/* encoder index to d axis: %.3f deg +- %.3f (1 sigma)%s%s */\n",
                    m->value[id] * (360.0 / 4294967296.0), m->sigma[id] * (360.0 / 4294967296.0),
                    m->note[id] ? ", " : "", m->note[id] ? m->note[id] : "");
            fprintf(f, "#define " MOTOR_PARAM_PREFIX "%s %.0fu\n", mp_name[id], m->value[id]);
        } else if (mp_integer[id]) {
            fprintf(f, "/* %s%s%s */\n", mp_text[id], m->note[id] ? ", " : "",
                    m->note[id] ? m->note[id] : "");
            fprintf(f, "#define " MOTOR_PARAM_PREFIX "%s %.0fu\n", mp_name[id], m->value[id]);
        } else {
            fprintf(f, "/* %s, %s: +- %.3g (1 sigma)%s%s */\n", mp_text[id], mp_unit[id],
                    m->sigma[id], m->note[id] ? ", " : "", m->note[id] ? m->note[id] : "");
            mp_float_literal(lit, sizeof lit, m->value[id]);
            fprintf(f, "#define " MOTOR_PARAM_PREFIX "%s %sf\n", mp_name[id], lit);
        }
    }
    return ferror(f) ? -1 : 0;
}
