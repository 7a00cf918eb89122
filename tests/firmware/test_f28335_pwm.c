/* ePWM driver against RAM register frames, and an action-qualifier model of the module that
 * runs the duty sequences a drive produces through the registers the driver wrote. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "f28335_hal.h"
#include "hal_pwm.h"

#define R (f28335_host_regs)

static int setup(void **state)
{
    (void)state;
    f28335_host_regs_reset();
    R.gpiodata.GPADAT = (uint32_t)1u << F28335_PWM_TRIP_GPIO; /* TZ1 inactive (high) */
    return 0;
}

static void test_period_and_deadband_helpers(void **state)
{
    (void)state;
    assert_int_equal(f28335_pwm_period_for(10000u), 7500);
    assert_int_equal(f28335_pwm_period_for(20000u), 3750);
    assert_int_equal(f28335_pwm_period_for(0u), 0);
    assert_int_equal(f28335_pwm_period_for(1000u), 0); /* 75000 > 16 bits */
    assert_int_equal(f28335_pwm_deadband_for(2000u), 300);
    assert_int_equal(f28335_pwm_deadband_for(0u), 0);
    assert_int_equal(f28335_pwm_deadband_for(6820u), 1023);
    assert_int_equal(f28335_pwm_deadband_for(6830u), 0xFFFF);
}

static void test_init_time_base_and_sync(void **state)
{
    int i;
    (void)state;
    assert_true(hal_pwm_init(10000u, 2000u));
    for (i = 0; i < 6; i++) {
        const uint16_t tbctl = R.epwm[i].TBCTL;
        assert_int_equal(tbctl & EPWM_TBCTL_CTRMODE_MASK, EPWM_TBCTL_CTRMODE_UPDOWN);
        assert_int_equal(R.epwm[i].TBPRD, 7500);
        assert_int_equal(tbctl & EPWM_TBCTL_PRDLD_IMMEDIATE, 0); /* period shadowed */
        assert_int_equal(tbctl & (EPWM_TBCTL_HSPCLKDIV_MASK | EPWM_TBCTL_CLKDIV_MASK),
                         0); /* TBCLK = SYSCLKOUT */
        assert_int_equal(R.epwm[i].TBPHS, 0);
        if (i == 0) {
            assert_int_equal(tbctl & EPWM_TBCTL_PHSEN, 0);
            assert_int_equal((tbctl & EPWM_TBCTL_SYNCOSEL_MASK) >> EPWM_TBCTL_SYNCOSEL_SHIFT,
                             EPWM_SYNCOSEL_CTR_ZERO);
        } else {
            assert_int_equal(tbctl & EPWM_TBCTL_PHSEN, EPWM_TBCTL_PHSEN);
            assert_int_equal(tbctl & EPWM_TBCTL_PHSDIR_UP, EPWM_TBCTL_PHSDIR_UP);
            assert_int_equal((tbctl & EPWM_TBCTL_SYNCOSEL_MASK) >> EPWM_TBCTL_SYNCOSEL_SHIFT,
                             EPWM_SYNCOSEL_SYNCI);
        }
    }
    /* time bases started together, ePWM clocks on */
    assert_int_equal(R.sysctrl.PCLKCR0 & PCLKCR0_TBCLKSYNC, PCLKCR0_TBCLKSYNC);
    assert_int_equal(R.sysctrl.PCLKCR1 & PCLKCR1_EPWM_ALL, PCLKCR1_EPWM_ALL);
    assert_int_equal(f28335_pwm_period(), 7500);
}

static void test_init_compare_actions_deadband(void **state)
{
    int i;
    (void)state;
    assert_true(hal_pwm_init(10000u, 2000u));
    for (i = 0; i < 6; i++) {
        /* CMPA shadowed, loaded at CTR = 0 */
        assert_int_equal(
            R.epwm[i].CMPCTL & (EPWM_CMPCTL_SHDWAMODE_IMMEDIATE | EPWM_CMPCTL_LOADAMODE_MASK), 0);
        /* A: clear on ZRO, set on CAU, clear on CAD, clear on CBU (CMPB = 1) */
        assert_int_equal(R.epwm[i].AQCTLA, (1u << 0) | (2u << 4) | (1u << 6) | (1u << 8));
        assert_int_equal(R.epwm[i].CMPB, 1u);
        /* continuous software force loaded at CTR = 0 with the compares, none at start */
        assert_int_equal(R.epwm[i].AQSFRC & 0x00C0u, 0u);
        assert_int_equal(R.epwm[i].AQCSFRC, 0u);
        assert_int_equal(R.epwm[i].AQCTLB, 0);
        /* dead band: full, active high complementary, A as source */
        assert_int_equal(R.epwm[i].DBCTL & 0x3u, 3u);
        assert_int_equal((R.epwm[i].DBCTL >> 2) & 0x3u, 2u);
        assert_int_equal((R.epwm[i].DBCTL >> 4) & 0x3u, 0u);
        assert_int_equal(R.epwm[i].DBRED, 300);
        assert_int_equal(R.epwm[i].DBFED, 300);
        /* starts at duty 0 */
        assert_int_equal(R.epwm[i].CMPA, 7501);
    }
    /* SOCA of ePWM1 at CTR = 0, every period; others no SOC */
    assert_int_equal((R.epwm[0].ETSEL >> 8) & 0x7u, 1u);
    assert_int_equal(R.epwm[0].ETSEL & EPWM_ETSEL_SOCAEN, EPWM_ETSEL_SOCAEN);
    assert_int_equal((R.epwm[0].ETPS >> 8) & 0x3u, 1u);
    for (i = 1; i < 6; i++) {
        assert_int_equal(R.epwm[i].ETSEL & EPWM_ETSEL_SOCAEN, 0);
    }
}

static void test_init_trip_zone_and_pins(void **state)
{
    int i;
    (void)state;
    assert_true(hal_pwm_init(10000u, 2000u));
    for (i = 0; i < 6; i++) {
        assert_int_equal(R.epwm[i].TZSEL, 0x0100u);                   /* OSHT1 only */
        assert_int_equal(R.epwm[i].TZCTL & 0x3u, 2u);                 /* TZA low */
        assert_int_equal((R.epwm[i].TZCTL >> 2) & 0x3u, 2u);          /* TZB low */
        assert_int_equal(R.epwm[i].TZFRC & EPWM_TZ_OST, EPWM_TZ_OST); /* left forced off */
    }
    /* GPIO0..11 on mux 1 (ePWM), GPIO12 mux 1 (TZ1) asynchronous with pull-up */
    assert_int_equal(R.gpioctrl.GPAMUX1 & 0x03FFFFFFu, 0x01555555u);
    assert_int_equal((R.gpioctrl.GPAQSEL1 >> 24) & 3u, 3u);
    assert_int_equal(R.gpioctrl.GPAPUD & 0xFFFu, 0xFFFu);
    assert_int_equal(R.gpioctrl.GPAPUD & (1u << 12), 0u);
    assert_true(f28335_host_core.eallow_count > 0u);
    assert_int_equal(f28335_host_core.eallow, 0); /* every EALLOW closed */
}

static void test_init_rejects_bad_arguments(void **state)
{
    (void)state;
    assert_false(hal_pwm_init(0u, 2000u));
    assert_false(hal_pwm_init(10000u, 10000u)); /* 1500 counts > 10 bits */
    assert_false(hal_pwm_init(100u, 2000u));
}

static void test_cmpa_for_duties(void **state)
{
    (void)state;
    /* 0 % and 100 %: no compare event; 100 % is the continuous force */
    assert_int_equal(f28335_pwm_cmpa_for(0u, 7500u), 7501);
    assert_int_equal(f28335_pwm_force_for(0u, 7500u), 0u);
    assert_int_equal(f28335_pwm_cmpa_for(32768u, 7500u), 7501);
    assert_int_equal(f28335_pwm_force_for(32768u, 7500u), EPWM_AQCSFRC_CSFA_HIGH);
    assert_int_equal(f28335_pwm_cmpa_for(40000u, 7500u), 7501); /* above full: full */
    assert_int_equal(f28335_pwm_force_for(40000u, 7500u), EPWM_AQCSFRC_CSFA_HIGH);
    assert_int_equal(f28335_pwm_cmpa_for(16384u, 7500u), 3750); /* 50 % */
    assert_int_equal(f28335_pwm_cmpa_for(8192u, 7500u), 5625);  /* 25 %: high 2*(7500-5625)/15000 */
    assert_int_equal(f28335_pwm_cmpa_for(24576u, 7500u), 1875); /* 75 % */
    assert_int_equal(f28335_pwm_force_for(24576u, 7500u), 0u);
    assert_int_equal(f28335_pwm_cmpa_for(1u, 7500u), 7501);     /* rounds to 0 counts: 0 % */
    assert_int_equal(f28335_pwm_cmpa_for(3u, 7500u), 7499);     /* smallest pulse: 2 counts */
    assert_int_equal(f28335_pwm_cmpa_for(32767u, 7500u), 7501); /* rounds to full */
    assert_int_equal(f28335_pwm_force_for(32767u, 7500u), EPWM_AQCSFRC_CSFA_HIGH);
    /* largest below full (7499 counts): CMPA kept one count above CMPB's clear at 1 */
    assert_int_equal(f28335_pwm_cmpa_for(32763u, 7500u), F28335_PWM_CMPA_MIN);
    assert_int_equal(f28335_pwm_force_for(32763u, 7500u), 0u);
}

static void test_write_duty_is_centred_pulse(void **state)
{
    /* high time = 2 (TBPRD - CMPA) of a 2 TBPRD period: duty d gives d. */
    const uint16_t duty[6] = {0u, 32768u, 16384u, 8192u, 24576u, 3277u};
    int i;
    (void)state;
    assert_true(hal_pwm_init(10000u, 2000u));
    hal_pwm_write(duty);
    assert_int_equal(R.epwm[0].CMPA, 7501);
    assert_int_equal(R.epwm[0].AQCSFRC, 0u);
    assert_int_equal(R.epwm[1].CMPA, 7501);
    assert_int_equal(R.epwm[1].AQCSFRC, EPWM_AQCSFRC_CSFA_HIGH);
    assert_int_equal(R.epwm[2].CMPA, 3750);
    assert_int_equal(R.epwm[3].CMPA, 5625);
    assert_int_equal(R.epwm[4].CMPA, 1875);
    assert_int_equal(R.epwm[5].CMPA, 7500 - 750);
    for (i = 2; i < 6; i++) {
        const uint32_t high = 2u * (7500u - R.epwm[i].CMPA);
        const uint32_t want = (uint32_t)duty[i] * 15000u / 32768u;
        assert_true(high + 2u >= want && high <= want + 2u);
    }
}

static void test_force_off_enable_and_trips(void **state)
{
    int i;
    (void)state;
    assert_true(hal_pwm_init(10000u, 2000u));
    for (i = 0; i < 6; i++) {
        R.epwm[i].TZFRC = 0u;
        R.epwm[i].TZFLG = EPWM_TZ_OST; /* hardware latched the forced trip */
    }
    assert_true(hal_pwm_is_off());
    assert_false(hal_pwm_hw_trip_seen()); /* software caused it */

    hal_pwm_enable();
    for (i = 0; i < 6; i++) {
        assert_int_equal(R.epwm[i].TZCLR & EPWM_TZ_OST, EPWM_TZ_OST);
        R.epwm[i].TZFLG = 0u; /* hardware cleared the latch */
        R.epwm[i].TZCLR = 0u;
    }
    assert_false(hal_pwm_is_off());

    hal_pwm_force_off();
    for (i = 0; i < 6; i++) { /* all six legs tripped at once */
        assert_int_equal(R.epwm[i].TZFRC & EPWM_TZ_OST, EPWM_TZ_OST);
    }

    /* hardware trip while running: latch not caused by software */
    hal_pwm_enable();
    R.epwm[3].TZFLG = EPWM_TZ_OST;
    assert_true(hal_pwm_is_off());
    assert_true(hal_pwm_hw_trip_seen());
    /* comparator still asserting TZ1 (active low) */
    hal_pwm_force_off();
    R.gpiodata.GPADAT = 0u;
    assert_true(hal_pwm_hw_trip_seen());
    R.gpiodata.GPADAT = (uint32_t)1u << F28335_PWM_TRIP_GPIO;
    assert_false(hal_pwm_hw_trip_seen());
}

/* An isolated leg: its module alone one-shot tripped, left tripped by enable, its compare at 0 %;
 * is_off and the hardware-trip judgement look at the other legs; restore gives it back. */
static void test_isolated_leg(void **state)
{
    const uint16_t duty[6] = {16384u, 16384u, 32768u, 16384u, 16384u, 16384u};
    int i;
    (void)state;
    assert_true(hal_pwm_init(10000u, 2000u));
    hal_pwm_enable();
    for (i = 0; i < 6; i++) {
        R.epwm[i].TZFRC = 0u;
        R.epwm[i].TZCLR = 0u;
        R.epwm[i].TZFLG = 0u;
    }
    assert_false(hal_pwm_isolate_leg(-1));
    assert_false(hal_pwm_isolate_leg(6));
    assert_int_equal(hal_pwm_isolated_legs(), 0u);
    f28335_host_eallow_watch_start();
    assert_true(hal_pwm_isolate_leg(2));
    assert_int_equal(f28335_host_eallow_violations(), 0u);
    assert_int_equal(hal_pwm_isolated_legs(), 1u << 2);
    for (i = 0; i < 6; i++) { /* ePWM3 alone */
        assert_int_equal(R.epwm[i].TZFRC & EPWM_TZ_OST, (i == 2) ? EPWM_TZ_OST : 0u);
    }
    R.epwm[2].TZFLG = EPWM_TZ_OST;
    assert_false(hal_pwm_is_off());       /* the others run */
    assert_false(hal_pwm_hw_trip_seen()); /* software isolated it */
    hal_pwm_write(duty);
    assert_int_equal(R.epwm[2].CMPA, 7501); /* 0 % */
    assert_int_equal(R.epwm[2].AQCSFRC, 0u);
    assert_int_equal(R.epwm[1].CMPA, 3750);
    /* a force-off and enable cycle (stop, run) leaves the leg tripped */
    hal_pwm_force_off();
    hal_pwm_enable();
    for (i = 0; i < 6; i++) {
        assert_int_equal(R.epwm[i].TZCLR & EPWM_TZ_OST, (i == 2) ? 0u : EPWM_TZ_OST);
    }
    hal_pwm_restore_legs();
    assert_int_equal(hal_pwm_isolated_legs(), 0u);
    assert_true(hal_pwm_is_off()); /* its latch stands until the next enable */
    hal_pwm_enable();
    assert_int_equal(R.epwm[2].TZCLR & EPWM_TZ_OST, EPWM_TZ_OST);
    /* a new init forgets the isolation */
    assert_true(hal_pwm_isolate_leg(4));
    assert_true(hal_pwm_init(10000u, 2000u));
    assert_int_equal(hal_pwm_isolated_legs(), 0u);
}

/* ---- Action-qualifier model of one module (up-down count, EPWMxA before the dead band) ----
 * Counts 0, 1, .., TBPRD, TBPRD - 1, .., 1 make one period of 2 TBPRD counts; the output of a
 * count is the level after that count's events. Shadowed CMPA, CMPB and AQCSFRC load at
 * CTR = 0; TI does not say whether that count's events see the old or the new software force,
 * so both orders are run. Simultaneous events: the highest priority wins (TI's ePWM guides:
 * software force; counting up CBU, CAU, ZRO, CBD, CAD; counting down CBD, CAD, PRD, CBU, CAU).
 * A compare value with an action that matches at CTR = 0 or TBPRD (where the direction turns)
 * is a boundary case the driver must never produce: the model counts it. */
typedef struct {
    uint16_t prd, aqctla;
    uint16_t cmpa, cmpb, csf;          /* active */
    uint16_t cmpa_sh, cmpb_sh, csf_sh; /* shadow */
    bool out;
    bool load_before_events;
    int boundary_matches;
} aq_model_t;

static uint16_t aq_action(const aq_model_t *m, uint16_t shift) { return (m->aqctla >> shift) & 3u; }

/* The action of this count's highest-priority configured event (0 none, 1 clear, 2 set). */
static uint16_t aq_event_action(aq_model_t *m, uint16_t ctr, bool up)
{
    const bool ca = (ctr == m->cmpa), cb = (ctr == m->cmpb);
    const bool zro = (ctr == 0u), prd = (ctr == m->prd);
    const struct {
        bool hit;
        uint16_t shift;
    } up_order[5] = {{cb, EPWM_AQ_CBU_SHIFT},
                     {ca, EPWM_AQ_CAU_SHIFT},
                     {zro, EPWM_AQ_ZRO_SHIFT},
                     {false, EPWM_AQ_CBD_SHIFT},
                     {false, EPWM_AQ_CAD_SHIFT}};
    const struct {
        bool hit;
        uint16_t shift;
    } down_order[5] = {{cb, EPWM_AQ_CBD_SHIFT},
                       {ca, EPWM_AQ_CAD_SHIFT},
                       {prd, EPWM_AQ_PRD_SHIFT},
                       {false, EPWM_AQ_CBU_SHIFT},
                       {false, EPWM_AQ_CAU_SHIFT}};
    const bool ca_acts = (aq_action(m, EPWM_AQ_CAU_SHIFT) | aq_action(m, EPWM_AQ_CAD_SHIFT)) != 0u;
    const bool cb_acts = (aq_action(m, EPWM_AQ_CBU_SHIFT) | aq_action(m, EPWM_AQ_CBD_SHIFT)) != 0u;
    int k;
    if (((ca && ca_acts) || (cb && cb_acts)) && (zro || prd)) {
        m->boundary_matches++;
    }
    for (k = 0; k < 5; k++) {
        const bool hit = up ? up_order[k].hit : down_order[k].hit;
        const uint16_t act = aq_action(m, up ? up_order[k].shift : down_order[k].shift);
        if (hit && act != 0u) {
            return act;
        }
    }
    return 0u;
}

static void aq_count(aq_model_t *m, uint16_t ctr, bool up)
{
    const uint16_t act = aq_event_action(m, ctr, up);
    if ((m->csf & EPWM_AQCSFRC_CSFA_MASK) == EPWM_AQCSFRC_CSFA_HIGH) {
        m->out = true;
    } else if ((m->csf & EPWM_AQCSFRC_CSFA_MASK) == EPWM_AQCSFRC_CSFA_LOW) {
        m->out = false;
    } else if (act == EPWM_AQ_SET) {
        m->out = true;
    } else if (act == EPWM_AQ_CLEAR) {
        m->out = false;
    }
}

static void aq_load(aq_model_t *m)
{
    m->cmpa = m->cmpa_sh;
    m->cmpb = m->cmpb_sh;
    m->csf = m->csf_sh;
}

/* Count `pos` of a period (0 .. 2 TBPRD - 1) with its shadow load at CTR = 0; the level after. */
static bool aq_step(aq_model_t *m, int pos)
{
    const bool up = pos < m->prd;
    const uint16_t ctr = (uint16_t)(up ? pos : 2 * m->prd - pos);
    if (ctr == 0u && m->load_before_events) {
        aq_load(m);
    }
    aq_count(m, ctr, up); /* at CTR = TBPRD the direction is down (TI) */
    if (ctr == 0u && !m->load_before_events) {
        aq_load(m);
    }
    return m->out;
}

/* One period: the level at count 0 (*high_at_zero) and the counts high after it, with the
 * first and last of those (positions 1 .. 2 prd - 1; -1 when never high). */
static int aq_period(aq_model_t *m, bool *high_at_zero, int *first, int *last)
{
    int pos, high = 0;
    *first = *last = -1;
    for (pos = 0; pos < 2 * m->prd; pos++) {
        aq_step(m, pos);
        if (pos == 0) {
            *high_at_zero = m->out;
        } else if (m->out) {
            high++;
            *first = (*first < 0) ? pos : *first;
            *last = pos;
        }
    }
    return high;
}

/* The module after hal_pwm_init, its registers as the driver left them. */
static void aq_from_registers(aq_model_t *m, int leg, bool load_before_events)
{
    memset(m, 0, sizeof *m);
    m->prd = R.epwm[leg].TBPRD;
    m->aqctla = R.epwm[leg].AQCTLA;
    m->load_before_events = load_before_events;
    m->cmpa_sh = R.epwm[leg].CMPA;
    m->cmpb_sh = R.epwm[leg].CMPB;
    m->csf_sh = R.epwm[leg].AQCSFRC;
    aq_load(m);
}

/* Writes duty to leg 0 through the driver, then runs the period that follows. 100 %: high
 * from count 1 on. Otherwise a pulse of 2 on counts (on limited to TBPRD -
 * F28335_PWM_CMPA_MIN) centred on CTR = TBPRD. Count 0 is where a force begins or ends: it
 * follows the previous period's force or this one's, depending on the load order (one count,
 * 6.7 ns, either way; f28335_pwm.c). */
static void aq_expect_period(aq_model_t *m, uint16_t duty_q15)
{
    uint16_t duty[6] = {0u, 0u, 0u, 0u, 0u, 0u};
    const uint32_t on = ((uint32_t)duty_q15 * m->prd + 16384u) >> 15;
    const bool full = on >= m->prd;
    const bool after_full = (m->csf & EPWM_AQCSFRC_CSFA_MASK) == EPWM_AQCSFRC_CSFA_HIGH;
    const uint32_t on_eff = (on > m->prd - F28335_PWM_CMPA_MIN) ? m->prd - F28335_PWM_CMPA_MIN : on;
    bool at_zero = false;
    int first, last, high;
    duty[0] = duty_q15;
    hal_pwm_write(duty);
    m->cmpa_sh = R.epwm[0].CMPA;
    m->cmpb_sh = R.epwm[0].CMPB;
    m->csf_sh = R.epwm[0].AQCSFRC;
    high = aq_period(m, &at_zero, &first, &last);
    /* count 0 follows the force of the period the load order makes it belong to */
    assert_true(at_zero == (m->load_before_events ? full : after_full));
    if (full) {
        assert_int_equal(high, 2 * m->prd - 1);
    } else {
        if ((uint32_t)high != 2u * on_eff) {
            print_error("duty %u: %d counts high, want %u\n", duty_q15, high,
                        (unsigned)(2u * on_eff));
            fail();
        }
        if (high > 0) { /* centred on the peak */
            assert_int_equal(m->prd - first, last - m->prd + 1);
        }
    }
    assert_int_equal(m->boundary_matches, 0);
}

static void aq_run_sequence(const uint16_t *duties, int n)
{
    int order;
    for (order = 0; order < 2; order++) {
        aq_model_t m;
        int k;
        f28335_host_regs_reset();
        R.gpiodata.GPADAT = (uint32_t)1u << F28335_PWM_TRIP_GPIO;
        assert_true(hal_pwm_init(10000u, 2000u));
        aq_from_registers(&m, 0, order == 0);
        for (k = 0; k < n; k++) {
            aq_expect_period(&m, duties[k]);
        }
    }
}

/* 0 % after 100 % must clear the upper switch in the next period (before the fix the output
 * stayed high: no event cleared it), and 100 % after 0 % must set it for the whole period. */
static void test_aq_full_and_zero_sequences(void **state)
{
    static const uint16_t full_zero_full[] = {32768u, 0u, 32768u, 0u, 0u, 32768u, 32768u, 0u};
    static const uint16_t zero_full_zero[] = {0u, 32768u, 0u, 32768u, 32768u, 0u};
    static const uint16_t full_mid_zero[] = {32768u, 16384u, 0u, 32768u, 8192u, 32768u, 0u};
    (void)state;
    aq_run_sequence(full_zero_full, 8);
    aq_run_sequence(zero_full_zero, 6);
    aq_run_sequence(full_mid_zero, 7);
}

/* The smallest and largest pulses, and each of them beside the extremes. */
static void test_aq_smallest_and_largest_duties(void **state)
{
    static const uint16_t edges[] = {3u,     0u, 3u, 32768u, 3u,     32763u, 32768u,
                                     32763u, 0u, 1u, 32767u, 32766u, 5u,     32760u};
    (void)state;
    aq_run_sequence(edges, 14);
}

/* Every duty level the core can command, one after the other and after each extreme. */
static void test_aq_duty_sweep(void **state)
{
    uint16_t duties[3 * 64];
    int k;
    (void)state;
    for (k = 0; k < 64; k++) {
        duties[3 * k] = (uint16_t)((uint16_t)k * 520u + 1u);
        duties[3 * k + 1] = (k & 1) ? 32768u : 0u;
        duties[3 * k + 2] = (uint16_t)(32768u - (uint16_t)k * 511u);
    }
    aq_run_sequence(duties, 3 * 64);
}

/* Every protected register the drivers write is written between EALLOW and EDIS (HRCNFG once
 * was not): the host watch counts protected-register changes made outside. */
static void test_no_protected_write_outside_eallow(void **state)
{
    const uint16_t duty[6] = {0u, 32768u, 16384u, 3u, 32763u, 100u};
    int i;
    (void)state;
    /* what a previous configuration left: the writes must change something to be seen */
    for (i = 0; i < 6; i++) {
        R.epwm[i].HRCNFG = 0x00A5u;
        R.epwm[i].TZSEL = 0x5A5Au;
        R.epwm[i].TZCTL = 0x000Fu;
        R.epwm[i].TZEINT = 0x0006u;
    }
    f28335_host_eallow_watch_start();
    assert_true(hal_pwm_init(10000u, 2000u));
    hal_pwm_write(duty);
    hal_pwm_enable();
    hal_pwm_force_off();
    assert_int_equal(f28335_host_eallow_violations(), 0u);
    /* the watch sees a write outside */
    R.epwm[2].HRCNFG = 1u;
    assert_int_equal(f28335_host_eallow_violations(), 1u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_period_and_deadband_helpers, setup),
        cmocka_unit_test_setup(test_init_time_base_and_sync, setup),
        cmocka_unit_test_setup(test_init_compare_actions_deadband, setup),
        cmocka_unit_test_setup(test_init_trip_zone_and_pins, setup),
        cmocka_unit_test_setup(test_init_rejects_bad_arguments, setup),
        cmocka_unit_test_setup(test_cmpa_for_duties, setup),
        cmocka_unit_test_setup(test_write_duty_is_centred_pulse, setup),
        cmocka_unit_test_setup(test_force_off_enable_and_trips, setup),
        cmocka_unit_test_setup(test_isolated_leg, setup),
        cmocka_unit_test_setup(test_aq_full_and_zero_sequences, setup),
        cmocka_unit_test_setup(test_aq_smallest_and_largest_duties, setup),
        cmocka_unit_test_setup(test_aq_duty_sweep, setup),
        cmocka_unit_test_setup(test_no_protected_write_outside_eallow, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
