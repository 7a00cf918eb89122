/* Decimal text of doubles and ints without printf, see csv_format.h. */
#include "csv_format.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

static const double csv_scale[CSV_FIXED_MAX_DECIMALS + 1] = {1e0, 1e1, 1e2, 1e3, 1e4,
                                                             1e5, 1e6, 1e7, 1e8, 1e9};
static const uint64_t csv_scale_int[CSV_FIXED_MAX_DECIMALS + 1] = {
    1u, 10u, 100u, 1000u, 10000u, 100000u, 1000000u, 10000000u, 100000000u, 1000000000u};

/* Below 2^50 the scaled value's integer part is exact and its rounding error under 1/16, which
 * the rounding decision below relies on. */
#define CSV_SCALED_LIMIT 1125899906842624.0

static const char csv_digit_pairs[] = "00010203040506070809"
                                      "10111213141516171819"
                                      "20212223242526272829"
                                      "30313233343536373839"
                                      "40414243444546474849"
                                      "50515253545556575859"
                                      "60616263646566676869"
                                      "70717273747576777879"
                                      "80818283848586878889"
                                      "90919293949596979899";

/* Writes the last `width` decimal digits of v (leading zeros included) ending just before
 * end; returns the first written character. */
static char *csv_digits_backward(char *end, uint64_t v, int width)
{
    while (width >= 2) {
        const unsigned pair = (unsigned)(v % 100u);
        v /= 100u;
        end -= 2;
        end[0] = csv_digit_pairs[2u * pair];
        end[1] = csv_digit_pairs[2u * pair + 1u];
        width -= 2;
    }
    if (width == 1) {
        *--end = (char)('0' + (int)(v % 10u));
    }
    return end;
}

static int csv_digit_count(uint64_t v)
{
    int n = 1;
    while (v >= 10u) {
        v /= 10u;
        n++;
    }
    return n;
}

static char *csv_put_u64(char *out, uint64_t v)
{
    const int width = csv_digit_count(v);
    (void)csv_digits_backward(out + width, v, width);
    return out + width;
}

/* a * scale rounded to an integer as printf rounds: the exact product (fma gives the rounding
 * error of the double product), ties to even. Needs 0 <= a * scale < CSV_SCALED_LIMIT. */
static uint64_t csv_round_scaled(double a, double scale)
{
    const double product = a * scale;
    const double error = fma(a, scale, -product); /* product + error == a * scale exactly */
    /* floor without the library call: product is in [0, 2^50), where truncation is floor and
     * the signed conversion exact */
    uint64_t q = (uint64_t)(int64_t)product;
    const double frac = product - (double)(int64_t)q; /* exact */
    /* below 1/4 the exact fraction stays below 1/2 whatever the (< 1/16) error */
    if (frac >= 0.25) {
        const double above_half = frac - 0.5; /* exact: frac is within a factor 2 of 0.5 */
        if (above_half > -error || (above_half == -error && (q & 1u) != 0u)) {
            q++;
        }
    }
    return q;
}

char *csv_put_fixed(char *out, double v, int decimals)
{
    const double a = fabs(v);
    uint64_t q, whole;
    /* out-of-range precision, NaN, infinities and huge values: the C library's text */
    if (decimals < 0 || decimals > CSV_FIXED_MAX_DECIMALS ||
        !(a * csv_scale[decimals] < CSV_SCALED_LIMIT)) {
        char text[CSV_FIXED_MAX_CHARS + 1];
        const int n = snprintf(text, sizeof text, "%.*f", decimals, v);
        const size_t len = (n < 0) ? 0u : (size_t)n;
        memcpy(out, text, len);
        return out + len;
    }
    q = csv_round_scaled(a, csv_scale[decimals]);
    if (signbit(v)) {
        *out++ = '-';
    }
    whole = q / csv_scale_int[decimals];
    out = csv_put_u64(out, whole);
    if (decimals > 0) {
        *out++ = '.';
        (void)csv_digits_backward(out + decimals, q - whole * csv_scale_int[decimals], decimals);
        out += decimals;
    }
    return out;
}

char *csv_put_int(char *out, int v)
{
    uint64_t magnitude;
    if (v < 0) {
        *out++ = '-';
        magnitude = (uint64_t)(-(int64_t)v);
    } else {
        magnitude = (uint64_t)v;
    }
    return csv_put_u64(out, magnitude);
}
