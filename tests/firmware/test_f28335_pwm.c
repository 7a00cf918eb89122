/* ePWM driver against RAM register frames. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

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
        /* A: set on CAU, clear on CAD, nothing else */
        assert_int_equal(R.epwm[i].AQCTLA, (2u << 4) | (1u << 6));
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
    assert_int_equal(f28335_pwm_cmpa_for(0u, 7500u), 7501);     /* never matches: 0 % */
    assert_int_equal(f28335_pwm_cmpa_for(32768u, 7500u), 0);    /* set at zero: 100 % */
    assert_int_equal(f28335_pwm_cmpa_for(40000u, 7500u), 0);    /* clamped */
    assert_int_equal(f28335_pwm_cmpa_for(16384u, 7500u), 3750); /* 50 % */
    assert_int_equal(f28335_pwm_cmpa_for(8192u, 7500u), 5625);  /* 25 %: high 2*(7500-5625)/15000 */
    assert_int_equal(f28335_pwm_cmpa_for(24576u, 7500u), 1875); /* 75 % */
    assert_int_equal(f28335_pwm_cmpa_for(1u, 7500u), 7500);     /* rounds to no pulse */
    assert_int_equal(f28335_pwm_cmpa_for(32767u, 7500u), 1);    /* below full: CMPA >= 1 */
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
    assert_int_equal(R.epwm[1].CMPA, 0);
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
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
