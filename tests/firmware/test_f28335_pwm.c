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
        /* A: clear on ZRO, set on CAU, clear on CAD; no CMPB action */
        assert_int_equal(R.epwm[i].AQCTLA, (1u << 0) | (2u << 4) | (1u << 6));
        /* no continuous software force (it would hold a leg high through a debugger halt) */
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
    /* 0 %: no compare event; 100 %: the widest compare pulse (CMPA = 1, low at CTR = 0) */
    assert_int_equal(f28335_pwm_cmpa_for(0u, 7500u), 7501);
    assert_int_equal(f28335_pwm_cmpa_for(32768u, 7500u), 1);
    assert_int_equal(f28335_pwm_cmpa_for(40000u, 7500u), 1);    /* above full: full */
    assert_int_equal(f28335_pwm_cmpa_for(16384u, 7500u), 3750); /* 50 % */
    assert_int_equal(f28335_pwm_cmpa_for(8192u, 7500u), 5625);  /* 25 %: high 2*(7500-5625)/15000 */
    assert_int_equal(f28335_pwm_cmpa_for(24576u, 7500u), 1875); /* 75 % */
    assert_int_equal(f28335_pwm_cmpa_for(1u, 7500u), 7501);     /* rounds to 0 counts: 0 % */
    assert_int_equal(f28335_pwm_cmpa_for(3u, 7500u), 7499);     /* smallest pulse: 2 counts */
    assert_int_equal(f28335_pwm_cmpa_for(32767u, 7500u), 1);    /* rounds to full */
    /* 7499 counts, one below full, gets the same pulse as full; 7498 its own */
    assert_int_equal(f28335_pwm_cmpa_for(32763u, 7500u), F28335_PWM_CMPA_MIN);
    assert_int_equal(f28335_pwm_cmpa_for(32759u, 7500u), 2);
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
    assert_int_equal(R.epwm[1].CMPA, 1); /* 100 %: 2 counts short of the period */
    assert_int_equal(R.epwm[2].CMPA, 3750);
    assert_int_equal(R.epwm[3].CMPA, 5625);
    assert_int_equal(R.epwm[4].CMPA, 1875);
    assert_int_equal(R.epwm[5].CMPA, 7500 - 750);
    for (i = 1; i < 6; i++) {
        assert_int_equal(R.epwm[i].AQCSFRC, 0u);
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
 * CTR = 0; TI does not say whether that count's events see the old or the new values, so both
 * orders are run (the driver no longer uses the software force, which the model keeps so that
 * the tests can run an older driver). Simultaneous events: the highest priority wins (TI's ePWM
 * guides: software force; counting up CBU, CAU, ZRO, CBD, CAD; counting down CBD, CAD, PRD, CBU,
 * CAU). A compare value with an action that matches at CTR = 0 or TBPRD (where the direction turns)
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

/* Writes duty to leg 0 through the driver, then runs the period that follows: a pulse of 2 on
 * counts centred on CTR = TBPRD, on limited to TBPRD - F28335_PWM_CMPA_MIN (100 % two counts
 * short), and count 0 low in every period, in both load orders. */
static void aq_expect_period(aq_model_t *m, uint16_t duty_q15)
{
    uint16_t duty[6] = {0u, 0u, 0u, 0u, 0u, 0u};
    const uint32_t on = ((uint32_t)duty_q15 * m->prd + 16384u) >> 15;
    const uint32_t on_eff = (on > m->prd - F28335_PWM_CMPA_MIN) ? m->prd - F28335_PWM_CMPA_MIN : on;
    bool at_zero = false;
    int first, last, high;
    duty[0] = duty_q15;
    hal_pwm_write(duty);
    m->cmpa_sh = R.epwm[0].CMPA;
    m->cmpb_sh = R.epwm[0].CMPB;
    m->csf_sh = R.epwm[0].AQCSFRC;
    high = aq_period(m, &at_zero, &first, &last);
    assert_false(at_zero); /* every period starts low, after 100 % too */
    if ((uint32_t)high != 2u * on_eff) {
        print_error("duty %u: %d counts high, want %u\n", duty_q15, high, (unsigned)(2u * on_eff));
        fail();
    }
    if (high > 0) { /* centred on the peak */
        assert_int_equal(m->prd - first, last - m->prd + 1);
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

/* 0 % after 100 % must clear the upper switch in the next period (an early driver left it high:
 * no event cleared it), and 100 % after 0 % must give the widest pulse at once. */
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

/* ---- Emulation halt: the six modules' time bases, action qualifiers and trip zones ----
 * TBCTL.FREE_SOFT decides where a time base stops when the emulator halts the CPU (SPRUG04A,
 * TBCTL bits 15:14): 0 after the next count, 1 when the counter completes its cycle (up-down:
 * at CTR = 0), 2 or 3 never (free run: the last duties keep switching). While stopped an
 * output holds its level: the one after the stop count's events or, should the stop come
 * before them, the one of the count before; both are checked. A tripped module's outputs are
 * low whatever its action qualifier does. The dead band only delays the rising edge of either
 * switch, so an upper switch can be on in a halt only if its EPWMxA is high and its module is
 * not tripped: the model records that per count as bit k for leg k (A..F). */
#define HALT_COUNTS_MAX (2 * 7500)

/* What the trip-zone hardware does with the driver's writes: a forced one-shot trip latches,
 * a clear ends it. The modules tripped now, bit k for ePWM k+1. */
static uint16_t tz_latch(void)
{
    uint16_t tripped = 0u;
    int i;
    for (i = 0; i < HAL_PWM_LEGS; i++) {
        if ((R.epwm[i].TZCLR & EPWM_TZ_OST) != 0u) {
            R.epwm[i].TZFLG &= (uint16_t)~EPWM_TZ_OST;
        }
        if ((R.epwm[i].TZFRC & EPWM_TZ_OST) != 0u) {
            R.epwm[i].TZFLG |= EPWM_TZ_OST;
        }
        R.epwm[i].TZCLR = 0u;
        R.epwm[i].TZFRC = 0u;
        if ((R.epwm[i].TZFLG & EPWM_TZ_OST) != 0u) {
            tripped |= (uint16_t)(1u << i);
        }
    }
    return tripped;
}

/* With two isolated neutrals each set (A B C, D E F) applies no voltage at 000 or 111; any
 * other state of its upper switches is an active vector. A tripped leg counts as off. */
static bool holds_active_vector(uint16_t upper_on)
{
    const uint16_t abc = upper_on & 7u, def = (upper_on >> 3) & 7u;
    return (abc != 0u && abc != 7u) || (def != 0u && def != 7u);
}

/* The stop count's level and the one before (positions into prev, then next). */
static void halt_expect_safe(const uint16_t *prev, const uint16_t *next, int n, int stop)
{
    const uint16_t held[2] = {stop < n ? prev[stop] : next[stop - n], prev[stop - 1]};
    int k;
    for (k = 0; k < 2; k++) {
        if (holds_active_vector(held[k]) || held[k] != 0u) {
            print_error("halt at count %d%s: upper switches %02o on (%s)\n", stop,
                        k == 0 ? "" : " (count before)", held[k],
                        holds_active_vector(held[k]) ? "an active vector" : "a zero vector");
        }
        assert_false(holds_active_vector(held[k])); /* the requirement */
        assert_int_equal(held[k], 0u);              /* the design: every upper switch off */
    }
}

/* A halt requested at every count of the period `prev`; `next` is the period after it. */
static void halt_check_requests(uint16_t free_soft, const uint16_t *prev, const uint16_t *next,
                                int n)
{
    int p;
    if (free_soft > EPWM_FREE_SOFT_STOP_AT_CYCLE_END) {
        fail_msg("FREE_SOFT %u: the time base runs on through a halt", free_soft);
    }
    for (p = 1; p < n; p++) { /* a request at count 0 is the previous period's last stop */
        halt_expect_safe(prev, next, n, free_soft == 0u ? p + 1 : n);
    }
}

/* One period of the six modules: per count the upper switches that may be on. */
static uint16_t halt_run_period(aq_model_t legs[HAL_PWM_LEGS], uint16_t tripped, uint16_t *on)
{
    uint16_t any = 0u;
    int pos, leg;
    for (pos = 0; pos < 2 * legs[0].prd; pos++) {
        uint16_t mask = 0u;
        for (leg = 0; leg < HAL_PWM_LEGS; leg++) {
            if (aq_step(&legs[leg], pos) && (((unsigned)tripped >> (unsigned)leg) & 1u) == 0u) {
                mask |= (uint16_t)(1u << leg);
            }
        }
        on[pos] = mask;
        any |= mask;
    }
    return any;
}

/* The six modules after hal_pwm_init and hal_pwm_enable, as the driver left them. */
static void halt_setup(aq_model_t legs[HAL_PWM_LEGS], bool load_before_events)
{
    int leg;
    f28335_host_regs_reset();
    R.gpiodata.GPADAT = (uint32_t)1u << F28335_PWM_TRIP_GPIO;
    assert_true(hal_pwm_init(10000u, 2000u));
    (void)tz_latch();
    hal_pwm_enable();
    assert_int_equal(tz_latch(), 0u);
    for (leg = 0; leg < HAL_PWM_LEGS; leg++) {
        aq_from_registers(&legs[leg], leg, load_before_events);
        /* the mode the argument needs, in every module */
        assert_int_equal((R.epwm[leg].TBCTL & EPWM_TBCTL_FREE_SOFT_MASK) >>
                             EPWM_TBCTL_FREE_SOFT_SHIFT,
                         EPWM_FREE_SOFT_STOP_AT_CYCLE_END);
    }
}

/* Writes each duty set for a period (and keeps the last one more period), checking a halt at
 * every count. Returns the upper switches on at any count. */
static uint16_t halt_run_sequence(aq_model_t legs[HAL_PWM_LEGS], const uint16_t (*duties)[6], int n)
{
    static uint16_t on[2][HALT_COUNTS_MAX];
    const uint16_t free_soft =
        (uint16_t)((R.epwm[0].TBCTL & EPWM_TBCTL_FREE_SOFT_MASK) >> EPWM_TBCTL_FREE_SOFT_SHIFT);
    const int counts = 2 * legs[0].prd;
    uint16_t any = 0u;
    int k, leg;
    assert_true(counts <= HALT_COUNTS_MAX);
    for (k = 0; k <= n; k++) {
        if (k < n) {
            hal_pwm_write(duties[k]);
            for (leg = 0; leg < HAL_PWM_LEGS; leg++) {
                legs[leg].cmpa_sh = R.epwm[leg].CMPA;
                legs[leg].cmpb_sh = R.epwm[leg].CMPB;
                legs[leg].csf_sh = R.epwm[leg].AQCSFRC;
            }
        }
        any |= halt_run_period(legs, tz_latch(), on[k & 1]);
        if (k > 0) {
            halt_check_requests(free_soft, on[(k - 1) & 1], on[k & 1], counts);
        }
    }
    return any;
}

/* Duty sets a drive commands: conventional MPTC's full-period vectors, DDC with a set's zero
 * state 111 (its two legs of v at 100 %), the limits of the compare range, 0 % and 100 %. */
static const uint16_t halt_duty_sets[][6] = {
    {0u, 0u, 0u, 0u, 0u, 0u},
    {32768u, 0u, 0u, 32768u, 0u, 0u},
    {32768u, 32768u, 32768u, 32768u, 32768u, 32768u},
    {32768u, 32768u, 0u, 0u, 32768u, 32768u},
    {32768u, 32768u, 13107u, 0u, 9830u, 32768u},
    {3u, 32763u, 32767u, 32766u, 1u, 32768u},
    {32768u, 3u, 0u, 32763u, 16384u, 32768u},
    {16384u, 8192u, 24576u, 32760u, 5u, 32768u},
    {0u, 32768u, 0u, 32768u, 0u, 32768u},
    {40000u, 0u, 32768u, 3u, 32768u, 0u},
};

/* No leg holds an active vector while the emulator halts the CPU, whatever the duties, wherever
 * in the period the halt comes, in both orders of the CTR = 0 load and events. Before the fix a
 * leg at 100 % stayed high (continuous software force) through the halt. */
static void test_halt_holds_no_active_vector(void **state)
{
    const int n = (int)(sizeof halt_duty_sets / sizeof halt_duty_sets[0]);
    int order;
    (void)state;
    for (order = 0; order < 2; order++) {
        aq_model_t legs[HAL_PWM_LEGS];
        halt_setup(legs, order == 0);
        (void)halt_run_sequence(legs, halt_duty_sets, n);
    }
}

/* An isolated leg (its module tripped) stays off through a halt, and the others hold no active
 * vector beside it; after the software force-off no output is on at any count. */
static void test_halt_tripped_and_forced_off(void **state)
{
    const int n = (int)(sizeof halt_duty_sets / sizeof halt_duty_sets[0]);
    aq_model_t legs[HAL_PWM_LEGS];
    (void)state;
    halt_setup(legs, true);
    assert_true(hal_pwm_isolate_leg(2));
    (void)halt_run_sequence(legs, halt_duty_sets, n);

    halt_setup(legs, true);
    hal_pwm_force_off();
    assert_int_equal(halt_run_sequence(legs, halt_duty_sets, n), 0u);
}

/* What the halt costs at 100 %: EPWMxA low for the two counts next to CTR = 0; the dead band
 * delays the upper switch's turn-on by DBRED after them and swallows the lower switch's pulse
 * (shorter than DBFED). Counts per period of 2 TBPRD, in steady 100 %. The dead band as run
 * lengths: a switch is on once EPWMxA has held its level (high for the upper, low for the lower)
 * for more than that switch's delay. */
static void test_halt_cost_at_full_duty(void **state)
{
    static const uint16_t full[6] = {32768u, 32768u, 32768u, 32768u, 32768u, 32768u};
    aq_model_t m;
    int period, pos, run = 1000; /* counts at this level: steady 0 % before */
    bool level = false;
    (void)state;
    assert_true(hal_pwm_init(10000u, 2000u));
    hal_pwm_write(full);
    aq_from_registers(&m, 0, true);
    for (period = 0; period < 3; period++) {
        int low = 0, upper = 0, lower = 0, upper_first = -1;
        for (pos = 0; pos < 2 * m.prd; pos++) {
            const bool in = aq_step(&m, pos);
            run = (in == level) ? run + 1 : 1;
            level = in;
            low += in ? 0 : 1;
            lower += (!in && run > (int)R.epwm[0].DBFED) ? 1 : 0;
            if (in && run > (int)R.epwm[0].DBRED) {
                upper++;
                upper_first = (upper_first < 0) ? pos : upper_first;
            }
        }
        if (period > 0) { /* the first one follows the 0 % of init */
            assert_int_equal(low, 2);
            assert_false(level); /* off from the count before CTR = 0 (the ADC start) ... */
            assert_int_equal(upper_first, 1 + 300); /* ... until DBRED after CTR = 1 */
            assert_int_equal(upper, 2 * 7500 - 2 - 300);
            assert_int_equal(lower, 0);
        }
    }
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
        cmocka_unit_test_setup(test_halt_holds_no_active_vector, setup),
        cmocka_unit_test_setup(test_halt_tripped_and_forced_off, setup),
        cmocka_unit_test_setup(test_halt_cost_at_full_duty, setup),
        cmocka_unit_test_setup(test_no_protected_write_outside_eallow, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
