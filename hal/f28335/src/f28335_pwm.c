/*
 * hal_pwm on the F28335: ePWM1..6, one module per inverter leg (A..F).
 *
 *   time base   up-down count, TBCLK = SYSCLKOUT, TBPRD = SYSCLK / (2 f),
 *               ePWM1 master (SYNCO at CTR = 0), ePWM2..6 slaves (phase 0,
 *               count up after sync, SYNCI passed on)
 *   compare     CMPA shadowed, loaded at CTR = 0; CMPB unused
 *   actions     EPWMxA set on CAU, cleared on CAD: high while CTR > CMPA, a
 *               pulse of 2 (TBPRD - CMPA) TBCLK centred on CTR = TBPRD, with
 *               CMPA kept in 1 .. TBPRD - 1; also cleared on ZRO, so every
 *               period starts low. Event priorities (TI's ePWM guides, up-down
 *               mode): counting up CBU, CAU, ZRO, CBD, CAD; counting down CBD,
 *               CAD, PRD, CBU, CAU; CMPA is never 0 or TBPRD, so no compare
 *               competes with ZRO or meets the turn at TBPRD.
 *   0 %, 100 %  0 %: no compare event (CMPA = TBPRD + 1), ZRO keeps it low.
 *               100 %: the widest compare pulse, CMPA = 1 (the largest duty
 *               that leaves CTR = 0 low): high from CTR = 1 counting up to
 *               CTR = 1 counting down, 2 (TBPRD - 1) of 2 TBPRD counts, 2 TBCLK
 *               short (13.3 ns at 150 MHz). The dead band makes that notch
 *               DBRED + 2 counts of the upper switch off, the lower one not
 *               turned on (tests/firmware: 302 of 15000 counts at 10 kHz and
 *               2 us). No continuous software force: it would hold a leg high
 *               through a debugger halt.
 *   emulation   FREE_SOFT = 1: on a debugger halt each time base runs on to the
 *   halt        end of its cycle, CTR = 0 in up-down mode, and stops there
 *               (SPRUG04A, TBCTL); the outputs hold their level. Every EPWMxA
 *               is low at CTR = 0 and at CTR = 1 counting down before it, so in
 *               a halt no upper switch is on and no three-phase set holds an
 *               active vector; a tripped module stays tripped (the one-shot
 *               latch needs software to clear it). The F2833x has no trip input
 *               tied to the CPU's emulation stop (TZ1..TZ6 are pins), so this
 *               is the only on-chip guard; FREE_SOFT = 0 would stop anywhere in
 *               the pattern, 2 or 3 would keep switching the last duties.
 *   dead band   EPWMxA as source of both edges, full mode, active high
 *               complementary: xA = upper switch, xB = lower switch
 *   trip zone   TZ1 (GPIO12, active low) one-shot trips every module, both
 *               outputs forced low; software force-off = TZFRC.OST; an isolated leg is
 *               its module's one-shot trip alone, which hal_pwm_enable leaves set
 *   ADC start   ePWM1 SOCA at CTR = 0: the period boundary, the symmetry
 *               point of the centred pulses, where every EPWMxA is low (a leg
 *               at 100 % is in its notch, both switches off)
 */
#include "f28335_hal.h"
#include "f28335_internal.h"
#include "hal_pwm.h"
#include "sixphase_placement.h"

static uint16_t pwm_prd;
static bool pwm_sw_forced = true;
static uint16_t pwm_isolated; /* bit k: ePWM k+1 tripped for good (hal_pwm_isolate_leg) */

uint16_t f28335_pwm_period_for(uint32_t carrier_hz)
{
    uint32_t prd;
    if (carrier_hz == 0u || carrier_hz > F28335_SYSCLK_HZ / 4u) {
        return 0u;
    }
    /* up-down: period = 2 TBPRD TBCLK; round to nearest */
    prd = (F28335_SYSCLK_HZ + carrier_hz) / (2u * carrier_hz);
    if (prd < 2u || prd > 65534u) { /* 65534: duty 0 needs CMPA = TBPRD + 1 */
        return 0u;
    }
    return (uint16_t)prd;
}

uint16_t f28335_pwm_deadband_for(uint32_t dead_time_ns)
{
    /* counts = ns * 150 MHz / 1e9 = ns * 3 / 20, rounded */
    const uint32_t counts = (dead_time_ns * 3u + 10u) / 20u;
    if (dead_time_ns > 1000000u || counts > EPWM_DB_MAX_COUNTS) {
        return 0xFFFFu;
    }
    return (uint16_t)counts;
}

SIXPHASE_RAMFUNC uint16_t f28335_pwm_cmpa_for(uint16_t duty_q15, uint16_t prd)
{
    const uint32_t on = ((uint32_t)duty_q15 * prd + (HAL_PWM_DUTY_ONE / 2u)) >> 15;
    if (on == 0u) {
        return (uint16_t)(prd + 1u); /* 0 %: no compare event */
    }
    if (on >= prd) {
        return F28335_PWM_CMPA_MIN; /* 100 %: low at CTR = 0, where a debugger halt stops */
    }
    return (uint16_t)(prd - on);
}

uint16_t f28335_pwm_period(void) { return pwm_prd; }

SIXPHASE_RAMFUNC static void pwm_force_all(void)
{
    int16_t i;
    F28335_EALLOW();
    for (i = 0; i < F28335_EPWM_COUNT; i++) {
        F28335_EPWM(i)->TZFRC = EPWM_TZ_OST;
    }
    F28335_EDIS();
}

/* One module (i = 0 for ePWM1, the master), its outputs tripped low before anything else. */
static void pwm_init_module(int16_t i, uint16_t prd, uint16_t db)
{
    volatile f28335_epwm_t *p = F28335_EPWM(i);
    uint16_t tbctl = (uint16_t)(EPWM_TBCTL_CTRMODE_UPDOWN |
                                (EPWM_FREE_SOFT_STOP_AT_CYCLE_END << EPWM_TBCTL_FREE_SOFT_SHIFT));
    F28335_EALLOW();
    p->TZSEL = EPWM_TZSEL_OSHT1;
    p->TZCTL = (uint16_t)(EPWM_TZCTL_TZA_LOW | EPWM_TZCTL_TZB_LOW);
    p->TZEINT = 0u;
    p->TZFRC = EPWM_TZ_OST;
    p->HRCNFG = 0u;
    F28335_EDIS();

    if (i == 0) {
        tbctl |= (uint16_t)(EPWM_SYNCOSEL_CTR_ZERO << EPWM_TBCTL_SYNCOSEL_SHIFT);
    } else {
        /* SYNCOSEL = SYNCI (value 0): each slave passes the master's sync on */
        tbctl |= (uint16_t)(EPWM_TBCTL_PHSEN | EPWM_TBCTL_PHSDIR_UP);
    }
    p->TBPRD = prd;
    p->TBPHS = 0u;
    p->TBPHSHR = 0u;
    p->TBCTR = 0u;
    p->TBCTL = tbctl; /* PRDLD = 0 (shadow), HSPCLKDIV = CLKDIV = 0 (/1) */

    p->CMPCTL = 0u; /* CMPA/CMPB shadowed, loaded at CTR = 0 */
    p->CMPA = f28335_pwm_cmpa_for(0u, prd);
    p->CMPAHR = 0u;
    p->CMPB = 0u; /* no action uses it */
    p->AQCTLA =
        (uint16_t)((EPWM_AQ_CLEAR << EPWM_AQ_ZRO_SHIFT) | (EPWM_AQ_SET << EPWM_AQ_CAU_SHIFT) |
                   (EPWM_AQ_CLEAR << EPWM_AQ_CAD_SHIFT));
    p->AQCTLB = 0u; /* xB comes from the dead band */
    p->AQSFRC = EPWM_AQSFRC_RLDCSF_ZERO;
    p->AQCSFRC = 0u; /* never forced: a force would hold through a halt */

    p->DBCTL = (uint16_t)(EPWM_DBCTL_OUT_MODE_FULL | EPWM_DBCTL_POLSEL_AHC);
    p->DBRED = db;
    p->DBFED = db;
    p->PCCTL = 0u;
    if (i == 0) {
        p->ETSEL = (uint16_t)((EPWM_ET_CTR_ZERO << EPWM_ETSEL_SOCASEL_SHIFT) | EPWM_ETSEL_SOCAEN);
        p->ETPS = (uint16_t)(1u << EPWM_ETPS_SOCAPRD_SHIFT);
    } else {
        p->ETSEL = 0u;
        p->ETPS = 0u;
    }
}

/* Pins last, when the outputs are already tripped low. GPIO0..11 = EPWM1A, 1B, 2A, ..., 6B;
 * gate drivers need pull-downs until here. */
static void pwm_init_pins(void)
{
    int16_t i;
    for (i = 0; i < 2 * F28335_EPWM_COUNT; i++) {
        f28335_gpio_set_pullup((uint16_t)i, false);
        f28335_gpio_set_mux((uint16_t)i, F28335_GPIO_MUX_PERIPH1);
    }
    f28335_gpio_set_pullup(F28335_PWM_TRIP_GPIO, true);
    f28335_gpio_set_qsel(F28335_PWM_TRIP_GPIO, F28335_GPIO_QSEL_ASYNC);
    f28335_gpio_set_mux(F28335_PWM_TRIP_GPIO, F28335_GPIO_MUX_PERIPH1);
}

bool hal_pwm_init(uint32_t carrier_hz, uint32_t dead_time_ns)
{
    volatile f28335_sysctrl_t *sys = F28335_SYSCTRL;
    const uint16_t prd = f28335_pwm_period_for(carrier_hz);
    const uint16_t db = f28335_pwm_deadband_for(dead_time_ns);
    int16_t i;

    if (prd == 0u || db == 0xFFFFu) {
        return false;
    }
    pwm_prd = prd;
    pwm_sw_forced = true;
    pwm_isolated = 0u;

    /* Stop all time bases while configuring; clocks of ePWM1..6 on. */
    F28335_EALLOW();
    sys->PCLKCR0 &= (uint16_t)~PCLKCR0_TBCLKSYNC;
    sys->PCLKCR1 |= PCLKCR1_EPWM_ALL;
    F28335_EDIS();
    for (i = 0; i < F28335_EPWM_COUNT; i++) {
        pwm_init_module(i, prd, db);
    }
    /* Start all time bases together. */
    F28335_EALLOW();
    sys->PCLKCR0 |= PCLKCR0_TBCLKSYNC;
    F28335_EDIS();
    pwm_init_pins();
    return true;
}

SIXPHASE_RAMFUNC void hal_pwm_write(const uint16_t duty[HAL_PWM_LEGS])
{
    int16_t i;
    for (i = 0; i < HAL_PWM_LEGS; i++) {
        volatile f28335_epwm_t *p = F28335_EPWM(i);
        /* an isolated leg's module is tripped; its compare gets 0 % all the same */
        const uint16_t d = (((unsigned)pwm_isolated >> i) & 1u) != 0u ? 0u : duty[i];
        p->CMPA = f28335_pwm_cmpa_for(d, pwm_prd);
    }
}

SIXPHASE_RAMFUNC void hal_pwm_force_off(void)
{
    pwm_sw_forced = true;
    pwm_force_all();
}

SIXPHASE_RAMFUNC void hal_pwm_enable(void)
{
    int16_t i;
    pwm_sw_forced = false;
    F28335_EALLOW();
    for (i = 0; i < F28335_EPWM_COUNT; i++) {
        if ((((unsigned)pwm_isolated >> i) & 1u) == 0u) {
            F28335_EPWM(i)->TZCLR = (uint16_t)(EPWM_TZ_OST | EPWM_TZ_INT);
        }
    }
    F28335_EDIS();
}

SIXPHASE_RAMFUNC bool hal_pwm_is_off(void)
{
    int16_t i;
    for (i = 0; i < F28335_EPWM_COUNT; i++) {
        if ((((unsigned)pwm_isolated >> i) & 1u) == 0u &&
            (F28335_EPWM(i)->TZFLG & EPWM_TZ_OST) != 0u) {
            return true;
        }
    }
    return false;
}

bool hal_pwm_isolate_leg(int16_t leg)
{
    if (leg < 0 || leg >= F28335_EPWM_COUNT) {
        return false;
    }
    pwm_isolated |= (uint16_t)(1u << leg);
    F28335_EALLOW();
    F28335_EPWM(leg)->TZFRC = EPWM_TZ_OST; /* this module only: the other legs run on */
    F28335_EDIS();
    return true;
}

uint16_t hal_pwm_isolated_legs(void) { return pwm_isolated; }

void hal_pwm_restore_legs(void) { pwm_isolated = 0u; }

SIXPHASE_RAMFUNC bool hal_pwm_hw_trip_seen(void)
{
    /* TZ1 is active low: the comparator still asserting, or a one-shot latch
     * that software did not cause. */
    if (!f28335_gpio_read(F28335_PWM_TRIP_GPIO)) {
        return true;
    }
    return !pwm_sw_forced && hal_pwm_is_off();
}

SIXPHASE_RAMFUNC uint16_t f28335_pwm_time_base(void) { return F28335_EPWM(0)->TBCTR; }
