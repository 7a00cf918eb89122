/* Motor parameters of this drive's machine: identified by sixphase-link identify. */
/* The firmware takes it with -DSIXPHASE_MOTOR_PARAMS_FILE=<path> (docs/porting.md). */
/* stator resistance, ohm: +- 0.000871 (1 sigma), ok */
#define SIXPHASE_MOTOR_R_OHM 2.612735f
/* d-axis inductance, H: +- 2.66e-05 (1 sigma), ok */
#define SIXPHASE_MOTOR_LD_H 0.03014173f
/* q-axis inductance, H: +- 0.000101 (1 sigma), ok */
#define SIXPHASE_MOTOR_LQ_H 0.06252999f
/* x-y (leakage) inductance, H: +- 2.37e-05 (1 sigma), ok */
#define SIXPHASE_MOTOR_LXY_H 0.01209352f
/* magnet flux linkage, Wb: +- 3.8e-05 (1 sigma), ok */
#define SIXPHASE_MOTOR_PSI_F_WB 0.200346f
/* pole pairs (checked), checked by the count */
#define SIXPHASE_MOTOR_POLE_PAIRS 3u
/* encoder index to d axis: 76.984 deg +- 0.024 (1 sigma), ok */
#define SIXPHASE_MOTOR_ENCODER_OFFSET 918454895u
