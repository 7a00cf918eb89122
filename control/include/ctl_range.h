/*
 * The domain of the Q24 range analysis (docs/range-analysis.md), in per unit: every control step
 * clamps its sampled inputs into it (ctl_range_clamp, ctl_vsd.h), and ctl_model_init refuses a
 * parameter set whose model could carry an input of the domain beyond CTL_RANGE_BOUND anywhere
 * the step computes without a saturation test (the _bnd forms of ctl_q.h). Plain numbers: the
 * fixed build takes them through CTL_Q (each is exact in binary), the analysis as floats.
 */
#ifndef CTL_RANGE_H
#define CTL_RANGE_H

/* |i_alpha|, |i_beta|, |i_x|, |i_y|: 40 A, twice what the board's sensors read */
#define CTL_RANGE_CURRENT 4
#define CTL_RANGE_VDC 2   /* DC link 0 .. 1080 V (the board's divider reads up to 1.48) */
#define CTL_RANGE_SPEED 4 /* |omega_e|: 12,000 r/min at three pole pairs */
/* and at most this angle per period (rad): beyond it an Euler step of the rotor frame means
 * nothing; 4 per unit at 10 kHz is 0.38 rad, and at 2.3 kHz the bound is 1.8 per unit */
#define CTL_RANGE_ANGLE 0.75
/* |alpha| + |beta| (and |x| + |y|) of any switching state's or virtual vector's voltage per
 * unit of the DC link: 0.644 * sqrt(2) = 0.911 at most (test_range.c checks the tables). */
#define CTL_RANGE_VECTOR_SUM 0.9375
#define CTL_RANGE_BOUND 64 /* every bounded quantity, half of Q24's 128 */
/* The open-phase step's projected currents and forced responses are held to this (80 A): an
 * oblique projection can magnify a current by sqrt(max/min) of the model's coefficients, so
 * they end their expressions clamped here rather than at Q24's limit (ctl_postfault.c). */
#define CTL_RANGE_PROJECTED 8

#endif /* CTL_RANGE_H */
