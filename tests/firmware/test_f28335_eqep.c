/* eQEP driver: register set-up, angle and speed at low and high speed, health. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "f28335_hal.h"
#include "hal_encoder.h"

#define R (f28335_host_regs)
#define LINES 2500u
#define COUNTS (4u * LINES)
#define PN 3u

static int setup(void **state)
{
    (void)state;
    f28335_host_regs_reset();
    assert_true(hal_encoder_init(LINES, PN, 0u));
    return 0;
}

static int32_t q16(double rev_s) { return (int32_t)(rev_s * 65536.0); }

static void assert_near_i32(int32_t got, int32_t want, int32_t tol)
{
    const int32_t d = got - want;
    if (d > tol || d < -tol) {
        fail_msg("got %d want %d (tol %d)", (int)got, (int)want, (int)tol);
    }
}

/* One unit period: position latched at poslat, capture period and status. */
static void unit_event(uint32_t poslat, uint16_t cprd, uint16_t ctmr, uint16_t sts)
{
    R.eqep1.QPOSLAT = poslat;
    R.eqep1.QCPRDLAT = cprd;
    R.eqep1.QCTMRLAT = ctmr;
    R.eqep1.QEPSTS = sts;
    R.eqep1.QFLG = EQEP_UTO | EQEP_INT;
}

static void test_init_registers(void **state)
{
    (void)state;
    assert_int_equal(R.eqep1.QDECCTL, 0u); /* quadrature count */
    assert_int_equal(R.eqep1.QPOSMAX, COUNTS - 1u);
    assert_int_equal(R.eqep1.QPOSINIT, 0u);
    assert_int_equal(R.eqep1.QUPRD, 150000000u / 500u);
    assert_int_equal(R.eqep1.QWDPRD, F28335_QEP_WATCHDOG_PRD);
    assert_int_equal(R.eqep1.QCAPCTL, EQEP_QCAPCTL_CEN | (6u << 4) | 4u);
    {
        const uint16_t c = R.eqep1.QEPCTL;
        assert_int_equal(c & EQEP_QEPCTL_QPEN, EQEP_QEPCTL_QPEN);
        assert_int_equal(c & EQEP_QEPCTL_PCRM_MASK, 0u); /* reset on index */
        assert_int_equal((c >> 4) & 3u, 1u);             /* latch on index rising edge */
        assert_int_equal(c & EQEP_QEPCTL_UTE, EQEP_QEPCTL_UTE);
        assert_int_equal(c & EQEP_QEPCTL_QCLM, EQEP_QEPCTL_QCLM);
        assert_int_equal(c & EQEP_QEPCTL_WDE, EQEP_QEPCTL_WDE);
    }
    assert_int_equal(R.sysctrl.PCLKCR1 & PCLKCR1_EQEP1ENCLK, PCLKCR1_EQEP1ENCLK);
    assert_int_equal(R.gpioctrl.GPAMUX2 & 0xFF00u, 0x5500u); /* GPIO20..23 on mux 1 */
    assert_false(hal_encoder_init(0u, 3u, 0u));
    assert_false(hal_encoder_init(2500u, 0u, 0u));
}

static void test_angle(void **state)
{
    hal_encoder_sample_t s;
    (void)state;
    R.eqep1.QEPSTS = EQEP_STS_FIMF;
    R.eqep1.QPOSCNT = 0u;
    hal_encoder_read(&s);
    assert_int_equal(s.elec_angle, 0u);
    assert_true(s.healthy);

    /* a quarter mechanical turn is 3/4 electrical turn at Pn = 3 */
    R.eqep1.QPOSCNT = COUNTS / 4u;
    hal_encoder_read(&s);
    assert_true(s.elec_angle >= 0xBFFFFFF0u && s.elec_angle <= 0xC0000010u);

    /* one electrical turn (counts / 3, not an integer) wraps to ~0 */
    R.eqep1.QPOSCNT = 3333u; /* 3333 * 3 / 10000 = 0.9999 turn */
    hal_encoder_read(&s);
    assert_true(s.elec_angle > 0xFFF00000u);

    /* offset added modulo one turn */
    assert_true(hal_encoder_init(LINES, PN, 0x40000000u));
    R.eqep1.QEPSTS = EQEP_STS_FIMF;
    R.eqep1.QPOSCNT = COUNTS / 4u;
    hal_encoder_read(&s);
    assert_true(s.elec_angle <= 0x00000010u || s.elec_angle >= 0xFFFFFFF0u);
}

static void test_high_speed_unit_timer(void **state)
{
    hal_encoder_sample_t s;
    (void)state;
    /* 50 rev/s: 500000 counts/s, 1000 counts per 2 ms, crossing the index */
    unit_event(9500u, 0u, 0u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(&s);
    assert_int_equal(R.eqep1.QCLR & EQEP_UTO, EQEP_UTO);
    unit_event(500u, 75u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(&s);
    assert_int_equal(s.mech_speed_q16, q16(50.0));
    assert_false(f28335_qep_state()->use_capture);
    /* reverse: -1000 counts per period */
    unit_event(9500u, 75u, 10u, EQEP_STS_FIMF);
    hal_encoder_read(&s);
    assert_int_equal(s.mech_speed_q16, q16(-50.0));
    assert_int_equal(f28335_qep_speed_unit(f28335_qep_state(), 1), q16(0.05));
}

static void test_low_speed_capture(void **state)
{
    hal_encoder_sample_t s;
    (void)state;
    /* 0.5 rev/s: 5000 counts/s; 16 counts take 3.2 ms = 7500 capture clocks
     * at 150 MHz / 64. The unit-timer difference (10 counts / 2 ms) is coarse. */
    unit_event(100u, 7500u, 100u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(&s);
    unit_event(110u, 7500u, 100u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(&s);
    assert_true(f28335_qep_state()->use_capture);
    assert_near_i32(s.mech_speed_q16, q16(0.5), 10);
    /* direction from QDF */
    unit_event(100u, 7500u, 100u, EQEP_STS_FIMF);
    hal_encoder_read(&s);
    assert_near_i32(s.mech_speed_q16, q16(-0.5), 10);
    /* decelerating: the running period bounds the estimate */
    unit_event(100u, 7500u, 15000u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(&s);
    assert_near_i32(s.mech_speed_q16, q16(0.25), 10);
    /* capture overflow: standstill */
    unit_event(100u, 7500u, 100u, EQEP_STS_FIMF | EQEP_STS_COEF);
    hal_encoder_read(&s);
    assert_int_equal(s.mech_speed_q16, 0);
    assert_int_equal(R.eqep1.QEPSTS & EQEP_STS_COEF, EQEP_STS_COEF); /* written back to clear */
    assert_true(s.healthy);                                          /* standing still is healthy */
}

static void test_switch_with_hysteresis(void **state)
{
    hal_encoder_sample_t s;
    uint32_t pos = 0u;
    (void)state;
    unit_event(pos, 1000u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(&s);
    /* 13.5 rev/s = 270 counts per unit: between thresholds, stays on capture */
    pos += 270u;
    unit_event(pos, 278u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(&s);
    assert_true(f28335_qep_state()->use_capture);
    /* 16 rev/s: switches to the unit timer */
    pos += 320u;
    unit_event(pos, 234u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(&s);
    assert_false(f28335_qep_state()->use_capture);
    assert_int_equal(s.mech_speed_q16, q16(16.0));
    /* back to 13.5: stays on the unit timer */
    pos += 270u;
    unit_event(pos, 278u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(&s);
    assert_false(f28335_qep_state()->use_capture);
    /* 10 rev/s: back to capture */
    pos += 200u;
    unit_event(pos, 375u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(&s);
    assert_true(f28335_qep_state()->use_capture);
    assert_near_i32(s.mech_speed_q16, q16(10.0), 700);
}

static void test_health(void **state)
{
    hal_encoder_sample_t s;
    (void)state;
    R.eqep1.QEPSTS = 0u; /* no index yet */
    hal_encoder_read(&s);
    assert_false(s.healthy);
    R.eqep1.QEPSTS = EQEP_STS_FIMF;
    hal_encoder_read(&s);
    assert_true(s.healthy);
    /* watchdog at standstill: still healthy */
    R.eqep1.QFLG = EQEP_WTO;
    hal_encoder_read(&s);
    assert_true(s.healthy);
    /* position counter error: latched unhealthy */
    R.eqep1.QFLG = EQEP_PCE;
    hal_encoder_read(&s);
    assert_false(s.healthy);
    R.eqep1.QFLG = 0u;
    hal_encoder_read(&s);
    assert_false(s.healthy);
}

/* Two unit periods: 1000 counts in 2 ms, 50 rev/s. */
static void spin_at_50_rev_s(hal_encoder_sample_t *s)
{
    unit_event(0u, 100u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(s);
    unit_event(1000u, 75u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(s);
}

/* No edge for 10 ms (the index is still valid). */
static void watchdog_time_out(hal_encoder_sample_t *s)
{
    R.eqep1.QEPSTS = EQEP_STS_FIMF; /* the RAM frame keeps what the driver wrote to clear COEF */
    R.eqep1.QFLG = EQEP_WTO;
    hal_encoder_read(s);
}

static void test_loss_of_edges_at_speed(void **state)
{
    hal_encoder_sample_t s;
    (void)state;
    spin_at_50_rev_s(&s);
    assert_true(s.healthy);
    R.eqep1.QFLG = EQEP_WTO; /* no edge for 10 ms at 50 rev/s */
    hal_encoder_read(&s);
    assert_false(s.healthy);
    assert_int_equal(s.mech_speed_q16, 0);
}

/* The realistic order: the unit timer sees the empty periods (speed 0) long before the
 * 10 ms watchdog; the watchdog must still judge by the speed before the signal stopped. */
static void test_loss_of_edges_after_unit_timer_reported_zero(void **state)
{
    hal_encoder_sample_t s;
    int k;
    (void)state;
    spin_at_50_rev_s(&s);
    for (k = 0; k < 9; k++) {
        unit_event(1000u, 75u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF | EQEP_STS_COEF);
        hal_encoder_read(&s);
    }
    assert_true(s.healthy);
    assert_int_equal(s.mech_speed_q16, 0);
    watchdog_time_out(&s);
    assert_false(s.healthy);
}

/* Slowing to a stop below the threshold is a stop, not a loss. */
static void test_slow_stop_stays_healthy(void **state)
{
    hal_encoder_sample_t s;
    (void)state;
    unit_event(0u, 100u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF);
    hal_encoder_read(&s);
    unit_event(2u, 100u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF | EQEP_STS_COEF);
    hal_encoder_read(&s);
    unit_event(2u, 100u, 10u, EQEP_STS_FIMF | EQEP_STS_QDF | EQEP_STS_COEF);
    hal_encoder_read(&s);
    watchdog_time_out(&s);
    assert_true(s.healthy);
}

/* The per-sample angle and speed use only 32-bit products (no 64-bit arithmetic in the ISR on
 * the C28x); they give exactly what the 64-bit forms give (the references below), for
 * encoders from 1 to 2^28 lines and 1 to 50 pole pairs, over every position class, difference
 * and capture period, including the saturation limits (where the 64-bit product itself would
 * have overflowed, as the old code's did for a 1-line encoder, the reference saturates). */
static uint32_t ref_angle(uint32_t counts, uint16_t pp, uint32_t off, uint32_t pos)
{
    const uint64_t a = (((uint64_t)pp << 48) + counts / 2u) / counts;
    return (uint32_t)(((uint64_t)pos * a) >> 16) + off;
}

static int32_t ref_speed_unit(uint32_t counts, int32_t delta)
{
    const int64_t k = (int64_t)((((uint64_t)F28335_QEP_UNIT_HZ << 32) + counts / 2u) / counts);
    int64_t v;
    if (delta > INT64_MAX / k || delta < -(INT64_MAX / k)) { /* beyond 64 bits: saturated */
        return (delta < 0) ? -INT32_MAX : INT32_MAX;
    }
    v = ((int64_t)delta * k) / 65536;
    return (v > (int64_t)INT32_MAX)    ? INT32_MAX
           : (v < -(int64_t)INT32_MAX) ? -INT32_MAX
                                       : (int32_t)v;
}

static int64_t ref_speed_capture(uint32_t counts, uint16_t period)
{
    const uint64_t k =
        (((uint64_t)F28335_SYSCLK_HZ << (16u + F28335_QEP_UPPS)) >> F28335_QEP_CCPS) / counts;
    const uint64_t v = k / period;
    return (v > (uint64_t)INT32_MAX) ? INT32_MAX : (int64_t)v;
}

static void check_encoder(uint32_t lines, uint16_t pp)
{
    const uint32_t counts = 4u * lines;
    const f28335_qep_state_t *q = f28335_qep_state();
    uint32_t i;
    f28335_host_regs_reset();
    assert_true(hal_encoder_init(lines, pp, 0x12345678u));
    for (i = 0; i < 4096u; i++) { /* positions spread over the turn, both ends included */
        const uint32_t pos = (uint32_t)(((uint64_t)(counts - 1u) * i) / 4095u);
        assert_int_equal(f28335_qep_angle(q, pos), ref_angle(counts, pp, 0x12345678u, pos));
    }
    for (i = 0; i < 64u; i++) { /* around 2^16 boundaries of the position */
        const uint32_t pos = ((i * 0x10000u) + (i & 1u) - 1u) % counts;
        assert_int_equal(f28335_qep_angle(q, pos), ref_angle(counts, pp, 0x12345678u, pos));
    }
    for (i = 0; i < 2000u; i++) {
        const int32_t d = (int32_t)((i * 2654435761u) >> (i % 31u)) * ((i & 1u) ? -1 : 1);
        if (f28335_qep_speed_unit(q, d) != ref_speed_unit(counts, d)) {
            print_error("lines %u pp %u delta %d\n", (unsigned)lines, (unsigned)pp, (int)d);
        }
        assert_int_equal(f28335_qep_speed_unit(q, d), ref_speed_unit(counts, d));
    }
    assert_int_equal(f28335_qep_speed_unit(q, INT32_MAX), ref_speed_unit(counts, INT32_MAX));
    assert_int_equal(f28335_qep_speed_unit(q, -INT32_MAX), ref_speed_unit(counts, -INT32_MAX));
    assert_int_equal(f28335_qep_speed_unit(q, (int32_t)q->ut_max_delta),
                     ref_speed_unit(counts, (int32_t)q->ut_max_delta));
    for (i = 1; i <= 65535u; i += (i < 300u) ? 1u : 97u) {
        const int64_t want = ref_speed_capture(counts, (uint16_t)i);
        const int64_t got = f28335_qep_speed_capture(q, (uint16_t)i);
        /* exact while the constant fits 32 bits (lines >= 144); below, within 2^cap_shift */
        assert_true(got - want <= 0 && want - got < ((int64_t)2 << q->cap_shift));
        if (q->cap_shift == 0u) {
            assert_true(got == want);
        }
    }
}

/* Position reads of the counter: the unwrapped position follows the shaft across the turn's
 * wrap (both directions) and across the first index, whose reset the eQEP latched. */
static void read_at(uint32_t poscnt, uint16_t sts, hal_encoder_sample_t *s)
{
    R.eqep1.QPOSCNT = poscnt;
    R.eqep1.QEPSTS = sts;
    hal_encoder_read(s);
}

static void test_unwrapped_position_and_index(void **state)
{
    hal_encoder_sample_t s;
    (void)state;
    read_at(0u, 0u, &s);
    assert_int_equal(s.position, 0);
    assert_false(s.index_seen);
    assert_false(s.healthy);
    read_at(COUNTS - 5u, 0u, &s); /* backwards over the wrap: -5 */
    assert_int_equal(s.position, -5);
    read_at(40u, 0u, &s); /* forwards again over the wrap: +45 */
    assert_int_equal(s.position, 40);
    /* counting up, the index came at count 1234 (latched) and reset the counter to 0; now 20 */
    R.eqep1.QPOSILAT = 1234u;
    read_at(20u, EQEP_STS_FIMF | EQEP_STS_FIDF | EQEP_STS_QDF, &s);
    assert_int_equal(s.position, 1234 + 20);
    assert_true(s.index_seen && s.healthy);
    read_at(COUNTS - 10u, EQEP_STS_FIMF | EQEP_STS_FIDF, &s); /* -30 over the wrap */
    assert_int_equal(s.position, 1224);
    /* a whole turn forward in many reads */
    {
        uint32_t k;
        for (k = 1u; k <= 10u; k++) {
            read_at((COUNTS - 10u + k * (COUNTS / 10u)) % COUNTS, EQEP_STS_FIMF, &s);
        }
        assert_int_equal(s.position, 1224 + (int32_t)COUNTS);
    }
    /* counting down through the first index: reset to QPOSMAX */
    f28335_host_regs_reset();
    assert_true(hal_encoder_init(LINES, PN, 0u));
    read_at(0u, 0u, &s);
    read_at(COUNTS - 700u, 0u, &s); /* -700 */
    R.eqep1.QPOSILAT = COUNTS - 1000u;
    read_at(COUNTS - 1u - 50u, EQEP_STS_FIMF, &s); /* -300 to the index, -50 after it */
    assert_int_equal(s.position, -1050);
    assert_int_equal(hal_encoder_counts_per_turn(), COUNTS);
}

static void test_offset_set_and_read(void **state)
{
    hal_encoder_sample_t s;
    (void)state;
    assert_int_equal(hal_encoder_offset(), 0u);
    read_at(COUNTS / 4u, EQEP_STS_FIMF, &s);
    hal_encoder_set_offset(0x40000000u);
    assert_int_equal(hal_encoder_offset(), 0x40000000u);
    read_at(COUNTS / 4u, EQEP_STS_FIMF, &s); /* 3/4 turn + 1/4 turn */
    assert_true(s.elec_angle <= 0x00000010u || s.elec_angle >= 0xFFFFFFF0u);
}

static void test_32bit_forms_equal_64bit_references(void **state)
{
    static const uint32_t lines[] = {1u,    100u,  143u,     144u,       1000u,
                                     2500u, 4096u, 1u << 20, 0x10000000u};
    static const uint16_t pole_pairs[] = {1u, 3u, 7u, 50u};
    size_t i, j;
    (void)state;
    for (i = 0; i < sizeof lines / sizeof lines[0]; i++) {
        for (j = 0; j < sizeof pole_pairs / sizeof pole_pairs[0]; j++) {
            check_encoder(lines[i], pole_pairs[j]);
        }
    }
    f28335_host_regs_reset();
    assert_true(hal_encoder_init(LINES, PN, 0u));
    assert_int_equal(f28335_qep_state()->cap_shift, 0u); /* the board's encoder: exact */
}

/* hal_encoder_rehome writes only FIMF's clear bit to QEPSTS (write 1 to clear; the zeros leave
 * the other flags alone): unhealthy until the next index sets FIMF again. */
static void test_rehome_waits_for_the_index(void **state)
{
    hal_encoder_sample_t s;
    (void)state;
    R.eqep1.QEPSTS = EQEP_STS_FIMF | EQEP_STS_QDF;
    hal_encoder_read(&s);
    assert_true(s.healthy);
    hal_encoder_rehome();
    assert_int_equal(R.eqep1.QEPSTS, EQEP_STS_FIMF);
    R.eqep1.QEPSTS = EQEP_STS_QDF; /* what the device then shows: FIMF cleared */
    hal_encoder_read(&s);
    assert_false(s.healthy);
    R.eqep1.QEPSTS = EQEP_STS_FIMF | EQEP_STS_QDF; /* the index passed */
    hal_encoder_read(&s);
    assert_true(s.healthy);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_init_registers, setup),
        cmocka_unit_test_setup(test_angle, setup),
        cmocka_unit_test_setup(test_32bit_forms_equal_64bit_references, setup),
        cmocka_unit_test_setup(test_high_speed_unit_timer, setup),
        cmocka_unit_test_setup(test_low_speed_capture, setup),
        cmocka_unit_test_setup(test_switch_with_hysteresis, setup),
        cmocka_unit_test_setup(test_health, setup),
        cmocka_unit_test_setup(test_rehome_waits_for_the_index, setup),
        cmocka_unit_test_setup(test_loss_of_edges_at_speed, setup),
        cmocka_unit_test_setup(test_loss_of_edges_after_unit_timer_reported_zero, setup),
        cmocka_unit_test_setup(test_slow_stop_stays_healthy, setup),
        cmocka_unit_test_setup(test_unwrapped_position_and_index, setup),
        cmocka_unit_test_setup(test_offset_set_and_read, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
