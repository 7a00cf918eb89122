/*
 * The open-phase part of `sixphase-sim reproduce` (docs/faults.md, "Riding through an open
 * phase"): its runs (group "postfault") and its report section with the plots'
 * (plot_postfault.py) captions.
 */
#ifndef SIM_REPRODUCE_POSTFAULT_H
#define SIM_REPRODUCE_POSTFAULT_H

#include <stdio.h>

#include "reproduce_cases.h"

/* The load the derated drive can carry (minimum loss: 8.4 / 1.803 = 4.66 N m). */
#define REP_POSTFAULT_LOAD_NM 3.5

/* Every open-phase run appended to cases[0..*n); output under dir/runs/NAME. */
void rep_cases_postfault(rep_case_t *cases, int *n, const char *dir);

/* The report's open-phase section. */
void rep_section_postfault(FILE *f, const rep_case_t *cases, int n);

#endif /* SIM_REPRODUCE_POSTFAULT_H */
