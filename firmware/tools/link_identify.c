/*
 * sixphase-link identify: run the drive's commissioning (docs/commissioning.md) over the link.
 *
 *   identify [--steps all|LIST] [--current FRACTION] [--apply] [--partial] [--out FILE] [--wait S]
 *
 * Starts the sequence (COMMISSION_START), polls COMMISSION_STATUS with the progress on a
 * terminal, reads every result (COMMISSION_RESULT) and prints one line per quantity with its
 * 1-sigma uncertainty and quality; --apply asks the drive to take the identified values
 * (COMMISSION_APPLY); --out writes them as the firmware's motor parameter file
 * (motor_params_file.h: OK results only, and the speed gains designed for an identified
 * inertia as the drive's APPLY designs them) once the sequence is done; after a failure it leaves
 * the file as it was, and a file that cannot be written is refused before the start. LIST:
 * phases,encoder,r,ldq,lxy,psi_f,mech (the phase check and, for r..mech, the encoder are
 * required, as the drive requires). FRACTION: the test current as a fraction of rated, 0.1..0.8
 * (default 0.4). Trustworthy or refused (docs/commissioning.md section 3.1): a selected quantity
 * that is not ok (poor, failed) refuses the apply and the file, unless --partial asks for the ok
 * ones; then the drive refuses a set that mixes contradicting values (MIXED_SET), and the file is
 * held to the same rule against the reference machine its missing entries stand for. Exit 0 when
 * the sequence finished with every step done and what was asked for is applied and written, 1 when
 * it failed, was refused or timed out, 2 for bad usage.
 */
#define _DEFAULT_SOURCE /* usleep */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ctl_machine.h"
#include "ctl_params.h"
#include "link_tool.h"
#include "motor_params_file.h"

#define IDENTIFY_POLL_US 200000

typedef struct {
    uint16_t mask;
    uint16_t permille;
    int apply;
    int partial; /* --partial: the ok results of an incomplete sequence are taken */
    const char *out;
    double wait_s;
} identify_request_t;

/* "all" or a comma list of step names into a mask. */
static int identify_steps(const char *list, uint16_t *mask)
{
    char buf[128];
    char *tok, *save = NULL;
    if (strcmp(list, "all") == 0) {
        *mask = SXL_COMM_STEPS_ALL;
        return 0;
    }
    if (strlen(list) >= sizeof buf) {
        return -1;
    }
    strcpy(buf, list);
    *mask = 0u;
    for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        uint16_t k;
        for (k = 0u; k < SXL_COMM_STEP_COUNT; k++) {
            if (strcmp(tok, sxl_comm_step_name(k)) == 0) {
                break;
            }
        }
        if (k == SXL_COMM_STEP_COUNT) {
            return -1;
        }
        *mask = (uint16_t)(*mask | (1u << k));
    }
    return (*mask != 0u) ? 0 : -1;
}

static int identify_parse(int argc, char **argv, identify_request_t *r)
{
    int i;
    r->mask = SXL_COMM_STEPS_ALL;
    r->permille = SXL_COMM_CURRENT_DEFAULT_PERMILLE;
    r->apply = 0;
    r->partial = 0;
    r->out = NULL;
    r->wait_s = 120.0;
    for (i = 0; i < argc; i++) {
        const char *v = (i + 1 < argc) ? argv[i + 1] : NULL;
        double x;
        if (strcmp(argv[i], "--apply") == 0 || strcmp(argv[i], "--partial") == 0) {
            r->apply |= (argv[i][2] == 'a') ? 1 : 0;
            r->partial |= (argv[i][2] == 'p') ? 1 : 0;
            continue;
        }
        if (strcmp(argv[i], "--steps") != 0 && strcmp(argv[i], "--current") != 0 &&
            strcmp(argv[i], "--wait") != 0 && strcmp(argv[i], "--out") != 0) {
            return fail(EXIT_USAGE, "identify: unknown option '%s'", argv[i]);
        }
        if (!v) {
            return fail(EXIT_USAGE, "identify: %s needs a value", argv[i]);
        }
        if (strcmp(argv[i], "--steps") == 0) {
            if (identify_steps(v, &r->mask) != 0) {
                return fail(EXIT_USAGE,
                            "identify: bad --steps '%s' (all or a list of "
                            "phases,encoder,r,ldq,lxy,psi_f,mech)",
                            v);
            }
        } else if (strcmp(argv[i], "--current") == 0) {
            if (!parse_double(v, 0.1, 0.8, &x)) {
                return fail(EXIT_USAGE,
                            "identify: bad --current '%s' (a fraction of rated, "
                            "0.1..0.8)",
                            v);
            }
            r->permille = (uint16_t)floor(x * 1000.0 + 0.5);
        } else if (strcmp(argv[i], "--wait") == 0) {
            if (!parse_double(v, 1.0, 3600.0, &x)) {
                return fail(EXIT_USAGE, "identify: bad --wait '%s' (1..3600 s)", v);
            }
            r->wait_s = x;
        } else {
            r->out = v;
        }
        i++;
    }
    if (!SXL_COMM_STEPS_VALID((unsigned)r->mask)) { /* the drive's own rule */
        return fail(EXIT_USAGE, "identify: --steps needs phases, and encoder before r, ldq, lxy, "
                                "psi_f or mech");
    }
    return 0;
}

int identify_status_reply(const sxl_frame_t *r, uint16_t *st)
{
    if (r->payload[0] != SXL_OK || r->len < 1u + SXL_CT_SIZE) {
        return fail(EXIT_IO, "commissioning status: %s", result_name(r->payload[0]));
    }
    memcpy(st, &r->payload[1], SXL_CT_SIZE * sizeof st[0]);
    return 0;
}

/* One status request; 0 and the fields, or the exit status. */
static int identify_status(int fd, const options_t *o, uint16_t *st)
{
    sxl_frame_t reply;
    const int rc = exchange(fd, o, SXL_CMD_COMMISSION_STATUS, NULL, 0u, &reply);
    return (rc != 0) ? rc : identify_status_reply(&reply, st);
}

/* Polls until the sequence is no longer running; 0 and the last status, or the exit status. */
static int identify_wait(int fd, const options_t *o, double wait_s, uint16_t *st)
{
    const int tty = isatty(2);
    double waited = 0.0;
    int rc;
    for (;;) {
        rc = identify_status(fd, o, st);
        if (rc != 0) {
            return rc;
        }
        if (st[SXL_CT_STATE] != SXL_COMM_STATE_RUNNING) {
            break;
        }
        if (waited > wait_s) {
            return fail(EXIT_IO, "identify: still running after %.0f s (send stop to end it)",
                        wait_s);
        }
        if (tty) {
            fprintf(stderr, "\ridentify: %3u %% (%s)   ", (unsigned)st[SXL_CT_PROGRESS],
                    sxl_comm_step_name(st[SXL_CT_STEP]));
        }
        usleep(IDENTIFY_POLL_US);
        waited += 1e-6 * IDENTIFY_POLL_US;
    }
    if (tty) {
        fprintf(stderr, "\ridentify: %3u %%                    \n", (unsigned)st[SXL_CT_PROGRESS]);
    }
    return 0;
}

int identify_result_reply(const sxl_frame_t *reply, uint16_t q, identify_results_t *res)
{
    motor_params_t *m = &res->m;
    static const motor_param_t file_id[SXL_COMM_QUANTITY_COUNT] = {
        MOTOR_PARAM_COUNT,   MOTOR_PARAM_POLE_PAIRS, MOTOR_PARAM_ENCODER_OFFSET,
        MOTOR_PARAM_R,       MOTOR_PARAM_LD,         MOTOR_PARAM_LQ,
        MOTOR_PARAM_LXY,     MOTOR_PARAM_PSI_F,      MOTOR_PARAM_INERTIA,
        MOTOR_PARAM_FRICTION};
    const uint16_t *r = &reply->payload[1];
    double scale, value, sigma, extra;
    if (reply->payload[0] != SXL_OK) {
        return fail(EXIT_IO, "commissioning result %u: %s", (unsigned)q,
                    result_name(reply->payload[0]));
    }
    if (reply->len < 1u + SXL_CR2_SIZE || r[SXL_CR2_QUANTITY] != q) {
        return fail(EXIT_IO,
                    "commissioning result %u: a short or another quantity's reply (%u bytes)",
                    (unsigned)q, (unsigned)reply->len);
    }
    scale = sxl_comm_quantity_scale(q);
    value = (double)sxl_get_i32(&r[SXL_CR2_VALUE]) / scale;
    sigma = (double)sxl_get_i32(&r[SXL_CR2_SIGMA]) / scale;
    extra = (double)sxl_get_i32(&r[SXL_CR2_EXTRA]) / sxl_comm_quantity_extra_scale(q);
    printf("%-20s %12.6g %-6s +- %-10.3g %-8s %-14s extra %g\n", sxl_comm_quantity_name(q), value,
           sxl_comm_quantity_unit(q), sigma, sxl_comm_quality_name(r[SXL_CR2_QUALITY]),
           sxl_comm_reason_name(r[SXL_CR2_REASON]), extra);
    res->quality[q] = r[SXL_CR2_QUALITY];
    res->reason[q] = r[SXL_CR2_REASON];
    res->value[q] = value;
    res->sigma[q] = sigma;
    if (r[SXL_CR2_QUALITY] == SXL_COMM_QUALITY_OK && file_id[q] != MOTOR_PARAM_COUNT) {
        if (q == SXL_COMM_Q_OFFSET) { /* degrees -> 2^32 per turn */
            const double turns = value / 360.0 - floor(value / 360.0);
            motor_params_set(m, MOTOR_PARAM_ENCODER_OFFSET, floor(turns * 4294967296.0 + 0.5),
                             sigma / 360.0 * 4294967296.0, "ok");
        } else if (q == SXL_COMM_Q_COUNTS) { /* the pole pairs the count confirmed */
            motor_params_set(m, MOTOR_PARAM_POLE_PAIRS, extra, 0.0, "checked by the count");
        } else {
            motor_params_set(m, file_id[q], value, sigma, "ok");
        }
    }
    return 0;
}

/* Reads one result; prints it; keeps it in res. */
static int identify_result(int fd, const options_t *o, uint16_t q, identify_results_t *res)
{
    uint16_t payload[1];
    sxl_frame_t reply;
    int rc;
    payload[0] = q;
    rc = exchange(fd, o, SXL_CMD_COMMISSION_RESULT, payload, 1u, &reply);
    return (rc != 0) ? rc : identify_result_reply(&reply, q, res);
}

int identify_apply_reply(const sxl_frame_t *r)
{
    if (r->payload[0] != SXL_OK || r->len < 1u + SXL_CA2_SIZE) {
        return fail(EXIT_IO, "apply: %s", result_name(r->payload[0]));
    }
    printf("applied: quantities 0x%04X (the drive's parameter set and encoder offset)\n",
           (unsigned)sxl_get_u16(&r->payload[1 + SXL_CA2_APPLIED]));
    return 0;
}

/* APPLY; a refusal names the drive's reason (COMMISSION_STATUS: the last refusal). */
static int identify_apply(int fd, const options_t *o, const identify_request_t *req)
{
    uint16_t st[SXL_CT_SIZE] = {0u};
    sxl_frame_t reply;
    const int rc = exchange(fd, o, SXL_CMD_COMMISSION_APPLY, NULL, 0u, &reply);
    if (rc == 0 && reply.payload[0] == SXL_ERR_REFUSED && identify_status(fd, o, st) == 0) {
        return fail(EXIT_IO, "apply refused: %s (%s)%s%s", sxl_comm_reason_text(st[SXL_CT_REASON]),
                    sxl_comm_reason_name(st[SXL_CT_REASON]), req->out ? "; not written: " : "",
                    req->out ? req->out : "");
    }
    return (rc != 0) ? rc : identify_apply_reply(&reply);
}

/* The speed PI's gains for an identified inertia, as the drive's APPLY designs them
 * (ctl_speed_gains_from_inertia), with the pole pairs the count confirmed or the reference's. */
static void identify_speed_gains(motor_params_t *m)
{
    ctl_params_t p;
    if ((m->have & (1u << MOTOR_PARAM_INERTIA)) == 0u) {
        return;
    }
    ctl_params_default(&p);
    if ((m->have & (1u << MOTOR_PARAM_POLE_PAIRS)) != 0u) {
        p.pole_pairs = (int16_t)m->value[MOTOR_PARAM_POLE_PAIRS];
    }
    p.inertia_kg_m2 = (float)m->value[MOTOR_PARAM_INERTIA];
    ctl_speed_gains_from_inertia(&p);
    motor_params_set(m, MOTOR_PARAM_SPEED_KP, (double)p.speed_kp_nm_per_rad_s, 0.0,
                     "from the inertia");
    motor_params_set(m, MOTOR_PARAM_SPEED_KI, (double)p.speed_ki_nm_per_rad, 0.0,
                     "from the inertia");
}

static int identify_write(const char *path, const motor_params_t *m)
{
    FILE *f = fopen(path, "w");
    int rc;
    if (!f) {
        return fail(EXIT_IO, "cannot write %s", path);
    }
    rc = motor_params_write(f, m, "identified by sixphase-link identify");
    if (fclose(f) != 0 || rc != 0) {
        return fail(EXIT_IO, "cannot write %s", path);
    }
    printf("wrote %s\n", path);
    return 0;
}

/* The identified values against the parameter ranges (MOTOR_PARAM_LIST, the ranges the control
 * core checks) before anything is applied or written: a drive's answer is not trusted. */
static int identify_check(const motor_params_t *m, const identify_request_t *req)
{
    char why[200];
    if (motor_params_check(m, why, sizeof why) == 0) {
        return 0;
    }
    return fail(EXIT_IO, "identify: the drive's %s: refused, nothing applied%s%s", why,
                req->out ? " or written to " : "", req->out ? req->out : "");
}

/* The quantities of the selected steps, bit per quantity. */
static uint16_t identify_selected(uint16_t mask)
{
    uint16_t k, q = 0u;
    for (k = 0u; k < SXL_COMM_STEP_COUNT; k++) {
        q = (uint16_t)(q | (((mask & (1u << k)) != 0u) ? sxl_comm_step_quantities(k) : 0u));
    }
    return q;
}

/* ", name quality (reason)" of quantity q appended to list. */
static void identify_list(char *list, size_t cap, const identify_results_t *res, uint16_t q)
{
    const size_t n = strlen(list);
    (void)snprintf(list + n, cap - n, "%s%s %s (%s)", n ? ", " : "", sxl_comm_quantity_name(q),
                   sxl_comm_quality_name(res->quality[q]), sxl_comm_reason_name(res->reason[q]));
}

/* Without --partial every selected quantity must be ok: 0, or the exit status after one line
 * naming the ones that are not. */
static int identify_complete(const identify_results_t *res, const identify_request_t *req)
{
    const uint16_t selected = identify_selected(req->mask);
    char list[512] = "";
    uint16_t q;
    for (q = 0u; q < SXL_COMM_QUANTITY_COUNT; q++) {
        if ((selected & (1u << q)) != 0u && res->quality[q] != SXL_COMM_QUALITY_OK) {
            identify_list(list, sizeof list, res, q);
        }
    }
    if (list[0] == '\0') {
        return 0;
    }
    return fail(EXIT_IO, "identify: %s: nothing applied%s%s (--partial takes the ok results)", list,
                req->out ? " or written to " : "", req->out ? req->out : "");
}

/* The value a missing entry of the parameter file stands for: the reference machine's. */
static double identify_reference(uint16_t q)
{
    switch (q) {
    case SXL_COMM_Q_R:
        return CTL_MACHINE_R_OHM;
    case SXL_COMM_Q_LD:
        return CTL_MACHINE_LD_H;
    case SXL_COMM_Q_LQ:
        return CTL_MACHINE_LQ_H;
    case SXL_COMM_Q_LXY:
        return CTL_MACHINE_LXY_H;
    default:
        return CTL_MACHINE_PSI_F_WB;
    }
}

/* --partial --out: the file is held to the drive's rule for APPLY (sxlink_commission.h), with
 * the reference machine as the values it keeps. 0, or the exit status after one line. */
static int identify_file_mixed(const identify_results_t *res, const identify_request_t *req)
{
    const uint16_t selected = identify_selected(req->mask) & SXL_COMM_MODEL_QUANTITIES;
    uint16_t got = 0u, unconfirmed = 0u, q;
    char list[512] = "";
    for (q = 0u; q < SXL_COMM_QUANTITY_COUNT; q++) {
        got = (uint16_t)(got | ((res->quality[q] == SXL_COMM_QUALITY_OK) ? (1u << q) : 0u));
    }
    for (q = 0u; q < SXL_COMM_QUANTITY_COUNT; q++) {
        if ((selected & ~got & (1u << q)) == 0u) {
            continue;
        }
        if (res->quality[q] != SXL_COMM_QUALITY_POOR) {
            unconfirmed = (uint16_t)(unconfirmed | (1u << q));
        } else if (SXL_COMM_KEPT_CONTRADICTS(res->value[q], res->sigma[q], identify_reference(q))) {
            identify_list(list, sizeof list, res, q);
            (void)snprintf(list + strlen(list), sizeof list - strlen(list),
                           " against the reference machine's %g", identify_reference(q));
        }
    }
    if (list[0] == '\0' &&
        ((got & SXL_COMM_FLUX_GROUP) == 0u || (unconfirmed & SXL_COMM_FLUX_GROUP) == 0u)) {
        return 0;
    }
    if (list[0] == '\0') {
        (void)snprintf(list, sizeof list, "L_d, L_q and psi_f in part");
    }
    return fail(EXIT_IO, "identify: %s: %s (%s); not written: %s", list,
                sxl_comm_reason_text(SXL_COMM_REASON_MIXED_SET),
                sxl_comm_reason_name(SXL_COMM_REASON_MIXED_SET), req->out);
}

/* The sequence after a start that was accepted: wait, read, check, apply, write. */
static int identify_finish(int fd, const options_t *o, const identify_request_t *req)
{
    uint16_t st[SXL_CT_SIZE];
    identify_results_t res;
    uint16_t q;
    int rc = identify_wait(fd, o, req->wait_s, st);
    const int done = rc == 0 && st[SXL_CT_STATE] == SXL_COMM_STATE_DONE;
    memset(&res, 0, sizeof res);
    motor_params_clear(&res.m);
    if (rc != 0) {
        return rc;
    }
    printf("commissioning %s (%s), %.1f s\n", sxl_comm_state_name(st[SXL_CT_STATE]),
           sxl_comm_reason_name(st[SXL_CT_REASON]),
           (double)sxl_get_u32(&st[SXL_CT_PERIODS]) * 1e-4);
    for (q = 0u; q < SXL_COMM_QUANTITY_COUNT && rc == 0; q++) {
        rc = identify_result(fd, o, q, &res);
    }
    if (rc == 0) {
        identify_speed_gains(&res.m);
        rc = identify_check(&res.m, req);
    }
    if (rc == 0 && done && !req->partial) {
        rc = identify_complete(&res, req);
    }
    if (rc == 0 && done && req->partial && req->out) {
        rc = identify_file_mixed(&res, req);
    }
    if (rc == 0 && req->apply && done) {
        rc = identify_apply(fd, o, req);
    }
    if (rc == 0 && st[SXL_CT_STATE] != SXL_COMM_STATE_DONE) {
        /* an earlier, good file stays: a failed sequence's file would hold nothing useful */
        return fail(EXIT_IO, "commissioning %s: %s%s%s", sxl_comm_state_name(st[SXL_CT_STATE]),
                    sxl_comm_reason_text(st[SXL_CT_REASON]), req->out ? "; not written: " : "",
                    req->out ? req->out : "");
    }
    if (rc == 0 && req->out) {
        rc = identify_write(req->out, &res.m);
    }
    return rc;
}

/* An --out that cannot be written is found before the sequence runs, and an existing file is
 * neither truncated nor removed by the check. */
static int identify_out_writable(const char *path)
{
    const int existed = access(path, F_OK) == 0;
    FILE *probe = fopen(path, "a");
    if (!probe) {
        return fail(EXIT_IO, "cannot write %s", path);
    }
    (void)fclose(probe);
    if (!existed) {
        (void)remove(path);
    }
    return 0;
}

int cmd_identify(const options_t *o, int argc, char **argv)
{
    identify_request_t req;
    uint16_t payload[SXL_CC_SIZE];
    uint16_t st[SXL_CT_SIZE] = {0u};
    sxl_frame_t reply;
    int fd = -1;
    int rc = identify_parse(argc, argv, &req);
    if (rc != 0) {
        return rc;
    }
    payload[SXL_CC_MASK] = req.mask;
    sxl_put_u16(&payload[SXL_CC_CURRENT], req.permille);
    if (o->print_only) {
        return print_request(SXL_CMD_COMMISSION_START, payload, SXL_CC_SIZE);
    }
    rc = req.out ? identify_out_writable(req.out) : 0;
    if (rc == 0) {
        rc = open_port(o, &fd);
    }
    if (rc == 0) {
        rc = exchange(fd, o, SXL_CMD_COMMISSION_START, payload, SXL_CC_SIZE, &reply);
    }
    if (rc == 0 && reply.payload[0] == SXL_ERR_REFUSED && identify_status(fd, o, st) == 0) {
        rc = fail(EXIT_IO, "commissioning refused: %s", sxl_comm_reason_text(st[SXL_CT_REASON]));
    } else if (rc == 0 && reply.payload[0] != SXL_OK) {
        rc = fail(EXIT_IO, "commissioning start: %s", result_name(reply.payload[0]));
    } else if (rc == 0) {
        rc = identify_finish(fd, o, &req);
    }
    if (fd >= 0) {
        close(fd);
    }
    return rc;
}
