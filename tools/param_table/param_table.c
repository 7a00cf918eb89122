/*
 * Prints the parameter set's ranges (control/include/ctl_param_ranges.h) as the markdown table
 * of docs/design.md, "The parameter set" (tools/param_table.py writes and checks it there).
 */
#include <stdio.h>

#include "ctl_params.h"

#define PRINT_ROW(row, field, error, lo, hi, unit, what, value)                                    \
    printf("| %s | `%s` | %g | %s | %s | %s | %s |\n", what, #field, (double)(value),              \
           CTL_RANGE_STR(lo), CTL_RANGE_STR(hi), (unit)[0] ? (unit) : "-",                         \
           ctl_param_error_text(error));

int main(void)
{
    printf("| parameter | field of `ctl_params_t` | default | minimum | maximum | unit | refused "
           "with |\n");
    printf("|---|---|---|---|---|---|---|\n");
    CTL_PARAM_RANGES(PRINT_ROW)
    return 0;
}
