/*
 * The virtual board end to end: `sixphase-sim serve --speed 800` in real time with an encoder
 * slip injected at 1.5 s, spoken to over its pseudo-terminal with the serial protocol and
 * through the host tool sixphase-link (--port). In order: ping; status (READY after the offset
 * calibration, the speed reference from --speed); RUN, speed reached; the tool's profile
 * while running; lambda and controller changed while running; garbage bytes, a bad CRC, an
 * oversize length and a half frame on the line (counted, ignored, the next frame answered); a
 * capture of references, vector and duty (compared with the trace later); the fault (status
 * shows it with the outputs off, the tool's `faults` reads every record in order, the root
 * cause first); clear and restart; the host tool times out when the board stops answering
 * (the server stopped with SIGSTOP). Then: a post-mortem capture of an over-current and its
 * records read in order; `sixphase-link shutdown` stops the server cleanly; --fast pacing,
 * the passive load, --out made, the whole trace written; a slow line; a frozen converter; the
 * torque-limited action set and read back with the tool, a run at the limit stopped by it.
 */
#define _DEFAULT_SOURCE /* cfmakeraw */

#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "capture_signals.h"
#include "drive/drive.h"
#include "link_bytes.h"
#include "sxlink.h"

static pid_t server;
static const char *server_scenario = "fault-encoder-jump";
static const char *server_fault_time = "1.5";
static const char *server_baud = "115200";
static const char *server_load = "0"; /* N*m: serve's own default */
static char trace_dir[] = "/tmp/sixphase-serve-XXXXXX";
static int port = -1;
static char port_path[160];
static sxl_decoder_t dec;

static double now_s(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void sleep_s(double s)
{
    struct timespec d;
    d.tv_sec = (time_t)s;
    d.tv_nsec = (long)((s - (double)d.tv_sec) * 1e9);
    (void)nanosleep(&d, NULL);
}

/* One request and its reply within timeout_s; the reply's result byte is returned (or -1). */
static int request_frame(uint16_t cmd, const uint16_t *payload, uint16_t len, sxl_frame_t *reply)
{
    uint16_t frame[SXL_MAX_FRAME];
    const uint16_t n = sxl_encode(cmd, payload, len, frame, (uint16_t)SXL_MAX_FRAME);
    const double deadline = now_s() + 15.0; /* a loaded host (CI beside other jobs) answers late */
    link_send_bytes(port, frame, n);
    while (now_s() < deadline) {
        struct pollfd p = {port, POLLIN, 0};
        unsigned char c;
        if (poll(&p, 1, 50) > 0 && read(port, &c, 1) == 1 &&
            sxl_decoder_push(&dec, c, reply) == SXL_RX_FRAME &&
            reply->cmd == ((cmd | SXL_REPLY) & 0xFFu)) {
            return (int)reply->payload[0];
        }
    }
    return -1;
}

/* As the host tool sends it: a command that moves the motor in a session armed just before. */
static int request(uint16_t cmd, const uint16_t *payload, uint16_t len, sxl_frame_t *reply)
{
    uint16_t armed[SXL_MAX_PAYLOAD];
    uint16_t i;
    if (!SXL_ARMED_COMMAND(cmd)) {
        return request_frame(cmd, payload, len, reply);
    }
    if (request_frame(SXL_CMD_ARM, NULL, 0u, reply) != (int)SXL_OK) {
        return -1;
    }
    for (i = 0u; i < SXL_TOKEN_BYTES; i++) {
        armed[i] = reply->payload[1u + i];
    }
    for (i = 0u; i < len; i++) {
        armed[SXL_TOKEN_BYTES + i] = payload[i];
    }
    return request_frame(cmd, armed, (uint16_t)(len + SXL_TOKEN_BYTES), reply);
}

static void status(sxl_frame_t *r) { assert_int_equal(request(SXL_CMD_GET_STATUS, NULL, 0, r), 0); }
static uint16_t st_u8(const sxl_frame_t *r, uint16_t at) { return r->payload[1 + at]; }
static int32_t st_i32(const sxl_frame_t *r, uint16_t at)
{
    return sxl_get_i32(&r->payload[1 + at]);
}

/* Control periods of the server's drive per simulated second (serve's default 10 kHz). */
#define SERVE_PERIODS_PER_S 10000.0
/* The host may fall behind real time on a loaded machine: the wall clock only guards against a
 * dead server, with this much slack over the simulated time asked for. */
#define SERVE_WALL_SLACK 20.0

/* Polls the status until pred holds or timeout_s of the drive's own (simulated) time passes,
 * counted by its control periods; false on timeout. */
static bool wait_for(bool (*pred)(const sxl_frame_t *), double timeout_s, sxl_frame_t *r)
{
    const double wall_deadline = now_s() + SERVE_WALL_SLACK * timeout_s + 5.0;
    uint32_t first = 0u;
    bool have_first = false;
    do {
        uint32_t periods;
        status(r);
        if (pred(r)) {
            return true;
        }
        periods = sxl_get_u32(&r->payload[1 + SXL_ST_ISR_COUNT]);
        if (!have_first) {
            first = periods;
            have_first = true;
        } else if ((double)(uint32_t)(periods - first) > timeout_s * SERVE_PERIODS_PER_S) {
            return false;
        }
        sleep_s(0.02);
    } while (now_s() < wall_deadline);
    return false;
}

static bool is_ready(const sxl_frame_t *r) { return st_u8(r, SXL_ST_STATE) == DRIVE_STATE_READY; }
static bool at_800(const sxl_frame_t *r)
{
    const int32_t s = st_i32(r, SXL_ST_SPEED); /* 0.1 r/min */
    return s > 7840 && s < 8160;               /* within 2 % */
}
static bool is_fault(const sxl_frame_t *r) { return st_u8(r, SXL_ST_STATE) == DRIVE_STATE_FAULT; }

static int start_server(void **state)
{
    int out[2];
    char line[160];
    ssize_t n = 0;
    struct termios t;
    (void)state;
    assert_non_null(mkdtemp(trace_dir));
    assert_int_equal(pipe(out), 0);
    server = fork();
    if (server == 0) {
        (void)dup2(out[1], 1);
        execl(SIXPHASE_SIM_EXE, SIXPHASE_SIM_EXE, "serve", "--scenario", server_scenario,
              "--fault-time", server_fault_time, "--duration", "60", "--out", trace_dir, "--baud",
              server_baud, "--speed", "800", "--load", server_load, "--quiet", (char *)NULL);
        _exit(127);
    }
    (void)close(out[1]);
    while (n < (ssize_t)sizeof line - 1 && read(out[0], &line[n], 1) == 1 && line[n] != '\n') {
        n++;
    }
    line[n] = '\0';
    (void)snprintf(port_path, sizeof port_path, "%s", line);
    port = open(port_path, O_RDWR | O_NOCTTY);
    assert_true(port >= 0);
    assert_int_equal(tcgetattr(port, &t), 0);
    cfmakeraw(&t);
    assert_int_equal(tcsetattr(port, TCSANOW, &t), 0);
    sxl_decoder_init(&dec);
    return 0;
}

static int stop_server(void **state)
{
    int st = 0;
    (void)state;
    if (port >= 0) {
        (void)close(port);
    }
    if (server > 0) { /* not reaped by a test already */
        (void)kill(server, SIGCONT);
        (void)kill(server, SIGTERM);
        (void)waitpid(server, &st, 0);
    }
    return 0;
}

static void test_ping_and_ready(void **state)
{
    sxl_frame_t r;
    (void)state;
    assert_int_equal(request(SXL_CMD_PING, NULL, 0, &r), 0);
    assert_int_equal(r.payload[1], SXL_VERSION);
    assert_true(wait_for(is_ready, 2.0, &r)); /* offset calibration: 0.1 s */
    assert_true((st_u8(&r, SXL_ST_FLAGS) & SXL_FLAG_PWM_OFF) != 0u);
}

/* The reference comes from `serve --speed 800`: RUN alone reaches it. */
static void test_run_reaches_speed(void **state)
{
    sxl_frame_t r;
    (void)state;
    status(&r);
    assert_int_equal(st_i32(&r, SXL_ST_SPEED_REF), 8000); /* 0.1 r/min */
    assert_int_equal(request(SXL_CMD_RUN, NULL, 0, &r), 0);
    assert_true(wait_for(at_800, 1.0, &r));
    assert_int_equal(st_u8(&r, SXL_ST_STATE), DRIVE_STATE_RUN);
}

/* A tool command's stdout into out (at most len - 1 bytes); its exit status. */
static int tool(const char *args, char *out, size_t len)
{
    char cmd[400];
    FILE *p;
    size_t n;
    int rc;
    (void)snprintf(cmd, sizeof cmd, "%s --port %s -t 5000 %s", SIXPHASE_LINK_EXE, port_path, args);
    p = popen(cmd, "r");
    assert_non_null(p);
    n = fread(out, 1, len - 1, p);
    out[n] = '\0';
    rc = pclose(p);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

/* `sixphase-link profile` on the running virtual board: the header, the column names and the
 * eight stages, the whole ISR taking time. */
static void test_tool_profile_while_running(void **state)
{
    char out[4096], *line;
    unsigned long last, min, max, mean;
    int lines = 0;
    (void)state;
    assert_int_equal(tool("profile", out, sizeof out), 0);
    for (line = out; (line = strchr(line, '\n')) != NULL; line++) {
        lines++;
    }
    assert_int_equal(lines, 10);
    assert_int_equal(strncmp(out, "period ", 7), 0);
    line = strstr(out, "ISR total");
    assert_non_null(line);
    assert_int_equal(sscanf(line + 9, "%lu %lu %lu %lu", &last, &min, &max, &mean), 4);
    print_message("ISR total: last %lu, min %lu, max %lu, mean %lu host ns\n", last, min, max,
                  mean);
    assert_true(mean > 0u && min <= mean && mean <= max);
}

/* `sixphase-link status` on the virtual board: the status line, then the stack's, which the
 * virtual board does not measure (it has no C28x stack; protocol 6 says so with size 0). */
static void test_tool_status_stack_not_measured(void **state)
{
    char out[2048];
    (void)state;
    assert_int_equal(tool("status", out, sizeof out), 0);
    assert_non_null(strstr(out, "state=RUN "));
    assert_non_null(strstr(out, "\nstack: not measured (virtual board)\n"));
}

static void test_controller_and_lambda_change_while_running(void **state)
{
    uint16_t p[5];
    sxl_frame_t r;
    (void)state;
    p[0] = SXL_CONTROLLER_MPTC13;
    sxl_put_u32(&p[1], 80000u); /* lambda 80 */
    assert_int_equal(request(SXL_CMD_SET_CONTROLLER, p, 5, &r), 0);
    sleep_s(0.05);
    status(&r);
    assert_int_equal(st_u8(&r, SXL_ST_CONTROLLER), SXL_CONTROLLER_MPTC13);
    assert_int_equal(sxl_get_u32(&r.payload[1 + SXL_ST_LAMBDA]), 80000u);
    p[0] = SXL_CONTROLLER_DDC;
    sxl_put_u32(&p[1], 100000u);
    assert_int_equal(request(SXL_CMD_SET_CONTROLLER, p, 5, &r), 0);
    assert_true(wait_for(at_800, 1.0, &r));
}

/* Noise on the line: each kind is counted and ignored, the next frame answered. Each comes
 * after a quiet line (more than the 20 ms after which a partial frame is given up). */
static void test_garbage_is_counted_and_skipped(void **state)
{
    static const uint16_t noise[] = {0x00u, 0xA5u, 0x13u, 0xFFu, 0x5Au};
    static const uint16_t oversize[] = {0xA5u, 0xFEu};
    uint16_t frame[SXL_MAX_FRAME], n;
    sxl_frame_t r;
    uint16_t before, after;
    (void)state;
    status(&r);
    before = sxl_get_u16(&r.payload[1 + SXL_ST_RX_ERRORS]);
    link_send_bytes(port, noise, 5); /* a start with a length whose bytes never come */
    sleep_s(0.05);
    n = sxl_encode(SXL_CMD_PING, NULL, 0, frame, (uint16_t)SXL_MAX_FRAME);
    frame[n - 1] ^= 0x55u; /* bad CRC */
    link_send_bytes(port, frame, n);
    sleep_s(0.05);
    link_send_bytes(port, oversize, 2);
    sleep_s(0.05);
    n = sxl_encode(SXL_CMD_GET_STATUS, NULL, 0, frame, (uint16_t)SXL_MAX_FRAME);
    link_send_bytes(port, frame, (uint16_t)(n / 2)); /* half a frame, then silence */
    sleep_s(0.05);
    assert_int_equal(request(SXL_CMD_PING, NULL, 0, &r), 0);
    status(&r);
    after = sxl_get_u16(&r.payload[1 + SXL_ST_RX_ERRORS]);
    print_message("receive errors %u -> %u\n", before, after);
    assert_true(after >= before + 4u);
}

/* The fault log through `sixphase-link faults`: one line per record the status counts, in
 * order of detection, the root cause first; the log is empty afterwards. */
static void read_records_with_the_tool(unsigned records, const char *root)
{
    char out[8192], *line = out;
    unsigned long period, previous = 0;
    unsigned n = 0;
    sxl_frame_t r;
    assert_int_equal(tool("faults", out, sizeof out), 0);
    print_message("%s", out);
    for (; *line != '\0'; line = strchr(line, '\n') + 1) {
        assert_int_equal(sscanf(line, "period=%lu", &period), 1);
        assert_true(period >= previous);
        if (n == 0) {
            assert_int_equal(strncmp(strstr(line, "faults="), root, strlen(root)), 0);
        }
        previous = period;
        n++;
    }
    assert_int_equal(n, records);
    status(&r);
    assert_int_equal(sxl_get_u16(&r.payload[1 + SXL_ST_RECORDS]), 0u);
}

static void test_fault_records_and_restart(void **state)
{
    sxl_frame_t r;
    unsigned records;
    int tries;
    (void)state;
    assert_true(wait_for(is_fault, 3.0, &r)); /* the slip at 1.5 s */
    assert_int_equal(st_u8(&r, SXL_ST_FAULT), DRIVE_FAULT_ENCODER);
    assert_true((st_u8(&r, SXL_ST_FLAGS) & SXL_FLAG_PWM_OFF) != 0u);
    records = sxl_get_u16(&r.payload[1 + SXL_ST_RECORDS]);
    assert_true(records >= 1u);
    read_records_with_the_tool(records, "faults=ENCODER "); /* the slip alone */
    assert_int_equal(request(SXL_CMD_CLEAR_FAULT, NULL, 0, &r), 0);
    assert_true(wait_for(is_ready, 1.0, &r));
    /* the clear dropped the homing: RUN is refused for the encoder until the coasting rotor
     * has passed the index (at 800 r/min, within 75 ms of simulated time) */
    for (tries = 0; request(SXL_CMD_RUN, NULL, 0, &r) != (int)SXL_OK; tries++) {
        assert_int_equal(r.payload[0], SXL_ERR_REFUSED);
        status(&r);
        assert_int_equal(st_u8(&r, SXL_ST_RUN_REFUSAL), DRIVE_RUN_REFUSED_ENCODER);
        assert_true(tries < 200);
        sleep_s(0.01);
    }
    print_message("RUN accepted after %d refusals for the encoder\n", tries);
    if (!wait_for(at_800, 2.0, &r)) {
        print_error("after the restart: state %u fault %u speed %d\n", st_u8(&r, SXL_ST_STATE),
                    st_u8(&r, SXL_ST_FAULT), st_i32(&r, SXL_ST_SPEED));
        fail();
    }
}

/* The tool's capture: a trigger that never comes times out and leaves the drive's capture
 * stopped, so the next capture runs; `capture stop` ends one a killed tool left armed. */
static void test_tool_capture_timeout_leaves_it_stopped(void **state)
{
    char cmd[400];
    (void)state;
    (void)snprintf(cmd, sizeof cmd,
                   "%s -d %s capture i_a --trigger rising:i_a:70 --wait 1 2>/dev/null >/dev/null",
                   SIXPHASE_LINK_EXE, port_path);
    assert_int_not_equal(system(cmd), 0);
    (void)snprintf(cmd, sizeof cmd, "%s -d %s capture i_a,iq --length 8 > /dev/null",
                   SIXPHASE_LINK_EXE, port_path);
    assert_int_equal(system(cmd), 0);
    (void)snprintf(cmd, sizeof cmd, "%s -d %s capture stop", SIXPHASE_LINK_EXE, port_path);
    assert_int_equal(system(cmd), 0);
}

/* The board stops answering: the host tool gives up after its timeout, non-zero. */
static void test_host_tool_times_out(void **state)
{
    char cmd[400];
    int rc;
    (void)state;
    (void)snprintf(cmd, sizeof cmd, "%s -d %s status > /dev/null", SIXPHASE_LINK_EXE, port_path);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(kill(server, SIGSTOP), 0);
    (void)snprintf(cmd, sizeof cmd, "%s -d %s -t 200 ping 2> /dev/null", SIXPHASE_LINK_EXE,
                   port_path);
    rc = system(cmd);
    assert_int_equal(kill(server, SIGCONT), 0);
    assert_true(WIFEXITED(rc) && WEXITSTATUS(rc) != 0);
}

/* ---- the capture buffer over the link ---- */

static uint32_t cap_first_period;
static int cap_count;
static int16_t cap_samples[4][512];

/* Arms a capture, waits until it is done (within 10 s of a possibly loaded host's time) and reads
 * every channel. */
static void capture(const uint16_t *signals, int n, uint16_t length, uint16_t trigger, uint16_t pre,
                    sxl_frame_t *st)
{
    uint16_t setup[SXL_CA_SIZE] = {0};
    const double deadline = now_s() + 10.0;
    int k;
    setup[SXL_CA_CHANNELS] = (uint16_t)n;
    for (k = 0; k < 4; k++) {
        setup[SXL_CA_SIGNAL + (unsigned)k] = (k < n) ? signals[k] : 0xFFu;
    }
    sxl_put_u16(&setup[SXL_CA_LENGTH], length);
    sxl_put_u16(&setup[SXL_CA_DECIMATION], 1u);
    setup[SXL_CA_TRIGGER] = trigger;
    setup[SXL_CA_PRE] = pre;
    assert_int_equal(request(SXL_CMD_CAPTURE_ARM, setup, SXL_CA_SIZE, st), 0);
    do {
        assert_int_equal(request(SXL_CMD_CAPTURE_STATUS, NULL, 0, st), 0);
        sleep_s(0.02);
    } while (st->payload[1 + SXL_CS_STATE] != 3u && now_s() < deadline);
    assert_int_equal(st->payload[1 + SXL_CS_STATE], 3u);
    cap_count = (int)sxl_get_u16(&st->payload[1 + SXL_CS_COUNT]);
    cap_first_period = sxl_get_u32(&st->payload[1 + SXL_CS_PERIOD]);
    for (k = 0; k < n; k++) {
        int j = 0;
        while (j < cap_count) {
            uint16_t q[3] = {(uint16_t)k, 0u, 0u};
            sxl_frame_t r;
            int m, i;
            sxl_put_u16(&q[1], (uint16_t)j);
            assert_int_equal(request(SXL_CMD_CAPTURE_READ, q, 3, &r), 0);
            m = (int)r.payload[1 + SXL_CR_COUNT];
            assert_true(m > 0);
            for (i = 0; i < m; i++) {
                cap_samples[k][j++] =
                    sxl_get_i16(&r.payload[1u + SXL_CR_SAMPLES + 2u * (unsigned)i]);
            }
        }
    }
}

/* Torque and flux references, vector and duty, 300 periods while running (compared with the
 * trace later). */
static void test_capture_while_running(void **state)
{
    static const uint16_t sig[4] = {CAPTURE_TORQUE_REF, CAPTURE_FLUX_REF, CAPTURE_VECTOR,
                                    CAPTURE_DUTY};
    uint16_t bad[SXL_CA_SIZE] = {0};
    sxl_frame_t st;
    (void)state;
    capture(sig, 4, 300u, 0u, 0u, &st);
    assert_int_equal(cap_count, 300);
    bad[SXL_CA_CHANNELS] = 2u;
    bad[SXL_CA_SIGNAL] = 200u; /* unknown signal */
    assert_int_equal(request(SXL_CMD_CAPTURE_ARM, bad, SXL_CA_SIZE, &st), SXL_ERR_VALUE);
    bad[SXL_CA_SIGNAL] = CAPTURE_I_A;
    bad[SXL_CA_SIGNAL + 1] = CAPTURE_I_B;
    sxl_put_u16(&bad[SXL_CA_LENGTH], 2000u); /* 2 x 2000 > 2048 */
    sxl_put_u16(&bad[SXL_CA_DECIMATION], 1u);
    assert_int_equal(request(SXL_CMD_CAPTURE_ARM, bad, SXL_CA_SIZE, &st), SXL_ERR_NO_ROOM);
    sxl_put_u16(&bad[SXL_CA_LENGTH], 100u);
    sxl_put_u16(&bad[SXL_CA_DECIMATION], 0u);
    assert_int_equal(request(SXL_CMD_CAPTURE_ARM, bad, SXL_CA_SIZE, &st), SXL_ERR_VALUE);
    sxl_put_u16(&bad[SXL_CA_DECIMATION], 1u);
    bad[SXL_CA_TRIGGER] = 2u; /* falling through 0 by i_a: armed, then armed again */
    assert_int_equal(request(SXL_CMD_CAPTURE_ARM, bad, SXL_CA_SIZE, &st), 0);
    assert_int_equal(request(SXL_CMD_CAPTURE_ARM, bad, SXL_CA_SIZE, &st), SXL_ERR_REFUSED);
    assert_int_equal(request(SXL_CMD_CAPTURE_STOP, NULL, 0, &st), 0);
}

/* After the server stopped (its trace.csv complete): the captured references equal the
 * simulator's trace sample for sample within one step of the 16-bit scaling, and the vector
 * and duty the drive commanded equal what the trace shows applied (the vector exactly, the
 * duty within a step and the trace's 4 decimals). The drive's period n is trace row n - 1
 * (the references computed in it) and row n (the command it wrote, applied in the next). */
static void test_capture_matches_the_trace(void **state)
{
    char path[200], line[1024];
    FILE *f;
    long row = -1;
    int matched_refs = 0, matched_cmds = 0;
    const double step_t = CTL_BASE_TORQUE_NM / 8192.0, step_f = CTL_BASE_FLUX_WB / 16384.0;
    const double step_d = 1.0 / 32768.0;
    (void)state;
    assert_true(cap_count > 0);
    (void)snprintf(path, sizeof path, "%s/trace.csv", trace_dir);
    f = fopen(path, "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f)) {
        double v[20];
        int vector;
        const long ref_j = row + 1 - (long)cap_first_period; /* sample of this row's refs */
        const long cmd_j = row - (long)cap_first_period;     /* sample of this row's command */
        row++;
        if (row == 0 || ((ref_j < 0 || ref_j >= cap_count) && (cmd_j < 0 || cmd_j >= cap_count))) {
            continue;
        }
        assert_int_equal(sscanf(line,
                                "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,"
                                "%lf,%lf,%lf,%lf,%*[01],%lf,%d",
                                &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &v[7], &v[8],
                                &v[9], &v[10], &v[11], &v[12], &v[13], &v[14], &v[15], &v[16],
                                &v[17], &v[18], &vector),
                         20);
        if (ref_j >= 0 && ref_j < cap_count) {
            assert_true(fabs(cap_samples[0][ref_j] * step_t - v[16]) <= step_t + 1e-5);
            assert_true(fabs(cap_samples[1][ref_j] * step_f - v[17]) <= step_f + 1e-5);
            matched_refs++;
        }
        if (cmd_j >= 0 && cmd_j < cap_count) {
            if (cap_samples[2][cmd_j] != vector ||
                fabs(cap_samples[3][cmd_j] * step_d - v[18]) > step_d + 0.5e-4 + 1e-9) {
                print_error("sample %ld: vector %d duty %d, trace row %ld: vector %d duty %.4f\n",
                            cmd_j, cap_samples[2][cmd_j], cap_samples[3][cmd_j], row, vector,
                            v[18]);
                fail();
            }
            matched_cmds++;
        }
    }
    fclose(f);
    (void)remove(path);
    (void)rmdir(trace_dir);
    assert_int_equal(matched_refs, cap_count);
    assert_int_equal(matched_cmds, cap_count);
}

/* Post-mortem: a gate of leg A stuck on at 1.0 s; the capture armed on the fault trigger
 * before it holds the currents rising to the 15 A trip, the trip at 90 % of the record. */
static void test_post_mortem_over_current(void **state)
{
    static const uint16_t sig[4] = {CAPTURE_I_A, CAPTURE_I_B, CAPTURE_I_C, CAPTURE_I_D_PHASE};
    const double amp = 10.0 / 4096.0; /* A per sample step: 8 pu / 2^15 */
    uint16_t p[4];
    sxl_frame_t r, st;
    double early = 0.0, at_trip = 0.0;
    int j, k, trig;
    (void)state;
    assert_true(wait_for(is_ready, 2.0, &r));
    sxl_put_u32(p, 15000u);
    assert_int_equal(request(SXL_CMD_SET_SPEED, p, 4, &r), 0);
    assert_int_equal(request(SXL_CMD_RUN, NULL, 0, &r), 0);
    capture(sig, 4, 400u, 3u, 90u, &st);
    trig = (int)sxl_get_u16(&st.payload[1 + SXL_CS_TRIGGER]);
    assert_int_equal(trig, 360);
    for (j = 0; j < cap_count; j++) {
        for (k = 0; k < 4; k++) {
            const double a = fabs(cap_samples[k][j] * amp);
            if (j < 100) {
                early = fmax(early, a);
            } else if (j <= trig) {
                at_trip = fmax(at_trip, a);
            }
        }
    }
    print_message("post-mortem: largest phase current %.1f A early, %.1f A at the trip\n", early,
                  at_trip);
    assert_true(at_trip >= 15.0);
    assert_true(early < at_trip);
    status(&r);
    assert_int_equal(st_u8(&r, SXL_ST_FAULT), DRIVE_FAULT_OVERCURRENT);
}

/* The over-current again after a clear and a restart (the gate is still stuck), then the
 * records over the protocol: as many as the status counts (records survive a clear until
 * read), each telling how many are left, in order of detection, an over-current first; then
 * "none". */
static void test_post_mortem_records_in_order(void **state)
{
    sxl_frame_t r;
    unsigned records, k;
    uint32_t previous = 0u;
    (void)state;
    assert_int_equal(request(SXL_CMD_CLEAR_FAULT, NULL, 0, &r), 0);
    assert_true(wait_for(is_ready, 1.0, &r));
    assert_int_equal(request(SXL_CMD_RUN, NULL, 0, &r), 0);
    assert_true(wait_for(is_fault, 1.0, &r));
    status(&r);
    records = sxl_get_u16(&r.payload[1 + SXL_ST_RECORDS]);
    print_message("%u fault records\n", records);
    assert_true(records >= 2u);
    for (k = 0; k < records; k++) {
        uint32_t period;
        assert_int_equal(request(SXL_CMD_GET_FAULT_RECORD, NULL, 0, &r), 0);
        assert_int_equal(r.payload[1 + SXL_FR_PRESENT], 1u);
        assert_int_equal(sxl_get_u16(&r.payload[1 + SXL_FR_PENDING]), records - 1u - k);
        period = sxl_get_u32(&r.payload[1 + SXL_FR_PERIOD]);
        print_message("record %u: period %lu faults 0x%x\n", k, (unsigned long)period,
                      sxl_get_u16(&r.payload[1 + SXL_FR_FAULTS]));
        assert_true(period > previous);
        previous = period;
        if (k == 0u) {
            assert_true((sxl_get_u16(&r.payload[1 + SXL_FR_FAULTS]) & CTL_FAULT_OVERCURRENT) != 0u);
        }
    }
    assert_int_equal(request(SXL_CMD_GET_FAULT_RECORD, NULL, 0, &r), 0);
    assert_int_equal(r.payload[1 + SXL_FR_PRESENT], 0u);
}

static int start_over_current_server(void **state)
{
    server_scenario = "fault-overcurrent";
    server_fault_time = "1.0";
    (void)snprintf(trace_dir, sizeof trace_dir, "/tmp/sixphase-serve-XXXXXX");
    return start_server(state);
}

/* A frozen converter (the ADC result registers stop at 1.5 s, the drive running under 3 N m,
 * so current flows and the words must move) is never cleared back into RUN:
 * a host that clears and restarts in a loop gets every clear refused and no restart. Before,
 * a clear reset the channels' history: 332 clear-and-run cycles in 6 s, each running 49
 * periods without a current measurement. */
static void test_frozen_adc_cannot_be_cleared_into_run(void **state)
{
    sxl_frame_t r;
    int cycle, refused = 0, restarts = 0;
    unsigned records;
    (void)state;
    assert_true(wait_for(is_ready, 2.0, &r));
    assert_int_equal(request(SXL_CMD_RUN, NULL, 0, &r), 0);
    assert_true(wait_for(is_fault, 3.0, &r));
    status(&r);
    assert_int_equal(st_u8(&r, SXL_ST_FAULT), DRIVE_FAULT_ADC_STUCK);
    records = sxl_get_u16(&r.payload[1 + SXL_ST_RECORDS]); /* a restart would trip anew */
    for (cycle = 0; cycle < 40; cycle++) {
        (void)request(SXL_CMD_CLEAR_FAULT, NULL, 0, &r);
        refused += r.payload[0] != SXL_OK ? 1 : 0;
        (void)request(SXL_CMD_RUN, NULL, 0, &r);
        status(&r);
        restarts += st_u8(&r, SXL_ST_STATE) != DRIVE_STATE_FAULT ? 1 : 0;
    }
    print_message("40 clear-and-run cycles: %d clears refused, %d restarts\n", refused, restarts);
    assert_int_equal(restarts, 0);
    status(&r);
    assert_int_equal(sxl_get_u16(&r.payload[1 + SXL_ST_RECORDS]), records);
    assert_int_equal(st_u8(&r, SXL_ST_STATE), DRIVE_STATE_FAULT);
    assert_int_equal(st_u8(&r, SXL_ST_FAULT), DRIVE_FAULT_ADC_STUCK);
}

static int start_adc_stuck_server(void **state)
{
    server_scenario = "fault-adc-stuck";
    server_fault_time = "1.5"; /* long after RUN, whatever the host's load */
    server_load = "3";
    (void)snprintf(trace_dir, sizeof trace_dir, "/tmp/sixphase-serve-XXXXXX");
    return start_server(state);
}

/* A slow line (57600 baud: 0.58 bytes a period at 10 kHz) still carries every frame. */
static void test_slow_line(void **state)
{
    sxl_frame_t r;
    (void)state;
    assert_int_equal(request(SXL_CMD_PING, NULL, 0, &r), 0);
    assert_true(wait_for(is_ready, 2.0, &r));
}

/* What the drive does when the speed cannot be held, set and read with the host tool (protocol
 * 8): a passive load of 10 N*m above the speed loop's 8.4 N*m limit holds the rotor, the loop
 * sits at its limit. With the default (continue) the drive runs on, flagged; set to stop after
 * 0.2 s over the link, the next run stops by itself, READY without a fault, and the tool says
 * the stop action did it. */
static bool torque_limited(const sxl_frame_t *r)
{
    return (st_u8(r, SXL_ST_FLAGS) & SXL_FLAG_TORQUE_LIMITED) != 0u;
}

static void test_tool_sets_the_torque_limited_action(void **state)
{
    char out[400];
    sxl_frame_t r;
    uint32_t run_at, stopped_at;
    (void)state;
    assert_true(wait_for(is_ready, 2.0, &r));
    assert_int_equal(tool("torque-limited", out, sizeof out), 0);
    assert_string_equal(out, "action=continue stop_after=0.500s stopped=no\n");
    /* the tool's RUN goes out in an armed session (before, a single command was sent bare and
     * the drive answered "not armed") */
    assert_int_equal(tool("run", out, sizeof out), 0);
    assert_string_equal(out, "ok\n");
    assert_true(wait_for(torque_limited, 1.0, &r));
    assert_false(wait_for(is_ready, 0.8, &r)); /* runs on at the limit */
    assert_int_equal(st_u8(&r, SXL_ST_STATE), DRIVE_STATE_RUN);
    assert_int_equal(request(SXL_CMD_STOP, NULL, 0, &r), 0);
    assert_true(wait_for(is_ready, 1.0, &r));

    assert_int_equal(tool("torque-limited stop --stop-after 0.2", out, sizeof out), 0);
    assert_string_equal(out, "ok\n");
    assert_int_equal(tool("torque-limited", out, sizeof out), 0);
    assert_string_equal(out, "action=stop stop_after=0.200s stopped=no\n");
    status(&r);
    run_at = sxl_get_u32(&r.payload[1 + SXL_ST_ISR_COUNT]);
    assert_int_equal(request(SXL_CMD_RUN, NULL, 0, &r), 0);
    assert_true(wait_for(is_ready, 2.0, &r));
    stopped_at = sxl_get_u32(&r.payload[1 + SXL_ST_ISR_COUNT]);
    print_message("stopped by the torque-limited action %.3f s after RUN\n",
                  (double)(uint32_t)(stopped_at - run_at) / SERVE_PERIODS_PER_S);
    /* 0.2 s at the limit, after the phase check at the start of the run */
    assert_true((double)(uint32_t)(stopped_at - run_at) > 0.2 * SERVE_PERIODS_PER_S);
    assert_true((double)(uint32_t)(stopped_at - run_at) < 0.6 * SERVE_PERIODS_PER_S);
    assert_int_equal(st_u8(&r, SXL_ST_FAULT), DRIVE_FAULT_NONE);
    assert_int_equal(tool("torque-limited", out, sizeof out), 0);
    assert_string_equal(out, "action=stop stop_after=0.200s stopped=yes\n");
}

static int start_torque_limited_server(void **state)
{
    server_scenario = "fault-encoder-jump"; /* at 50 s: not within this test */
    server_fault_time = "50";
    server_baud = "115200";
    server_load = "10";
    (void)snprintf(trace_dir, sizeof trace_dir, "/tmp/sixphase-serve-XXXXXX");
    return start_server(state);
}

static int start_slow_line_server(void **state)
{
    server_scenario = "fault-encoder-jump"; /* at 50 s: not within this test */
    server_fault_time = "50";
    server_baud = "57600";
    (void)snprintf(trace_dir, sizeof trace_dir, "/tmp/sixphase-serve-XXXXXX");
    return start_server(state);
}

static int start_shutdown_server(void **state)
{
    server_scenario = "fault-encoder-jump"; /* at 50 s: not within this test */
    server_fault_time = "50";
    (void)snprintf(trace_dir, sizeof trace_dir, "/tmp/sixphase-serve-XXXXXX");
    return start_server(state);
}

static int stop_and_clean(void **state)
{
    char path[200];
    (void)stop_server(state);
    (void)snprintf(path, sizeof path, "%s/trace.csv", trace_dir);
    (void)remove(path);
    (void)rmdir(trace_dir);
    return 0;
}

/* `sixphase-link shutdown`: the virtual board answers, then stops with exit status 0. */
static void test_host_shuts_the_board_down(void **state)
{
    char out[200];
    const double t0 = now_s();
    int st = 0;
    pid_t done = 0;
    (void)state;
    assert_int_equal(tool("shutdown", out, sizeof out), 0);
    assert_string_equal(out, "ok\n");
    while (done == 0 && now_s() - t0 < 3.0) {
        done = waitpid(server, &st, WNOHANG);
        sleep_s(0.01);
    }
    assert_int_equal(done, server);
    server = -1; /* reaped */
    assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 0);
    print_message("the server stopped %.0f ms after the request\n", 1e3 * (now_s() - t0));
}

/* --fast serves as fast as the host can and stops at the duration with a clean exit and the
 * whole trace in an --out directory it made; a load on the idle drive is passive (2 N*m
 * leaves the rotor at rest, not spun backwards into an over-speed); a bad pacing value is
 * refused in one line with exit 2. */
static void test_fast_pacing_and_bad_rate(void **state)
{
    char cmd[400], line[512], last[512] = "", dir[] = "/tmp/sixphase-fast-XXXXXX";
    const double t0 = now_s();
    double peak = 0.0;
    long rows = 0;
    FILE *f;
    int rc;
    (void)state;
    assert_non_null(mkdtemp(dir));
    (void)snprintf(cmd, sizeof cmd,
                   "%s serve --fast --duration 2 --load 2 --out %s/new/dir --quiet > /dev/null",
                   SIXPHASE_SIM_EXE, dir);
    rc = system(cmd);
    assert_true(WIFEXITED(rc) && WEXITSTATUS(rc) == 0);
    assert_true(now_s() - t0 < 5.0);
    (void)snprintf(cmd, sizeof cmd, "%s/new/dir/trace.csv", dir);
    f = fopen(cmd, "r");
    assert_non_null(f);
    while (fgets(line, sizeof line, f)) {
        double t, speed;
        if (rows++ > 0 && sscanf(line, "%lf,%lf", &t, &speed) == 2) {
            peak = fmax(peak, fabs(speed));
            (void)snprintf(last, sizeof last, "%s", line);
        }
    }
    fclose(f);
    print_message("idle rotor under 2 N*m: largest speed %.3f r/min; last row %s", peak, last);
    assert_int_equal(rows, 20001); /* header and every period of the 2 s */
    assert_true(peak < 1.0);
    (void)snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    assert_int_equal(system(cmd), 0);
    (void)snprintf(cmd, sizeof cmd, "%s serve --rate 0 2> /dev/null", SIXPHASE_SIM_EXE);
    rc = system(cmd);
    assert_true(WIFEXITED(rc) && WEXITSTATUS(rc) == 2);
}

/* serve --fast --out stops at --out-limit-mb (it writes about 116 MB/s): one line naming the
 * limit, exit 1, trace.csv up to the last whole row before it (even with --quiet). */
static void test_fast_session_stops_at_the_out_limit(void **state)
{
    char cmd[400], dir[] = "/tmp/sixphase-limit-XXXXXX", path[200], text[2048];
    const double t0 = now_s();
    struct stat st;
    FILE *f;
    size_t n;
    int rc;
    (void)state;
    assert_non_null(mkdtemp(dir));
    (void)snprintf(cmd, sizeof cmd,
                   "%s serve --fast --duration 600 --out %s --out-limit-mb 1 --quiet > /dev/null "
                   "2> %s/err.txt",
                   SIXPHASE_SIM_EXE, dir, dir);
    rc = system(cmd);
    print_message("stopped after %.2f s\n", now_s() - t0);
    assert_true(WIFEXITED(rc) && WEXITSTATUS(rc) == 1);
    assert_true(now_s() - t0 < 30.0);
    (void)snprintf(path, sizeof path, "%s/err.txt", dir);
    f = fopen(path, "r");
    assert_non_null(f);
    n = fread(text, 1, sizeof text - 1, f);
    text[n] = '\0';
    fclose(f);
    print_message("%s", text);
    assert_non_null(strstr(text, "--out-limit-mb 1 (MB)"));
    assert_true(strchr(text, '\n') && strchr(text, '\n')[1] == '\0'); /* one line */
    (void)snprintf(path, sizeof path, "%s/trace.csv", dir);
    assert_int_equal(stat(path, &st), 0);
    assert_true(st.st_size > 900000 && st.st_size <= 1000000);
    f = fopen(path, "r");
    assert_non_null(f);
    assert_int_equal(fseek(f, -1L, SEEK_END), 0);
    assert_int_equal(fgetc(f), '\n');
    fclose(f);
    (void)snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ping_and_ready),
        cmocka_unit_test(test_run_reaches_speed),
        cmocka_unit_test(test_tool_profile_while_running),
        cmocka_unit_test(test_tool_status_stack_not_measured),
        cmocka_unit_test(test_controller_and_lambda_change_while_running),
        cmocka_unit_test(test_garbage_is_counted_and_skipped),
        cmocka_unit_test(test_capture_while_running),
        cmocka_unit_test(test_fault_records_and_restart),
        cmocka_unit_test(test_tool_capture_timeout_leaves_it_stopped),
        cmocka_unit_test(test_host_tool_times_out),
    };
    const struct CMUnitTest after[] = {cmocka_unit_test(test_capture_matches_the_trace)};
    const struct CMUnitTest post_mortem[] = {cmocka_unit_test(test_post_mortem_over_current),
                                             cmocka_unit_test(test_post_mortem_records_in_order)};
    const struct CMUnitTest shutdown[] = {cmocka_unit_test(test_host_shuts_the_board_down)};
    const struct CMUnitTest pacing[] = {cmocka_unit_test(test_fast_pacing_and_bad_rate),
                                        cmocka_unit_test(test_fast_session_stops_at_the_out_limit)};
    const struct CMUnitTest slow[] = {cmocka_unit_test(test_slow_line)};
    const struct CMUnitTest frozen[] = {
        cmocka_unit_test(test_frozen_adc_cannot_be_cleared_into_run)};
    const struct CMUnitTest torque_limit[] = {
        cmocka_unit_test(test_tool_sets_the_torque_limited_action)};
    int failed = cmocka_run_group_tests(tests, start_server, stop_server);
    failed += cmocka_run_group_tests(after, NULL, NULL);
    failed += cmocka_run_group_tests(post_mortem, start_over_current_server, stop_and_clean);
    failed += cmocka_run_group_tests(shutdown, start_shutdown_server, stop_and_clean);
    failed += cmocka_run_group_tests(pacing, NULL, NULL);
    failed += cmocka_run_group_tests(slow, start_slow_line_server, stop_and_clean);
    failed += cmocka_run_group_tests(frozen, start_adc_stuck_server, stop_and_clean);
    failed += cmocka_run_group_tests(torque_limit, start_torque_limited_server, stop_and_clean);
    return failed;
}
