/* Harmonic current regulation in the x-y plane: see ident_xy_harmonics.h. */
#include "ident_xy_harmonics.h"

#include "ctl_q.h"
#include "ctl_qmath.h"

#define XY_KH_RAD_S 60.0f  /* each harmonic current's decay rate */
#define XY_MIN_SPEED 30.0f /* rad/s electrical: below, the integrators hold */
#define XY_LIMIT_V 50.0f   /* each integrator's output magnitude */

static const float xy_order[IDENT_XY_SEQUENCES] = {5.0f, -5.0f, 7.0f, -7.0f};

void ident_xy_harmonics_reset(ident_xy_harmonics_t *h)
{
    int16_t k;
    h->on = false;
    for (k = 0; k < IDENT_XY_SEQUENCES; k++) {
        h->integ[k][0] = 0.0f;
        h->integ[k][1] = 0.0f;
    }
}

void ident_xy_harmonics_start(ident_xy_harmonics_t *h)
{
    ident_xy_harmonics_reset(h);
    h->on = true;
}

/* (c + j s) to the 5th and the 7th power. */
static void xy_powers(float c, float s, float z[IDENT_XY_SEQUENCES][2])
{
    const float c2 = c * c - s * s, s2 = 2.0f * c * s;
    const float c4 = c2 * c2 - s2 * s2, s4 = 2.0f * c2 * s2;
    const float c5 = c4 * c - s4 * s, s5 = c4 * s + s4 * c;
    z[0][0] = c5;
    z[0][1] = s5;
    z[1][0] = c5;
    z[1][1] = -s5;
    z[2][0] = c5 * c2 - s5 * s2;
    z[2][1] = c5 * s2 + s5 * c2;
    z[3][0] = z[2][0];
    z[3][1] = -z[2][1];
}

static float xy_abs(float v) { return (v < 0.0f) ? -v : v; }

/* One sequence's integrator: the error in its frame times its impedance times KH, clamped. */
static void xy_integrate(float integ[2], const float e[2], float h_w,
                         const ident_xy_harmonics_in_t *in)
{
    /* the frame sees R + kp + j (h w L - ki / (h w)) */
    const float zr = in->r + in->kp;
    const float zi = h_w * in->l_xy - in->ki_ts / (in->ts * h_w);
    const float g = XY_KH_RAD_S * in->ts;
    float mag2;
    integ[0] += g * (zr * e[0] - zi * e[1]);
    integ[1] += g * (zr * e[1] + zi * e[0]);
    mag2 = integ[0] * integ[0] + integ[1] * integ[1];
    if (mag2 > XY_LIMIT_V * XY_LIMIT_V) {
        const float k = XY_LIMIT_V / ctl_sqrtf(mag2);
        integ[0] *= k;
        integ[1] *= k;
    }
}

void ident_xy_harmonics_step(ident_xy_harmonics_t *h, const ident_xy_harmonics_in_t *in,
                             const float err_xy[2], float u_xy[2])
{
    float zm[IDENT_XY_SEQUENCES][2], zo[IDENT_XY_SEQUENCES][2];
    const bool run = xy_abs(in->w_e) >= XY_MIN_SPEED;
    int16_t k;
    u_xy[0] = 0.0f;
    u_xy[1] = 0.0f;
    if (!h->on) {
        return;
    }
    xy_powers(in->c_meas, in->s_meas, zm);
    xy_powers(in->c_out, in->s_out, zo);
    for (k = 0; k < IDENT_XY_SEQUENCES; k++) {
        float *const integ = h->integ[k];
        if (run) {
            /* the error into the frame: times the conjugate of its rotation */
            const float e[2] = {err_xy[0] * zm[k][0] + err_xy[1] * zm[k][1],
                                err_xy[1] * zm[k][0] - err_xy[0] * zm[k][1]};
            xy_integrate(integ, e, xy_order[k] * in->w_e, in);
        }
        u_xy[0] += integ[0] * zo[k][0] - integ[1] * zo[k][1];
        u_xy[1] += integ[0] * zo[k][1] + integ[1] * zo[k][0];
    }
}
