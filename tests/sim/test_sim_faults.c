/*
 * Fault injection regression (issue 6): for every fault scenario the firmware's drive,
 * running the paper's operating point through the simulator, must report the expected
 * fault code, within the latency bound of fault_inject.c, with every leg off from the
 * detection on and the detection in the fault log. Healthy runs must not trip. The trace row of
 * every period the plant runs with the outputs off shows them off (vector 0, duty 0), the trip
 * period included, for every fault and the hardware trip, and so does trace.csv.
 */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "run/sim.h"
#include "sim_run_checked.h"
#include "sxlink.h"

static void check_fault(sim_fault_t kind, int arith)
{
    const sim_fault_info_t *fi = sim_fault_info(kind);
    const double ts = 1e-4;
    sim_config_t c;
    sim_result_t r;
    sim_config_default(&c);
    c.arith = arith;
    c.fault = kind;
    sim_run_quiet(&c, &r);
    print_message("fault-%-16s %-5s code %2d mask 0x%04x detect %6.1f ms (bound %5.1f) outputs_off "
                  "%d records %d\n",
                  fi->name, r.arith, r.fault, r.faults_latched, r.fault_detect_ms,
                  fi->detect_bound_ms, r.outputs_off ? 1 : 0, r.fault_records);
    assert_int_equal(r.fault, fi->expected_fault);
    assert_true(r.fault_detect_ms >= 0.0); /* never before the injection */
    assert_true(r.fault_detect_ms <= fi->detect_bound_ms);
    assert_true(r.outputs_off);
    assert_true(r.fault_records >= 1);
    assert_true(r.have_first_record);
    assert_int_not_equal(r.first_record.faults, 0u);
    assert_true((r.first_record.faults & r.faults_latched) == r.first_record.faults);
    if (!sim_fault_at_power_up(kind)) {
        /* the oldest record is the detecting period */
        assert_true(r.first_record_t_s > r.fault_time_s - 0.5 * ts);
        assert_true(r.first_record_t_s < r.fault_time_s + 0.5 * ts);
    }
}

static void test_each_fault_fixed(void **state)
{
    int k;
    (void)state;
    for (k = 1; k < (int)SIM_FAULT_COUNT; k++) {
        check_fault((sim_fault_t)k, 0);
    }
}

static void test_each_fault_float(void **state)
{
    int k;
    (void)state;
    for (k = 1; k < (int)SIM_FAULT_COUNT; k++) {
        check_fault((sim_fault_t)k, 1);
    }
}

/* The later injection time moves the detection with it (the latency is the drive's). */
static void test_injection_time_is_honoured(void **state)
{
    sim_config_t c;
    sim_result_t r;
    (void)state;
    sim_config_default(&c);
    c.fault = SIM_FAULT_DC_OVERVOLTAGE;
    c.fault_time_s = 0.3;
    sim_run_quiet(&c, &r);
    assert_true(r.fault_inject_s > 0.2999 && r.fault_inject_s < 0.3001);
    assert_true(r.fault_time_s >= 0.3 && r.fault_time_s < 0.301);
}

/* No fault without an injection: the product's controllers at the paper's operating points
 * with the default protection, with and without the plant's non-idealities. */
static void test_healthy_runs_do_not_trip(void **state)
{
    static const sim_scenario_t scen[4] = {SIM_SCEN_STEADY, SIM_SCEN_LOAD_STEP, SIM_SCEN_ACCEL,
                                           SIM_SCEN_REVERSAL};
    int controller, s, ideal;
    (void)state;
    for (controller = 0; controller <= 2; controller += 2) { /* DDC and MPTC-13 */
        for (s = 0; s < 4; s++) {
            for (ideal = 0; ideal <= 1; ideal++) {
                sim_config_t c;
                sim_result_t r;
                sim_config_default(&c);
                c.controller = controller;
                c.scenario = scen[s];
                if (ideal) {
                    c.plant.dead_time_on = c.plant.harmonics_on = false;
                    c.plant.adc_offset_on = c.plant.adc_gain_on = c.plant.adc_noise_on = false;
                    c.plant.encoder_quant_on = false;
                }
                sim_run_quiet(&c, &r);
                if (r.fault != 0) {
                    print_error("%s %s ideal=%d: fault %d mask 0x%04x at %.4f s\n", r.controller,
                                r.scenario, ideal, r.fault, r.faults_latched, r.fault_time_s);
                }
                assert_int_equal(r.fault, 0);
                assert_int_equal(r.faults_latched, 0u);
                assert_int_equal(r.fault_records, 0);
            }
        }
    }
}

/* MPTC-49 overloads the drive (x-y currents, peaks near 30 A): with the protection at its
 * limits the firmware stops it, outputs off, within a few milliseconds of the start. */
static void test_mptc49_trips_the_protection(void **state)
{
    sim_config_t c;
    sim_result_t r;
    (void)state;
    sim_config_default(&c);
    c.controller = 1;
    sim_run_quiet(&c, &r);
    print_message("mptc49 with protection: code %d mask 0x%04x at %.2f ms\n", r.fault,
                  r.faults_latched, 1e3 * r.fault_time_s);
    assert_int_not_equal(r.fault, 0);
    assert_true(r.fault_time_s >= 0.0 && r.fault_time_s < 0.02);
    assert_true(r.outputs_off);
}

/* fault-encoder-jump, then a clear and a run request every period: the clear drops the homing,
 * so RUN is refused for the encoder until the shaft has passed the index (mechanical angle 0),
 * then accepted; the index re-homed the slipped count, so the drive runs on without a fault. */
#define REHOME_TWO_PI 6.28318530717958647692

typedef struct {
    const sim_ctl_ops_t *ops;
    double pole_pairs;
    double theta_m; /* latest plant sample of the mechanical angle (analysis window) */
    int phase;      /* 0 until FAULT, 1 clear sent, 2 READY: asking to run, 3 running */
    double turn_at_clear;
    bool index_passed; /* a whole mechanical turn crossed since the clear */
    double t_index, t_run;
    unsigned refused_seen; /* the drive's refusal count when the last request was sent */
    unsigned refused_before_index, refused_after_index, refusal_reason_other;
    bool faulted_again;
} rehome_probe_t;

static void rehome_fine(void *ctx, const sim_fine_row_t *row)
{
    rehome_probe_t *p = ctx;
    p->theta_m = row->theta_e_unwrapped / p->pole_pairs;
    if (p->phase >= 1 && !p->index_passed &&
        floor(p->theta_m / REHOME_TWO_PI) != p->turn_at_clear) {
        p->index_passed = true;
        p->t_index = row->t;
    }
}

static void rehome_period(void *ctx, const sim_trace_row_t *row, const sim_period_input_t *in)
{
    rehome_probe_t *p = ctx;
    sim_ctl_status_t st;
    (void)in;
    p->ops->status(&st);
    if (p->phase == 0 && st.faulted) {
        p->phase = 1;
        p->turn_at_clear = floor(p->theta_m / REHOME_TWO_PI);
        p->ops->request_clear();
    } else if (p->phase >= 1 && p->phase <= 2 && st.ready) {
        if (p->phase == 2 && st.run_refused != p->refused_seen) {
            p->refused_before_index += p->index_passed ? 0u : 1u;
            p->refused_after_index += p->index_passed ? 1u : 0u;
            if (strcmp(sxl_run_refusal_name((uint16_t)st.run_refusal), "ENCODER") != 0) {
                p->refusal_reason_other++;
            }
        }
        p->refused_seen = st.run_refused;
        p->phase = 2;
        p->ops->request_run();
    } else if (p->phase == 2 && st.running) {
        p->phase = 3;
        p->t_run = row->t;
    } else if (p->phase == 3 && st.faulted) {
        p->faulted_again = true;
    }
}

static void test_encoder_clear_waits_for_the_index(void **state)
{
    int arith;
    (void)state;
    for (arith = 0; arith <= 1; arith++) {
        rehome_probe_t p;
        sim_observer_t ob = {&p, rehome_period, rehome_fine};
        sim_config_t c;
        sim_result_t r;
        memset(&p, 0, sizeof p);
        sim_config_default(&c);
        c.arith = arith;
        c.fault = SIM_FAULT_ENCODER_JUMP;
        c.observer = &ob;
        p.ops = arith ? &simflt_sim_ctl_ops_float : &sim_ctl_ops_fixed;
        p.pole_pairs = (double)c.plant.pole_pairs;
        sim_run_quiet(&c, &r);
        print_message("%s: refused %u times before the index (at %.4f s), %u after; running "
                      "from %.4f s\n",
                      r.arith, p.refused_before_index, p.t_index, p.refused_after_index, p.t_run);
        assert_int_equal(p.phase, 3);
        assert_true(p.index_passed);
        assert_true(p.refused_before_index > 0u);
        assert_int_equal(p.refused_after_index, 0u);
        assert_int_equal(p.refusal_reason_other, 0u);
        assert_true(p.t_run >= p.t_index && p.t_run < p.t_index + 3e-4); /* at the next ISR */
        assert_false(p.faulted_again);
    }
}

/* Periods the plant ran with the outputs off, and those whose trace row showed a command. */
typedef struct {
    long off, off_with_command;
    double first_off_s, first_shown_s;
} off_probe_t;

static void off_period(void *ctx, const sim_trace_row_t *row, const sim_period_input_t *in)
{
    off_probe_t *p = (off_probe_t *)ctx;
    if (!in->forced_off) {
        return;
    }
    if (p->off++ == 0) {
        p->first_off_s = row->t;
    }
    if (row->vector != 0 || row->duty != 0.0) {
        if (p->off_with_command++ == 0) {
            p->first_shown_s = row->t;
        }
    }
}

/* Every fault (and the hardware comparator): from the trip period on the rows show the outputs
 * off (before: the trip row showed the command of the period before). */
static void test_trace_shows_outputs_off_from_the_trip(void **state)
{
    int k;
    (void)state;
    for (k = 0; k <= (int)SIM_FAULT_COUNT; k++) {
        off_probe_t p;
        sim_observer_t ob = {&p, off_period, NULL};
        sim_config_t c;
        sim_result_t r;
        memset(&p, 0, sizeof p);
        sim_config_default(&c);
        c.observer = &ob;
        if (k == (int)SIM_FAULT_COUNT) {
            c.trip_current_a = 12.0; /* below the software limit: the comparator trips first */
            c.fault = SIM_FAULT_OVERCURRENT;
        } else if (k == 0 || sim_fault_at_power_up((sim_fault_t)k)) {
            continue; /* no fault, or none after RUN */
        } else {
            c.fault = (sim_fault_t)k;
        }
        sim_run_quiet(&c, &r);
        print_message("%-16s outputs off in %ld periods from %.4f s, %ld of them showing a "
                      "command (first %.4f s)\n",
                      k == (int)SIM_FAULT_COUNT ? "hardware trip" : sim_fault_info(c.fault)->name,
                      p.off, p.first_off_s, p.off_with_command, p.first_shown_s);
        assert_true(p.off > 0);
        assert_int_equal(p.off_with_command, 0);
    }
}

/* trace.csv's row of the trip period: legs 000000, duty 0, vector 0. */
static void test_trace_csv_trip_row(void **state)
{
    char dir[] = "/tmp/sixphase-trip-XXXXXX", path[200], line[512], cmd[240];
    sim_config_t c;
    sim_result_t r;
    char err[200] = "";
    FILE *f;
    int rows_checked = 0;
    (void)state;
    assert_non_null(mkdtemp(dir));
    sim_config_default(&c);
    c.fault = SIM_FAULT_OVERCURRENT;
    c.out_dir = dir;
    c.write_fine = false;
    assert_int_equal(sim_run(&c, &r, err, sizeof err), 0);
    assert_true(r.fault_time_s > 0.0);
    (void)snprintf(path, sizeof path, "%s/trace.csv", dir);
    f = fopen(path, "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f)) {
        const char *legs = line;
        int comma;
        if (line[0] == 't' || atof(line) < r.fault_time_s - 0.5e-4) {
            continue;
        }
        for (comma = 0; comma < 18 && legs; comma++) {
            legs = strchr(legs, ',') ? strchr(legs, ',') + 1 : NULL;
        }
        assert_non_null(legs);
        if (rows_checked == 0) {
            print_message("trip row: %s", line);
        }
        assert_int_equal(strncmp(legs, "000000,0.0000,0\n", 16), 0);
        rows_checked++;
    }
    fclose(f);
    assert_true(rows_checked > 100);
    (void)snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_each_fault_fixed),
        cmocka_unit_test(test_each_fault_float),
        cmocka_unit_test(test_injection_time_is_honoured),
        cmocka_unit_test(test_healthy_runs_do_not_trip),
        cmocka_unit_test(test_mptc49_trips_the_protection),
        cmocka_unit_test(test_encoder_clear_waits_for_the_index),
        cmocka_unit_test(test_trace_shows_outputs_off_from_the_trip),
        cmocka_unit_test(test_trace_csv_trip_row),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
