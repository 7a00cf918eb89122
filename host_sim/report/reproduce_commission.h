/*
 * The reproduce report's commissioning section (reproduce_commission.c): its runs, added to the
 * reproduce batches, and the section of report.md.
 */
#ifndef SIM_REPRODUCE_COMMISSION_H
#define SIM_REPRODUCE_COMMISSION_H

#include <stdio.h>

#include "reproduce_cases.h"

/* The first batch's runs: the identification, the closed loops with the exact and the default
 * parameters, the mismatch sweep (cases comm_* and mm_*). */
void rep_cases_commission(rep_case_t *cases, int *n);

/* After the first batch: the closed loop with the identified set (comm_identified). */
void rep_cases_commission_identified(rep_case_t *cases, int *n);

/* Section 9 of report.md. */
void rep_write_commission_section(FILE *f, const rep_case_t *cases, int n);

#endif /* SIM_REPRODUCE_COMMISSION_H */
