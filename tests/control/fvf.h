/* Fixed-vs-float comparison: one operating point evaluated by one arithmetic build of the
 * core. Only double in the interface, so the two builds can be linked into one program
 * (the float build's symbols carry the prefix flt_, see cmake/prefix_symbols.cmake). */
#ifndef FVF_H
#define FVF_H

#include <stdint.h>

typedef struct {
    int16_t controller;    /* ctl_controller_t */
    double lambda;         /* N*m/Wb */
    double id, iq, ix, iy; /* A, at sample k */
    double theta;          /* electrical angle, turns */
    double omega;          /* electrical rad/s */
    double vdc;            /* V */
    int16_t vector_in_force;
    double duty_in_force;
    double torque_ref; /* N*m */
} fvf_point_t;

typedef struct {
    int16_t vector;
    double duty;
    double flux_ref;    /* Wb, as the build computed it */
    double leg_duty[6]; /* the command's leg duties (FOC-VSD's whole command) */
} fvf_result_t;

void fvf_evaluate(const fvf_point_t *p, fvf_result_t *r);
void flt_fvf_evaluate(const fvf_point_t *p, fvf_result_t *r);

#endif /* FVF_H */
