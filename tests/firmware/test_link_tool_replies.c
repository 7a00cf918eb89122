/*
 * The host tool checks what a drive answers before it uses it, against a fake drive on a
 * pseudo-terminal that answers with scripted replies (issue 24, item 4):
 * - identify --out: identified values outside the parameter ranges (MOTOR_PARAM_LIST, the ones
 *   the control core checks) are refused in one line naming the value, before anything is
 *   written (R -2147 ohm, L_d 0, 1000 pole pairs); good values are written and read back;
 * - capture: a short status reply, and a read reply that counts more samples than it carries,
 *   end the capture with exit 1 and no CSV instead of reading bytes past the reply; good
 *   replies give the CSV.
 * usage: test_link_tool_replies PATH_TO_SIXPHASE_LINK
 */
#define _DEFAULT_SOURCE   /* cfmakeraw */
#define _XOPEN_SOURCE 600 /* posix_openpt, grantpt, unlockpt, ptsname */

#include <fcntl.h>
#include <poll.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <cmocka.h>

#include "motor_params_file.h"
#include "link_bytes.h"
#include "sxlink.h"
#include "sxlink_commission.h"

static const char *tool;

typedef struct {
    int master, slave; /* the slave held open here too: the line never hangs up between opens */
    pid_t child;
    int err;    /* the tool's standard error */
    int status; /* its wait status once it has exited */
    int exited;
} session_t;

/* The tool on the slave side of a new pseudo-terminal, with args after "-d SLAVE -t 400". */
static void start(session_t *s, const char *const *args)
{
    const char *argv[24];
    int pipefd[2], n = 0, k;
    const char *slave;
    struct termios tio;
    s->master = posix_openpt(O_RDWR | O_NOCTTY);
    assert_true(s->master >= 0);
    assert_int_equal(grantpt(s->master), 0);
    assert_int_equal(unlockpt(s->master), 0);
    slave = ptsname(s->master);
    assert_non_null(slave);
    s->slave = open(slave, O_RDWR | O_NOCTTY);
    assert_true(s->slave >= 0);
    assert_int_equal(tcgetattr(s->slave, &tio), 0);
    cfmakeraw(&tio);
    assert_int_equal(tcsetattr(s->slave, TCSANOW, &tio), 0);
    s->exited = 0;
    argv[n++] = tool;
    argv[n++] = "-d";
    argv[n++] = slave;
    argv[n++] = "-t";
    argv[n++] = "400";
    for (k = 0; args[k]; k++) {
        argv[n++] = args[k];
    }
    argv[n] = NULL;
    assert_int_equal(pipe(pipefd), 0);
    s->child = fork();
    assert_true(s->child >= 0);
    if (s->child == 0) {
        (void)dup2(pipefd[1], 2);
        (void)close(pipefd[0]);
        (void)freopen("/dev/null", "w", stdout);
        execv(tool, (char *const *)(uintptr_t)argv);
        _exit(127);
    }
    close(pipefd[1]);
    s->err = pipefd[0];
}

/* The next request, or 0 once the tool has exited (or after 10 s without one). */
static int next_request(session_t *s, sxl_decoder_t *dec, sxl_frame_t *req)
{
    int idle_ms = 0;
    while (idle_ms < 10000) {
        unsigned char b;
        struct pollfd p = {s->master, POLLIN, 0};
        if (poll(&p, 1, 20) > 0 && read(s->master, &b, 1) == 1) {
            idle_ms = 0;
            if (sxl_decoder_push(dec, b, req) == SXL_RX_FRAME) {
                return 1;
            }
            continue;
        }
        idle_ms += 20;
        if (waitpid(s->child, &s->status, WNOHANG) == s->child) {
            s->exited = 1;
            return 0;
        }
    }
    return 0;
}

static void reply(session_t *s, uint16_t cmd, const uint16_t *payload, uint16_t len)
{
    link_send_frame(s->master, (uint16_t)(cmd | SXL_REPLY), payload, len);
}

/* The tool's exit status and its standard error. */
static int finish(session_t *s, char *err, size_t cap)
{
    int status;
    ssize_t got;
    size_t have = 0u;
    while ((got = read(s->err, err + have, cap - 1u - have)) > 0) {
        have += (size_t)got;
    }
    err[have] = '\0';
    if (s->exited) {
        status = s->status;
    } else {
        assert_int_equal(waitpid(s->child, &status, 0), s->child);
    }
    close(s->err);
    close(s->slave);
    close(s->master);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static void assert_one_line(const char *text, const char *must_contain)
{
    const char *nl = strchr(text, '\n');
    print_message("stderr: %s", text);
    assert_non_null(nl);
    assert_true(nl[1] == '\0');
    assert_non_null(strstr(text, must_contain));
}

/* ---- identify ---- */

typedef struct {
    int32_t value[SXL_COMM_QUANTITY_COUNT]; /* as the reply carries them (SI x scale) */
    int32_t sigma[SXL_COMM_QUANTITY_COUNT];
    uint16_t quality[SXL_COMM_QUANTITY_COUNT];
    uint16_t reason[SXL_COMM_QUANTITY_COUNT];
    int32_t pole_pairs; /* the extra of the count's result */
    int apply_refused;  /* APPLY answered REFUSED, the status' reason MIXED_SET */
    int applies;        /* APPLY requests seen */
} drive_results_t;

/* A machine in range: the reference one's R 2.6 ohm, L_d 35 mH, ... (scales of
 * sxlink_commission.h). */
static void good_results(drive_results_t *d)
{
    d->value[0] = 1000;     /* phases: 1.0 */
    d->value[1] = 3333333;  /* counts per electrical turn */
    d->value[2] = 77000;    /* offset, deg */
    d->value[3] = 2600000;  /* R, ohm */
    d->value[4] = 35000000; /* L_d, H */
    d->value[5] = 62000000; /* L_q */
    d->value[6] = 10000000; /* L_xy */
    d->value[7] = 200000;   /* psi_f, Wb */
    d->value[8] = 10000;    /* inertia, kg m^2 */
    d->value[9] = 10000;    /* friction, N m s/rad */
    d->pole_pairs = 3;
    for (int q = 0; q < (int)SXL_COMM_QUANTITY_COUNT; q++) {
        d->sigma[q] = 10;
        d->quality[q] = SXL_COMM_QUALITY_OK;
        d->reason[q] = SXL_COMM_REASON_NONE;
    }
    d->apply_refused = 0;
    d->applies = 0;
}

static void identify_answer(session_t *s, const sxl_frame_t *req, drive_results_t *d)
{
    uint16_t p[1u + SXL_CR2_SIZE];
    memset(p, 0, sizeof p);
    p[0] = SXL_OK;
    switch (req->cmd) {
    case SXL_CMD_ARM: /* the session COMMISSION_START needs (protocol 7) */
        sxl_put_u32(&p[1], 0x1234ABCDu);
        reply(s, req->cmd, p, 1u + SXL_TOKEN_BYTES);
        break;
    case SXL_CMD_COMMISSION_START:
        assert_int_equal(sxl_get_u32(req->payload), 0x1234ABCDu);
        reply(s, req->cmd, p, 1u);
        break;
    case SXL_CMD_COMMISSION_STATUS:
        p[1u + SXL_CT_STATE] = SXL_COMM_STATE_DONE;
        p[1u + SXL_CT_PROGRESS] = 100u;
        p[1u + SXL_CT_REASON] = d->applies ? SXL_COMM_REASON_MIXED_SET : SXL_COMM_REASON_NONE;
        reply(s, req->cmd, p, 1u + SXL_CT_SIZE);
        break;
    case SXL_CMD_COMMISSION_RESULT: {
        const uint16_t q = req->payload[0];
        assert_true(q < SXL_COMM_QUANTITY_COUNT);
        p[1u + SXL_CR2_QUANTITY] = q;
        p[1u + SXL_CR2_QUALITY] = d->quality[q];
        p[1u + SXL_CR2_REASON] = d->reason[q];
        sxl_put_i32(&p[1u + SXL_CR2_VALUE], d->value[q]);
        sxl_put_i32(&p[1u + SXL_CR2_SIGMA], d->sigma[q]);
        sxl_put_i32(&p[1u + SXL_CR2_EXTRA], q == 1u ? d->pole_pairs : 0);
        reply(s, req->cmd, p, 1u + SXL_CR2_SIZE);
        break;
    }
    default: /* APPLY: nothing applied, or refused */
        d->applies++;
        p[0] = d->apply_refused ? SXL_ERR_REFUSED : SXL_OK;
        reply(s, req->cmd, p, d->apply_refused ? 1u : 1u + SXL_CA2_SIZE);
        break;
    }
}

/* identify with args against a drive with these results; the tool's exit status. */
static int identify_args(drive_results_t *d, const char *const *args, char *err, size_t cap)
{
    sxl_decoder_t dec;
    sxl_frame_t req;
    session_t s;
    sxl_decoder_init(&dec);
    start(&s, args);
    while (next_request(&s, &dec, &req)) {
        identify_answer(&s, &req, d);
    }
    return finish(&s, err, cap);
}

/* identify --out PATH against a drive with these results; the tool's exit status. */
static int identify_with(drive_results_t *d, const char *path, char *err, size_t cap)
{
    const char *const args[] = {"identify", "--out", path, NULL};
    return identify_args(d, args, err, cap);
}

static void test_identify_refuses_values_out_of_range(void **state)
{
    char path[] = "/tmp/sixphase-replies-XXXXXX", file[64], err[1024];
    drive_results_t d;
    motor_params_t m;
    int k;
    (void)state;
    assert_non_null(mkdtemp(path));
    (void)snprintf(file, sizeof file, "%s/motor.h", path);
    for (k = 0; k < 3; k++) {
        static const char *const named[3] = {"R_OHM -2147.48 ohm", "LD_H 0 H", "POLE_PAIRS 1000"};
        good_results(&d);
        if (k == 0) {
            d.value[3] = INT32_MIN; /* -2147.483648 ohm */
        } else if (k == 1) {
            d.value[4] = 0;
        } else {
            d.pole_pairs = 1000;
        }
        assert_int_equal(identify_with(&d, file, err, sizeof err), 1);
        assert_one_line(err, named[k]);
        assert_int_not_equal(access(file, F_OK), 0); /* nothing written */
    }
    good_results(&d); /* the fake drive itself: good values are written and read back */
    assert_int_equal(identify_with(&d, file, err, sizeof err), 0);
    assert_int_equal(motor_params_read(file, &m, err, sizeof err), 0);
    assert_true(m.value[MOTOR_PARAM_R] > 2.59 && m.value[MOTOR_PARAM_R] < 2.61);
    assert_true(m.value[MOTOR_PARAM_POLE_PAIRS] == 3.0);
    assert_int_equal(remove(file), 0);
    assert_int_equal(rmdir(path), 0);
}

/* Issue 25's weak-magnet machine: every step done, psi_f poor (no_speed) at 0.0672 Wb. Before,
 * identify --apply --out exited 0, applied the rest and wrote a file without psi_f, L_d and
 * L_q (the reference 0.225 Wb kept). Now: refused in one line naming it, no APPLY sent, no
 * file; --partial asks for the ok ones, and then a file that would keep 0.225 Wb against the
 * measured 0.0672 is refused (mixed_set), as is an APPLY the drive refuses; a poor psi_f that
 * agrees with the reference is left out and the rest written. */
static void test_identify_incomplete_is_refused(void **state)
{
    char path[] = "/tmp/sixphase-replies-XXXXXX", file[64], err[1024];
    drive_results_t d;
    motor_params_t m;
    (void)state;
    assert_non_null(mkdtemp(path));
    (void)snprintf(file, sizeof file, "%s/motor.h", path);
    {
        const char *const strict[] = {"identify", "--apply", "--out", file, NULL};
        const char *const partial[] = {"identify", "--apply", "--partial", "--out", file, NULL};
        const char *const partial_apply[] = {"identify", "--partial", "--apply", NULL};
        const char *const plain[] = {"identify", NULL};
        good_results(&d);
        d.value[7] = 67200; /* psi_f 0.0672 Wb +- 0.0009, poor */
        d.sigma[7] = 900;
        d.quality[7] = SXL_COMM_QUALITY_POOR;
        d.reason[7] = SXL_COMM_REASON_NO_SPEED;
        assert_int_equal(identify_args(&d, strict, err, sizeof err), 1);
        assert_one_line(err, "psi_f poor (no_speed): nothing applied or written");
        assert_int_equal(d.applies, 0);
        assert_int_not_equal(access(file, F_OK), 0);
        assert_int_equal(identify_args(&d, plain, err, sizeof err), 1); /* no option: exit 1 */
        assert_one_line(err, "psi_f poor (no_speed)");
        assert_int_equal(identify_args(&d, partial, err, sizeof err), 1);
        assert_one_line(err, "(mixed_set); not written");
        assert_int_equal(d.applies, 0);
        assert_int_not_equal(access(file, F_OK), 0);
        d.apply_refused = 1; /* the drive's own rule */
        assert_int_equal(identify_args(&d, partial_apply, err, sizeof err), 1);
        assert_one_line(err, "apply refused: ");
        assert_non_null(strstr(err, "(mixed_set)"));
        assert_int_equal(d.applies, 1);
        good_results(&d); /* poor, but within 3 sigma of 0.225 Wb: no contradiction */
        d.value[7] = 224500;
        d.sigma[7] = 1000;
        d.quality[7] = SXL_COMM_QUALITY_POOR;
        d.reason[7] = SXL_COMM_REASON_NO_SPEED;
        assert_int_equal(identify_args(&d, partial, err, sizeof err), 0);
        assert_int_equal(d.applies, 1);
    }
    assert_int_equal(motor_params_read(file, &m, err, sizeof err), 0);
    assert_true((m.have & (1u << MOTOR_PARAM_PSI_F)) == 0u);
    assert_true((m.have & (1u << MOTOR_PARAM_LD)) != 0u);
    assert_int_equal(remove(file), 0);
    assert_int_equal(rmdir(path), 0);
}

/* ---- capture ---- */

typedef enum { CAP_GOOD, CAP_SHORT_STATUS, CAP_SHORT_READ } capture_fault_t;

#define CAP_COUNT 30u

static void capture_answer(session_t *s, const sxl_frame_t *req, capture_fault_t fault,
                           uint16_t *setup)
{
    uint16_t p[SXL_MAX_PAYLOAD];
    uint16_t k, first, n;
    memset(p, 0, sizeof p);
    p[0] = SXL_OK;
    switch (req->cmd) {
    case SXL_CMD_CAPTURE_ARM:
        memcpy(setup, req->payload, SXL_CA_SIZE * sizeof setup[0]);
        reply(s, req->cmd, p, 1u);
        break;
    case SXL_CMD_CAPTURE_STATUS:
        p[1u + SXL_CS_STATE] = 3u;
        p[1u + SXL_CS_CHANNELS] = setup[SXL_CA_CHANNELS];
        for (k = 0u; k < 4u; k++) {
            p[1u + SXL_CS_SIGNAL + k] = setup[SXL_CA_SIGNAL + k];
        }
        sxl_put_u16(&p[1u + SXL_CS_LENGTH], (uint16_t)CAP_COUNT);
        sxl_put_u16(&p[1u + SXL_CS_DECIMATION], 1u);
        sxl_put_u16(&p[1u + SXL_CS_COUNT], (uint16_t)CAP_COUNT);
        sxl_put_u16(&p[1u + SXL_CS_TRIGGER], 3u);
        sxl_put_u32(&p[1u + SXL_CS_TS_NS], 100000u);
        /* short: the state and the channel count only, the rest missing */
        reply(s, req->cmd, p, (fault == CAP_SHORT_STATUS) ? 3u : 1u + SXL_CS_SIZE);
        break;
    case SXL_CMD_CAPTURE_READ:
        first = sxl_get_u16(&req->payload[1]);
        n = (uint16_t)((CAP_COUNT - first < SXL_CR_MAX) ? CAP_COUNT - first : SXL_CR_MAX);
        p[1u + SXL_CR_COUNT] = n;
        for (k = 0u; k < n; k++) {
            sxl_put_u16(&p[1u + SXL_CR_SAMPLES + 2u * k], (uint16_t)(100u + first + k));
        }
        /* short: counts n samples, carries 5 */
        reply(s, req->cmd, p,
              (uint16_t)(1u + SXL_CR_SAMPLES + 2u * ((fault == CAP_SHORT_READ) ? 5u : n)));
        break;
    default:
        reply(s, req->cmd, p, 1u);
        break;
    }
}

static int capture_with(capture_fault_t fault, const char *csv, char *err, size_t cap)
{
    const char *const args[] = {"capture", "i_a", "--length", "30", "--out", csv, NULL};
    uint16_t setup[SXL_CA_SIZE] = {0u};
    sxl_decoder_t dec;
    sxl_frame_t req;
    session_t s;
    sxl_decoder_init(&dec);
    start(&s, args);
    while (next_request(&s, &dec, &req)) {
        capture_answer(&s, &req, fault, setup);
    }
    return finish(&s, err, cap);
}

static void test_capture_checks_reply_lengths(void **state)
{
    char path[] = "/tmp/sixphase-replies-XXXXXX", csv[64], err[1024], line[256];
    FILE *f;
    int rows = 0;
    (void)state;
    assert_non_null(mkdtemp(path));
    (void)snprintf(csv, sizeof csv, "%s/cap.csv", path);
    assert_int_equal(capture_with(CAP_SHORT_STATUS, csv, err, sizeof err), 1);
    assert_one_line(err, "capture status: short reply (3 bytes");
    assert_int_not_equal(access(csv, F_OK), 0);
    assert_int_equal(capture_with(CAP_SHORT_READ, csv, err, sizeof err), 1);
    assert_one_line(err, "capture read at sample 0: short or malformed reply (12 bytes)");
    assert_int_not_equal(access(csv, F_OK), 0);
    assert_int_equal(capture_with(CAP_GOOD, csv, err, sizeof err), 0); /* the fake drive itself */
    f = fopen(csv, "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f)) {
        rows++;
    }
    fclose(f);
    assert_int_equal(rows, 1 + (int)CAP_COUNT);
    assert_int_equal(remove(csv), 0);
    assert_int_equal(rmdir(path), 0);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_identify_refuses_values_out_of_range),
        cmocka_unit_test(test_identify_incomplete_is_refused),
        cmocka_unit_test(test_capture_checks_reply_lengths),
    };
    if (argc != 2) {
        fprintf(stderr, "test_link_tool_replies: usage: test_link_tool_replies SIXPHASE_LINK\n");
        return 2;
    }
    tool = argv[1];
    return cmocka_run_group_tests(tests, NULL, NULL);
}
