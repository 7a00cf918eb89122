/*
 * The files `sixphase-sim reproduce` writes from its runs: report.md and summary.json, which
 * depend only on the commit (committed under docs/reproduce/; a rerun changes nothing), and
 * timings.md, the host's wall times and real-time factors (machine-dependent, not committed).
 */
#ifndef SIM_REPRODUCE_REPORT_H
#define SIM_REPRODUCE_REPORT_H

#include "reproduce_cases.h"

/* dir/report.md. 0 on success. */
int rep_write_report(const char *dir, const rep_case_t *cases, int n);

/* dir/summary.json: every run's metrics. 0 on success. */
int rep_write_summary(const char *dir, const rep_case_t *cases, int n);

/* dir/timings.md: wall time of the runs and each run's real-time factor and host ISR time. */
int rep_write_timings(const char *dir, const rep_case_t *cases, int n, double wall_s, int jobs);

#endif /* SIM_REPRODUCE_REPORT_H */
