/* Command-line parsing, see cli.h. */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sim_cli_usage(FILE *f)
{
    fprintf(
        f,
        "usage:\n"
        "  sixphase-sim run --controller {ddc,mptc49,mptc13} --scenario "
        "{steady,load-step,accel,reversal,fault-<name>}\n"
        "                   [--lambda X] [--fs HZ] [--speed RPM] [--load NM] [--duration S]\n"
        "                   [--arith {fixed,float}] [--seed N] [--out DIR]\n"
        "                   [--ddc-direction {flux-error,xy-table}] [--duty-levels N] "
        "[--ddc-torque-guard | --paper-ddc]\n"
        "                   [--flux-ref {constant,mtpa}] [--torque-limit NM] [--trip-current A] "
        "[--lxy H] [--vdc V] [--dead-time S]\n"
        "                   [--psi5 WB] [--psi7 WB] [--plant-step S] [--fine-rate HZ]\n"
        "                   [--no-dead-time] [--no-harmonics] [--no-adc-offset] [--no-adc-gain]\n"
        "                   [--no-adc-noise] [--no-encoder-quant] [--ideal] [--no-fine] "
        "[--no-protect]\n"
        "                   [--quiet]\n"
        "                   [--fault-time S]\n"
        "  sixphase-sim reproduce --out DIR [--jobs N] [--quiet]\n"
        "fault scenarios (rated operation, the fault at 0.25 s; docs/faults.md):\n");
    {
        int k;
        for (k = 1; k < (int)SIM_FAULT_COUNT; k++) {
            const sim_fault_info_t *fi = sim_fault_info((sim_fault_t)k);
            fprintf(f, "  fault-%-16s %s\n", fi->name, fi->injection);
        }
    }
}

static int cli_bad(char *err, size_t len, const char *opt, const char *val)
{
    (void)snprintf(err, len, "bad value for %s: '%s'", opt, val ? val : "(missing)");
    return -1;
}

static int cli_num(const char *s, double lo, double hi, double *out)
{
    char *end;
    double v;
    if (!s || !*s) {
        return -1;
    }
    errno = 0;
    v = strtod(s, &end);
    if (errno != 0 || *end != '\0' || !(v == v) || v < lo || v > hi) {
        return -1;
    }
    *out = v;
    return 0;
}

static int cli_int(const char *s, long lo, long hi, long *out)
{
    char *end;
    long v;
    if (!s || !*s) {
        return -1;
    }
    errno = 0;
    v = strtol(s, &end, 10);
    if (errno != 0 || *end != '\0' || v < lo || v > hi) {
        return -1;
    }
    *out = v;
    return 0;
}

static int cli_u64(const char *s, uint64_t *out)
{
    char *end;
    unsigned long long v;
    if (!s || !*s || s[0] == '-' || s[0] == '+') {
        return -1;
    }
    errno = 0;
    v = strtoull(s, &end, 10);
    if (errno != 0 || *end != '\0') {
        return -1;
    }
    *out = (uint64_t)v;
    return 0;
}

static void cli_defaults(sim_cli_t *o)
{
    memset(o, 0, sizeof *o);
    sim_config_default(&o->cfg);
    o->jobs = 2;
}

static int cli_parse(int argc, char **argv, sim_cli_t *o, char *err, size_t len, int reproduce)
{
    int i;
    int have_ctl = 0, have_scen = 0;
    sim_config_t *c = &o->cfg;
    plant_params_t *p = &c->plant;
    cli_defaults(o);
    for (i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *v = (i + 1 < argc) ? argv[i + 1] : NULL;
        long n;
        /* flags without a value */
        if (strcmp(a, "--quiet") == 0) {
            o->quiet = 1;
            continue;
        }
        if (!reproduce) {
            if (strcmp(a, "--no-dead-time") == 0) {
                p->dead_time_on = false;
                continue;
            }
            if (strcmp(a, "--no-harmonics") == 0) {
                p->harmonics_on = false;
                continue;
            }
            if (strcmp(a, "--no-adc-offset") == 0) {
                p->adc_offset_on = false;
                continue;
            }
            if (strcmp(a, "--no-adc-gain") == 0) {
                p->adc_gain_on = false;
                continue;
            }
            if (strcmp(a, "--no-adc-noise") == 0) {
                p->adc_noise_on = false;
                continue;
            }
            if (strcmp(a, "--no-encoder-quant") == 0) {
                p->encoder_quant_on = false;
                continue;
            }
            if (strcmp(a, "--ideal") == 0) {
                p->dead_time_on = p->harmonics_on = p->adc_offset_on = p->adc_gain_on = false;
                p->adc_noise_on = p->encoder_quant_on = false;
                continue;
            }
            if (strcmp(a, "--ddc-torque-guard") == 0) {
                c->ddc_torque_guard = 1;
                continue;
            }
            if (strcmp(a, "--paper-ddc") == 0) { /* the paper's duty search: no torque guard */
                c->ddc_torque_guard = 0;
                continue;
            }
            if (strcmp(a, "--no-protect") == 0) {
                c->protect = false;
                continue;
            }
            if (strcmp(a, "--no-fine") == 0) {
                c->write_fine = false;
                continue;
            }
        }
        /* options with a value */
        if (strcmp(a, "--out") == 0) {
            if (!v || !*v || strlen(v) > 900) {
                return cli_bad(err, len, a, v);
            }
            c->out_dir = v;
        } else if (reproduce && strcmp(a, "--jobs") == 0) {
            if (cli_int(v, 1, 64, &n) != 0) {
                return cli_bad(err, len, a, v);
            }
            o->jobs = (int)n;
        } else if (reproduce) {
            (void)snprintf(err, len, "unknown option '%s'", a);
            return -1;
        } else if (strcmp(a, "--controller") == 0) {
            if (v && strcmp(v, "ddc") == 0) {
                c->controller = 0;
            } else if (v && strcmp(v, "mptc49") == 0) {
                c->controller = 1;
            } else if (v && strcmp(v, "mptc13") == 0) {
                c->controller = 2;
            } else {
                return cli_bad(err, len, a, v);
            }
            have_ctl = 1;
        } else if (strcmp(a, "--scenario") == 0) {
            if (v && strcmp(v, "steady") == 0) {
                c->scenario = SIM_SCEN_STEADY;
            } else if (v && strcmp(v, "load-step") == 0) {
                c->scenario = SIM_SCEN_LOAD_STEP;
            } else if (v && strcmp(v, "accel") == 0) {
                c->scenario = SIM_SCEN_ACCEL;
            } else if (v && strcmp(v, "reversal") == 0) {
                c->scenario = SIM_SCEN_REVERSAL;
            } else if (sim_fault_from_scenario(v) != SIM_FAULT_NONE) {
                c->scenario = SIM_SCEN_STEADY; /* rated operation, then the fault */
                c->fault = sim_fault_from_scenario(v);
            } else {
                return cli_bad(err, len, a, v);
            }
            have_scen = 1;
        } else if (strcmp(a, "--arith") == 0) {
            if (v && strcmp(v, "fixed") == 0) {
                c->arith = 0;
            } else if (v && strcmp(v, "float") == 0) {
                c->arith = 1;
            } else {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--ddc-direction") == 0) {
            if (v && strcmp(v, "flux-error") == 0) {
                c->ddc_direction = 0;
            } else if (v && strcmp(v, "xy-table") == 0) {
                c->ddc_direction = 1;
            } else {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--flux-ref") == 0) {
            if (v && strcmp(v, "constant") == 0) {
                c->flux_ref_mode = 0;
            } else if (v && strcmp(v, "mtpa") == 0) {
                c->flux_ref_mode = 1;
            } else {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--lambda") == 0) {
            if (cli_num(v, 0.0, 10000.0, &c->lambda) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--fs") == 0) {
            if (cli_num(v, 1000.0, 100000.0, &c->fs_hz) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--speed") == 0) {
            if (cli_num(v, -6000.0, 6000.0, &c->speed_rpm) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--load") == 0) {
            if (cli_num(v, -50.0, 50.0, &c->load_nm) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--duration") == 0) {
            if (cli_num(v, 0.01, 100.0, &c->duration_s) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--seed") == 0) {
            if (cli_u64(v, &c->seed) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--duty-levels") == 0) {
            if (cli_int(v, 2, 11, &n) != 0) {
                return cli_bad(err, len, a, v);
            }
            c->duty_levels = (int)n;
        } else if (strcmp(a, "--torque-limit") == 0) {
            if (cli_num(v, 0.1, 50.0, &c->torque_limit_nm) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--fault-time") == 0) {
            if (cli_num(v, 0.001, 100.0, &c->fault_time_s) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--trip-current") == 0) {
            if (cli_num(v, 0.1, 1000.0, &c->trip_current_a) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--fine-rate") == 0) {
            if (cli_num(v, 10000.0, 10e6, &c->fine_rate_hz) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--lxy") == 0) {
            if (cli_num(v, 1e-4, 1.0, &p->lxy_h) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--vdc") == 0) {
            if (cli_num(v, 50.0, 1500.0, &p->vdc_v) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--dead-time") == 0) {
            if (cli_num(v, 0.0, 20e-6, &p->dead_time_s) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--psi5") == 0) {
            if (cli_num(v, 0.0, 0.1, &p->psi5_wb) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--psi7") == 0) {
            if (cli_num(v, 0.0, 0.1, &p->psi7_wb) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else if (strcmp(a, "--plant-step") == 0) {
            if (cli_num(v, 1e-7, 1e-4, &p->max_step_s) != 0) {
                return cli_bad(err, len, a, v);
            }
        } else {
            (void)snprintf(err, len, "unknown option '%s'", a);
            return -1;
        }
        i++; /* consumed the value */
    }
    if (!reproduce && !have_ctl) {
        (void)snprintf(err, len, "missing --controller");
        return -1;
    }
    if (!reproduce && !have_scen) {
        (void)snprintf(err, len, "missing --scenario");
        return -1;
    }
    if (c->fault_time_s > 0.0 && c->fault == SIM_FAULT_NONE) {
        (void)snprintf(err, len, "--fault-time needs a fault-<name> scenario");
        return -1;
    }
    if (c->fault != SIM_FAULT_NONE && sim_fault_at_power_up(c->fault) && c->fault_time_s > 0.0) {
        (void)snprintf(err, len, "fault-%s is present from power-up: no --fault-time",
                       sim_fault_info(c->fault)->name);
        return -1;
    }
    if (reproduce && !c->out_dir) {
        (void)snprintf(err, len, "missing --out");
        return -1;
    }
    {
        const char *chk = plant_params_check(p);
        if (chk[0] != '\0') {
            (void)snprintf(err, len, "%s", chk);
            return -1;
        }
    }
    return 0;
}

int sim_cli_parse_run(int argc, char **argv, sim_cli_t *out, char *err, size_t err_len)
{
    return cli_parse(argc, argv, out, err, err_len, 0);
}

int sim_cli_parse_reproduce(int argc, char **argv, sim_cli_t *out, char *err, size_t err_len)
{
    return cli_parse(argc, argv, out, err, err_len, 1);
}
