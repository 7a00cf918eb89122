/*
 * The motor parameter file: the identified machine as a C header of #defines, written by
 * `sixphase-link identify --out FILE` (and `sixphase-sim run --scenario commission --out
 * DIR`), read back by the firmware build (-DSIXPHASE_MOTOR_PARAMS="FILE": fw.h includes it,
 * fw_startup.c uses its values instead of the reference machine's) and by
 * `sixphase-sim --ctl-params FILE`. docs/porting.md section 8.
 *
 * The file holds only full-line comments ("/ * ... * /" on one line), blank lines and lines
 * "#define NAME VALUE" with a name of MOTOR_PARAM_LIST; every entry is optional (a missing
 * one keeps the reference machine's value), but not all of them (a file without any is the
 * wrong file or a truncated one). The reader refuses anything else: another line,
 * an unknown or repeated name, a value that is not a plain number of its kind (a float with
 * an optional f suffix, an unsigned integer with an optional u suffix) or outside its range.
 * Host code only.
 */
#ifndef MOTOR_PARAMS_FILE_H
#define MOTOR_PARAMS_FILE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "ctl_param_ranges.h"

/* X(id, NAME suffix, description, unit, lo, hi, is_integer); the controller's ranges are the
 * core's (ctl_param_ranges.h), the encoder offset's and the friction's the file's own */
#define MOTOR_PARAM_LIST(X)                                                                        \
    X(MOTOR_PARAM_R, "R_OHM", "stator resistance", "ohm", CTL_RESISTANCE_MIN, CTL_RESISTANCE_MAX,  \
      0)                                                                                           \
    X(MOTOR_PARAM_LD, "LD_H", "d-axis inductance", "H", CTL_INDUCTANCE_MIN, CTL_INDUCTANCE_MAX, 0) \
    X(MOTOR_PARAM_LQ, "LQ_H", "q-axis inductance", "H", CTL_INDUCTANCE_MIN, CTL_INDUCTANCE_MAX, 0) \
    X(MOTOR_PARAM_LXY, "LXY_H", "x-y (leakage) inductance", "H", CTL_INDUCTANCE_MIN,               \
      CTL_INDUCTANCE_MAX, 0)                                                                       \
    X(MOTOR_PARAM_PSI_F, "PSI_F_WB", "magnet flux linkage", "Wb", CTL_PM_FLUX_MIN,                 \
      CTL_PM_FLUX_MAX, 0)                                                                          \
    X(MOTOR_PARAM_POLE_PAIRS, "POLE_PAIRS", "pole pairs (checked)", "", CTL_POLE_PAIRS_MIN,        \
      CTL_POLE_PAIRS_MAX, 1)                                                                       \
    X(MOTOR_PARAM_ENCODER_OFFSET, "ENCODER_OFFSET",                                                \
      "electrical angle of the encoder index to the d axis, 2^32 = one turn", "", 0.0,             \
      4294967295.0, 1)                                                                             \
    X(MOTOR_PARAM_INERTIA, "INERTIA_KG_M2", "rotor and load inertia", "kg m^2", CTL_INERTIA_MIN,   \
      CTL_INERTIA_MAX, 0)                                                                          \
    X(MOTOR_PARAM_FRICTION, "FRICTION_NMS",                                                        \
      "viscous friction (reported; the controller has no term for it)", "N m s/rad", 0.0, 1000.0,  \
      0)                                                                                           \
    X(MOTOR_PARAM_SPEED_KP, "SPEED_KP_NMS", "speed PI gain, per mechanical rad/s", "N m s/rad",    \
      CTL_SPEED_KP_MIN, CTL_SPEED_KP_MAX, 0)                                                       \
    X(MOTOR_PARAM_SPEED_KI, "SPEED_KI_NM", "speed PI integral gain, per mechanical rad",           \
      "N m/rad", CTL_SPEED_KI_MIN, CTL_SPEED_KI_MAX, 0)

#define MOTOR_PARAM_ENUM(id, name, text, unit, lo, hi, integer) id,
typedef enum { MOTOR_PARAM_LIST(MOTOR_PARAM_ENUM) MOTOR_PARAM_COUNT } motor_param_t;
#undef MOTOR_PARAM_ENUM

#define MOTOR_PARAM_PREFIX "SIXPHASE_MOTOR_"

typedef struct {
    unsigned have;                       /* bit (1 << motor_param_t) per entry present */
    double value[MOTOR_PARAM_COUNT];     /* SI units; pole pairs and the offset as integers */
    double sigma[MOTOR_PARAM_COUNT];     /* 1-sigma uncertainty (writer's comments; 0: none) */
    const char *note[MOTOR_PARAM_COUNT]; /* a word for the comment (quality), or NULL */
} motor_params_t;

void motor_params_clear(motor_params_t *m);
void motor_params_set(motor_params_t *m, motor_param_t id, double value, double sigma,
                      const char *note);

/* Every entry m has within its range of MOTOR_PARAM_LIST (and whole where it is an integer);
 * 0, or -1 with one line naming the first that is not ("stator resistance R_OHM -2147.48 ohm is
 * outside 0..1000 ohm"). */
int motor_params_check(const motor_params_t *m, char *err, size_t err_len);

/* Read path into m; 0, or -1 with one line in err (the file and line that are refused). A NUL
 * byte anywhere is refused. */
int motor_params_read(const char *path, motor_params_t *m, char *err, size_t err_len);

/* Write m as the header, a comment line with its origin first; 0, or -1 on a write error or
 * when motor_params_check refuses m (then nothing is written). */
int motor_params_write(FILE *f, const motor_params_t *m, const char *origin);

#endif /* MOTOR_PARAMS_FILE_H */
