/*
 * hal_encoder on the F28335: eQEP1 in quadrature mode.
 *
 *   position   QPOSCNT counts 0 .. 4 lines - 1 (QPOSMAX), reset by the index
 *              (PCRM = 0), so after the first index it is the angle from the
 *              index; QPOSILAT latches the count at each rising index edge
 *   angle      theta_e = pos * Pn / (4 lines) turns (Q48 factor, no division
 *              per sample) + elec_offset, 2^32 = one electrical turn
 *   speed      high speed: position difference over the unit timer
 *              (QUPRD = SYSCLK / 500 Hz, QCLM = 1 latches QPOSLAT, QCPRDLAT,
 *              QCTMRLAT together); low speed: capture timer period of
 *              2^UPPS = 16 counts at SYSCLK / 64; switched with hysteresis
 *              at 12 / 15 rev/s; capture overflow (slower than about
 *              0.06 rev/s) reads as standstill
 *   health     first index seen (QEPSTS.FIMF) and no position-counter error,
 *              quadrature phase error or loss of edges above 5 rev/s (QEP
 *              watchdog, 10 ms) since init
 *   re-homing  hal_encoder_rehome clears FIMF (write 1 to clear): unhealthy
 *              until the next index sets it again and resets the count
 *   position   unwrapped counts since init (commissioning): the change of QPOSCNT
 *              between reads, taken modulo the turn; at the first index the counter
 *              was reset (to 0 counting up, to QPOSMAX counting down, QEPSTS.FIDF),
 *              so that read adds the motion up to the count latched at the index
 *              (QPOSILAT) and from the reset value on (within a count of the edge);
 *              the index after a re-homing is taken the same way (FIMF set again;
 *              that FIDF is latched again then is UNCONFIRMED on the silicon)
 */
#include "f28335_hal.h"
#include "f28335_internal.h"
#include "hal_encoder.h"
#include "sixphase_placement.h"

static f28335_qep_state_t qep;

const f28335_qep_state_t *f28335_qep_state(void) { return &qep; }

/* (pos * (2^16 hi + lo)) >> 16 mod 2^32, exactly, in 32-bit products: with pos = 2^16 p_hi +
 * p_lo, it is pos hi + p_hi lo + ((p_lo lo) >> 16), the angle wrapping at one turn. */
SIXPHASE_RAMFUNC uint32_t f28335_qep_angle(const f28335_qep_state_t *q, uint32_t pos)
{
    const uint32_t p_hi = pos >> 16, p_lo = pos & 0xFFFFu;
    return pos * q->angle_hi + p_hi * q->angle_lo + ((p_lo * q->angle_lo) >> 16) + q->elec_offset;
}

/* delta (2^16 hi + lo) / 2^16 truncated toward zero, as the 64-bit quotient was, on the
 * magnitude m = 2^16 m_hi + m_lo: m hi + m_hi lo + ((m_lo lo) >> 16), every product within 32
 * bits while m <= ut_max_delta; the sign put back after. */
SIXPHASE_RAMFUNC int32_t f28335_qep_speed_unit(const f28335_qep_state_t *q, int32_t delta_counts)
{
    const uint32_t m =
        (delta_counts < 0) ? (uint32_t)0u - (uint32_t)delta_counts : (uint32_t)delta_counts;
    uint32_t v;
    if (m > q->ut_max_delta) {
        return (delta_counts < 0) ? -INT32_MAX : INT32_MAX;
    }
    v = m * q->ut_hi + (m >> 16) * q->ut_lo + (((m & 0xFFFFu) * q->ut_lo) >> 16);
    return (delta_counts < 0) ? -(int32_t)v : (int32_t)v;
}

SIXPHASE_RAMFUNC int32_t f28335_qep_speed_capture(const f28335_qep_state_t *q, uint16_t period)
{
    uint32_t v;
    if (period == 0u) {
        return 0;
    }
    v = q->cap_k / period;
    if (v > ((uint32_t)INT32_MAX >> q->cap_shift)) {
        return INT32_MAX;
    }
    return (int32_t)(v << q->cap_shift);
}

/* The speed and angle constants of an encoder (background: 64-bit arithmetic allowed). */
static void qep_constants(f28335_qep_state_t *q, uint16_t pole_pairs)
{
    const uint64_t angle_q48 = (((uint64_t)pole_pairs << 48) + q->counts / 2u) / q->counts;
    /* unit timer: rev/s = delta * f_unit / counts; in Q16 with a Q16 factor */
    const uint64_t ut_k = (((uint64_t)F28335_QEP_UNIT_HZ << 32) + q->counts / 2u) / q->counts;
    /* capture: rev/s = 2^UPPS / counts / (period * 2^CCPS / SYSCLK) */
    uint64_t cap_k =
        (((uint64_t)F28335_SYSCLK_HZ << (16u + F28335_QEP_UPPS)) >> F28335_QEP_CCPS) / q->counts;
    q->angle_hi = (uint32_t)(angle_q48 >> 16);
    q->angle_lo = (uint32_t)(angle_q48 & 0xFFFFu);
    q->ut_hi = (uint32_t)(ut_k >> 16);
    q->ut_lo = (uint32_t)(ut_k & 0xFFFFu);
    /* the largest |delta| whose speed, |delta| ut_k / 2^16, is at most INT32_MAX */
    const uint64_t max_delta = (((uint64_t)INT32_MAX << 16) + 0xFFFFu) / ut_k;
    q->ut_max_delta = (max_delta > 0x80000000u) ? 0x80000000u : (uint32_t)max_delta;
    q->cap_shift = 0u;
    while (cap_k > UINT32_MAX) {
        cap_k >>= 1;
        q->cap_shift++;
    }
    q->cap_k = (uint32_t)cap_k;
}

SIXPHASE_RAMFUNC static int32_t abs32(int32_t x) { return (x < 0) ? -x : x; }

bool hal_encoder_init(uint32_t lines, uint16_t pole_pairs, uint32_t elec_offset)
{
    volatile f28335_eqep_t *e = F28335_EQEP1;
    uint16_t pin;

    if (lines == 0u || lines > 0x10000000uL || pole_pairs == 0u) {
        return false;
    }
    qep.counts = 4u * lines;
    qep.elec_offset = elec_offset;
    qep_constants(&qep, pole_pairs);
    qep.last_poslat = 0u;
    qep.have_poslat = false;
    qep.use_capture = true;
    qep.error_latched = false;
    qep.speed_q16 = 0;
    qep.edge_speed_q16 = 0;
    qep.last_pos = 0u;
    qep.position = 0;
    qep.index_seen = false;

    F28335_EALLOW();
    F28335_SYSCTRL->PCLKCR1 |= PCLKCR1_EQEP1ENCLK;
    F28335_EDIS();
    for (pin = F28335_QEP_A_GPIO; pin < F28335_QEP_A_GPIO + 4u; pin++) {
        f28335_gpio_set_pullup(pin, true);
        f28335_gpio_set_qsel(pin, F28335_GPIO_QSEL_SYNC);
        f28335_gpio_set_mux(pin, F28335_GPIO_MUX_PERIPH1);
    }

    e->QEPCTL = 0u; /* stop while configuring */
    e->QDECCTL = EQEP_QDECCTL_QSRC_QUAD;
    e->QPOSINIT = 0u;
    e->QPOSMAX = qep.counts - 1u;
    e->QPOSCNT = 0u;
    e->QUPRD = F28335_SYSCLK_HZ / F28335_QEP_UNIT_HZ;
    e->QWDPRD = F28335_QEP_WATCHDOG_PRD;
    e->QCAPCTL = 0u; /* prescalers change only with the capture unit off */
    e->QCAPCTL = (uint16_t)((F28335_QEP_CCPS << EQEP_QCAPCTL_CCPS_SHIFT) |
                            (F28335_QEP_UPPS << EQEP_QCAPCTL_UPPS_SHIFT));
    e->QCAPCTL = (uint16_t)(e->QCAPCTL | EQEP_QCAPCTL_CEN);
    e->QEINT = 0u; /* polled from the control ISR */
    e->QCLR = 0x0FFFu;
    e->QEPSTS = (uint16_t)(EQEP_STS_FIMF | EQEP_STS_CDEF | EQEP_STS_COEF | EQEP_STS_UPEVNT);
    e->QEPCTL =
        (uint16_t)(EQEP_QEPCTL_FREE_SOFT_FREE | EQEP_QEPCTL_PCRM_INDEX | EQEP_QEPCTL_IEL_RISING |
                   EQEP_QEPCTL_QPEN | EQEP_QEPCTL_QCLM | EQEP_QEPCTL_UTE | EQEP_QEPCTL_WDE);
    return true;
}

SIXPHASE_RAMFUNC static void qep_unit_period(volatile f28335_eqep_t *e, uint16_t sts)
{
    const uint32_t poslat = e->QPOSLAT;
    const uint16_t cprd = e->QCPRDLAT;
    const uint16_t ctmr = e->QCTMRLAT;
    int32_t ut_speed = qep.speed_q16;
    int32_t cap_speed;
    bool cap_valid = true;
    bool moved = false;

    if (qep.have_poslat) {
        int32_t delta = (int32_t)(poslat - qep.last_poslat);
        const int32_t half = (int32_t)(qep.counts / 2u);
        if (delta >= half) {
            delta -= (int32_t)qep.counts;
        } else if (delta < -half) {
            delta += (int32_t)qep.counts;
        }
        ut_speed = f28335_qep_speed_unit(&qep, delta);
        moved = (delta != 0);
    }
    qep.last_poslat = poslat;
    qep.have_poslat = true;

    if ((sts & EQEP_STS_COEF) != 0u) {
        cap_speed = 0; /* capture timer overflowed: slower than the minimum */
    } else if ((sts & EQEP_STS_CDEF) != 0u || cprd == 0u) {
        cap_valid = false; /* direction changed within a capture period */
        cap_speed = ut_speed;
    } else {
        /* The period still running bounds the speed from above (deceleration). */
        cap_speed = f28335_qep_speed_capture(&qep, (ctmr > cprd) ? ctmr : cprd);
        if ((sts & EQEP_STS_QDF) == 0u) {
            cap_speed = -cap_speed;
        }
    }
    if ((sts & (EQEP_STS_COEF | EQEP_STS_CDEF)) != 0u) {
        e->QEPSTS = (uint16_t)(sts & (EQEP_STS_COEF | EQEP_STS_CDEF)); /* write 1 to clear */
    }

    if (qep.use_capture && abs32(ut_speed) > F28335_QEP_HIGH_SPEED_Q16) {
        qep.use_capture = false;
    } else if (!qep.use_capture && abs32(ut_speed) < F28335_QEP_LOW_SPEED_Q16) {
        qep.use_capture = true;
    }
    qep.speed_q16 = (qep.use_capture && cap_valid) ? cap_speed : ut_speed;
    if (moved) {
        qep.edge_speed_q16 = qep.speed_q16;
    }
}

/* now - before in counts, taken into -counts/2 .. counts/2 (both below counts). */
SIXPHASE_RAMFUNC static int32_t qep_count_step(uint32_t now, uint32_t before)
{
    const int32_t half = (int32_t)(qep.counts / 2u);
    int32_t d = (int32_t)now - (int32_t)before;
    if (d >= half) {
        d -= (int32_t)qep.counts;
    } else if (d < -half) {
        d += (int32_t)qep.counts;
    }
    return d;
}

/* The unwrapped position: the counter's change since the last read, across the first index's
 * reset. The sum wraps at 2^32 like the counter it extends (unsigned: no overflow). */
SIXPHASE_RAMFUNC static void qep_track_position(volatile f28335_eqep_t *e, uint32_t pos,
                                                uint16_t sts)
{
    const bool seen = (sts & EQEP_STS_FIMF) != 0u;
    int32_t step;
    if (seen && !qep.index_seen) {
        const uint32_t reset = ((sts & EQEP_STS_FIDF) != 0u) ? 0u : qep.counts - 1u;
        step = qep_count_step(e->QPOSILAT, qep.last_pos) + qep_count_step(pos, reset);
    } else {
        step = qep_count_step(pos, qep.last_pos);
    }
    qep.position = (int32_t)((uint32_t)qep.position + (uint32_t)step);
    qep.last_pos = pos;
    qep.index_seen = seen;
}

uint32_t hal_encoder_counts_per_turn(void) { return qep.counts; }

uint32_t hal_encoder_offset(void) { return qep.elec_offset; }

void hal_encoder_set_offset(uint32_t elec_offset) { qep.elec_offset = elec_offset; }

SIXPHASE_RAMFUNC void hal_encoder_read(hal_encoder_sample_t *s)
{
    volatile f28335_eqep_t *e = F28335_EQEP1;
    const uint32_t pos = e->QPOSCNT;
    const uint16_t flg = e->QFLG;
    const uint16_t sts = e->QEPSTS;
    uint16_t clr = 0u;

    if ((flg & (EQEP_PCE | EQEP_PHE)) != 0u) {
        qep.error_latched = true;
        clr = (uint16_t)(flg & (EQEP_PCE | EQEP_PHE)); /* first flag to acknowledge */
    }
    if ((flg & EQEP_UTO) != 0u) {
        qep_unit_period(e, sts);
        clr = (uint16_t)(clr | EQEP_UTO);
    }
    if ((flg & EQEP_WTO) != 0u) {
        /* No edge for 10 ms: a stop from above the threshold is a lost signal. The speed
         * is the one measured while the shaft still moved: by now the unit timer has
         * already reported zero for the empty periods. */
        if (abs32(qep.edge_speed_q16) > F28335_QEP_TIMEOUT_SPEED_Q16) {
            qep.error_latched = true;
        }
        qep.speed_q16 = 0;
        qep.edge_speed_q16 = 0;
        clr = (uint16_t)(clr | EQEP_WTO);
    }
    if (clr != 0u) {
        e->QCLR = (uint16_t)(clr | EQEP_INT);
    }

    qep_track_position(e, pos, sts);
    s->elec_angle = f28335_qep_angle(&qep, pos);
    s->mech_speed_q16 = qep.speed_q16;
    s->healthy = ((sts & EQEP_STS_FIMF) != 0u) && !qep.error_latched;
    s->position = qep.position;
    s->index_seen = qep.index_seen;
}

/* FIMF is write-1-to-clear; the zeros written with it leave the other status bits alone. */
SIXPHASE_RAMFUNC void hal_encoder_rehome(void) { F28335_EQEP1->QEPSTS = EQEP_STS_FIMF; }
