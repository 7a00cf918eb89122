/* The reference VSD model (vsd_reference.h). */
#include "vsd_reference.h"

#include <math.h>

#define VSD_REF_DEG (3.14159265358979323846 / 180.0)

const double vsd_ref_phase_deg[6] = {0.0, 120.0, 240.0, 30.0, 150.0, 270.0};

vsd_d vsd_ref_forward(const double p[6])
{
    vsd_d r = {0.0, 0.0, 0.0, 0.0};
    int32_t k;
    for (k = 0; k < 6; k++) {
        const double th = vsd_ref_phase_deg[k] * VSD_REF_DEG;
        r.alpha += p[k] * cos(th) / 3.0;
        r.beta += p[k] * sin(th) / 3.0;
        r.x += p[k] * cos(5.0 * th) / 3.0;
        r.y += p[k] * sin(5.0 * th) / 3.0;
    }
    return r;
}

int32_t vsd_ref_state_leg(int32_t v, int32_t leg)
{
    const int32_t digit = (leg < 3) ? v / 8 : v % 8;
    const int32_t pos = leg % 3; /* 0 = most significant */
    if (pos == 0) {
        return digit / 4;
    }
    if (pos == 1) {
        return (digit / 2) % 2;
    }
    return digit % 2;
}

vsd_d vsd_ref_state(int32_t v)
{
    double s[6];
    double p[6];
    double m1;
    double m2;
    int32_t k;
    for (k = 0; k < 6; k++) {
        s[k] = (double)vsd_ref_state_leg(v, k);
    }
    m1 = (s[0] + s[1] + s[2]) / 3.0;
    m2 = (s[3] + s[4] + s[5]) / 3.0;
    for (k = 0; k < 6; k++) {
        p[k] = s[k] - ((k < 3) ? m1 : m2);
    }
    return vsd_ref_forward(p);
}

double vsd_ref_mag_ab(vsd_d u) { return hypot(u.alpha, u.beta); }
double vsd_ref_mag_xy(vsd_d u) { return hypot(u.x, u.y); }
