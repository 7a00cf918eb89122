/*
 * The virtual board end to end: `sixphase-sim serve` in real time with an encoder slip
 * injected at 1.5 s, spoken to over its pseudo-terminal with the serial protocol, and once
 * through the host tool sixphase-link. In order: ping; status (READY after the offset
 * calibration); speed reference and RUN, speed reached; lambda and controller changed while
 * running; garbage bytes, a bad CRC, an oversize length and a half frame on the line (counted,
 * ignored, the next frame answered); the fault (status shows it with the outputs off, the
 * records read in order, the root cause first); clear and restart; the host tool times out
 * when the board stops answering (the server stopped with SIGSTOP).
 */
#define _DEFAULT_SOURCE /* cfmakeraw */

#include <fcntl.h>
#include <poll.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include "drive.h"
#include "sxlink.h"

static pid_t server;
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

static void send_bytes(const uint16_t *b, uint16_t n)
{
    uint16_t i;
    for (i = 0; i < n; i++) {
        const unsigned char c = (unsigned char)b[i];
        assert_int_equal(write(port, &c, 1), 1);
    }
}

/* One request and its reply within timeout_s; the reply's result byte is returned (or -1). */
static int request(uint16_t cmd, const uint16_t *payload, uint16_t len, sxl_frame_t *reply)
{
    uint16_t frame[SXL_MAX_FRAME];
    const uint16_t n = sxl_encode(cmd, payload, len, frame, (uint16_t)SXL_MAX_FRAME);
    const double deadline = now_s() + 1.0;
    send_bytes(frame, n);
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

static void status(sxl_frame_t *r) { assert_int_equal(request(SXL_CMD_GET_STATUS, NULL, 0, r), 0); }
static uint16_t st_u8(const sxl_frame_t *r, uint16_t at) { return r->payload[1 + at]; }
static int32_t st_i32(const sxl_frame_t *r, uint16_t at)
{
    return sxl_get_i32(&r->payload[1 + at]);
}

/* Polls the status until pred holds or timeout_s passes; false on timeout. */
static bool wait_for(bool (*pred)(const sxl_frame_t *), double timeout_s, sxl_frame_t *r)
{
    const double deadline = now_s() + timeout_s;
    do {
        status(r);
        if (pred(r)) {
            return true;
        }
        sleep_s(0.02);
    } while (now_s() < deadline);
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
    assert_int_equal(pipe(out), 0);
    server = fork();
    if (server == 0) {
        (void)dup2(out[1], 1);
        execl(SIXPHASE_SIM_EXE, SIXPHASE_SIM_EXE, "serve", "--scenario", "fault-encoder-jump",
              "--fault-time", "1.5", "--duration", "60", "--quiet", (char *)NULL);
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
    (void)kill(server, SIGCONT);
    (void)kill(server, SIGTERM);
    (void)waitpid(server, &st, 0);
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

static void test_run_reaches_speed(void **state)
{
    uint16_t p[4];
    sxl_frame_t r;
    (void)state;
    sxl_put_u32(p, 8000u); /* 800 r/min */
    assert_int_equal(request(SXL_CMD_SET_SPEED, p, 4, &r), 0);
    assert_int_equal(request(SXL_CMD_RUN, NULL, 0, &r), 0);
    assert_true(wait_for(at_800, 1.0, &r));
    assert_int_equal(st_u8(&r, SXL_ST_STATE), DRIVE_STATE_RUN);
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
    send_bytes(noise, 5); /* a start with a length whose bytes never come */
    sleep_s(0.05);
    n = sxl_encode(SXL_CMD_PING, NULL, 0, frame, (uint16_t)SXL_MAX_FRAME);
    frame[n - 1] ^= 0x55u; /* bad CRC */
    send_bytes(frame, n);
    sleep_s(0.05);
    send_bytes(oversize, 2);
    sleep_s(0.05);
    n = sxl_encode(SXL_CMD_GET_STATUS, NULL, 0, frame, (uint16_t)SXL_MAX_FRAME);
    send_bytes(frame, (uint16_t)(n / 2)); /* half a frame, then silence */
    sleep_s(0.05);
    assert_int_equal(request(SXL_CMD_PING, NULL, 0, &r), 0);
    status(&r);
    after = sxl_get_u16(&r.payload[1 + SXL_ST_RX_ERRORS]);
    print_message("receive errors %u -> %u\n", before, after);
    assert_true(after >= before + 4u);
}

static void test_fault_records_and_restart(void **state)
{
    sxl_frame_t r;
    (void)state;
    assert_true(wait_for(is_fault, 3.0, &r)); /* the slip at 1.5 s */
    assert_int_equal(st_u8(&r, SXL_ST_FAULT), DRIVE_FAULT_ENCODER);
    assert_true((st_u8(&r, SXL_ST_FLAGS) & SXL_FLAG_PWM_OFF) != 0u);
    assert_true(sxl_get_u16(&r.payload[1 + SXL_ST_RECORDS]) >= 1u);
    assert_int_equal(request(SXL_CMD_GET_FAULT_RECORD, NULL, 0, &r), 0);
    assert_int_equal(r.payload[1 + SXL_FR_PRESENT], 1u);
    assert_int_equal(sxl_get_u16(&r.payload[1 + SXL_FR_FAULTS]), CTL_FAULT_ENCODER); /* root */
    while (request(SXL_CMD_GET_FAULT_RECORD, NULL, 0, &r) == 0 && r.payload[1 + SXL_FR_PRESENT]) {
    }
    assert_int_equal(request(SXL_CMD_CLEAR_FAULT, NULL, 0, &r), 0);
    assert_true(wait_for(is_ready, 1.0, &r));
    assert_int_equal(request(SXL_CMD_RUN, NULL, 0, &r), 0);
    assert_true(wait_for(at_800, 2.0, &r));
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ping_and_ready),
        cmocka_unit_test(test_run_reaches_speed),
        cmocka_unit_test(test_controller_and_lambda_change_while_running),
        cmocka_unit_test(test_garbage_is_counted_and_skipped),
        cmocka_unit_test(test_fault_records_and_restart),
        cmocka_unit_test(test_host_tool_times_out),
    };
    return cmocka_run_group_tests(tests, start_server, stop_server);
}
