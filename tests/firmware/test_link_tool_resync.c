/*
 * The host tool against a pseudo-terminal standing in for the drive: noise, a malformed
 * frame and a stale reply to an earlier request before the real reply must not make it
 * fail; a drive that never answers must make it time out with a non-zero exit.
 * usage: test_link_tool_resync PATH_TO_SIXPHASE_LINK
 */
#define _XOPEN_SOURCE 600

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

#include "link_bytes.h"
#include "sxlink.h"

static const char *tool;

typedef struct {
    int master;
    pid_t child;
    int out; /* the tool's standard output */
} session_t;

static void start(session_t *s, const char *command)
{
    int pipefd[2];
    const char *slave;
    struct termios tio;
    s->master = posix_openpt(O_RDWR | O_NOCTTY);
    assert_true(s->master >= 0);
    assert_int_equal(grantpt(s->master), 0);
    assert_int_equal(unlockpt(s->master), 0);
    slave = ptsname(s->master);
    assert_non_null(slave);
    /* raw on the drive's side too, so bytes pass unchanged */
    assert_int_equal(tcgetattr(s->master, &tio), 0);
    tio.c_iflag = 0u;
    tio.c_oflag = 0u;
    tio.c_lflag = 0u;
    tio.c_cflag = (tio.c_cflag & ~(tcflag_t)CSIZE) | CS8 | CREAD | CLOCAL;
    tio.c_cc[VMIN] = 1u;
    tio.c_cc[VTIME] = 0u;
    assert_int_equal(tcsetattr(s->master, TCSANOW, &tio), 0);
    assert_int_equal(pipe(pipefd), 0);
    s->child = fork();
    assert_true(s->child >= 0);
    if (s->child == 0) {
        dup2(pipefd[1], 1);
        close(pipefd[0]);
        execl(tool, tool, "-d", slave, "-t", "400", command, (char *)NULL);
        _exit(127);
    }
    close(pipefd[1]);
    s->out = pipefd[0];
}

/* The request the tool sent, decoded. */
static void read_request(const session_t *s, sxl_frame_t *req)
{
    sxl_decoder_t dec;
    sxl_decoder_init(&dec);
    for (;;) {
        unsigned char b;
        struct pollfd p = {s->master, POLLIN, 0};
        assert_true(poll(&p, 1, 2000) > 0);
        assert_int_equal(read(s->master, &b, 1), 1);
        if (sxl_decoder_push(&dec, b, req) == SXL_RX_FRAME) {
            return;
        }
    }
}

static int finish(session_t *s, char *out, size_t cap)
{
    int status;
    ssize_t got;
    size_t have = 0u;
    while ((got = read(s->out, out + have, cap - 1u - have)) > 0) {
        have += (size_t)got;
    }
    out[have] = '\0';
    assert_int_equal(waitpid(s->child, &status, 0), s->child);
    close(s->out);
    close(s->master);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static void test_noise_and_a_stale_reply_are_skipped(void **state)
{
    static const uint16_t noise[6] = {0x00u, SXL_SOF, 0x30u, 0x13u, SXL_SOF, 0xFFu};
    uint16_t status[1u + SXL_ST_SIZE];
    uint16_t bad[SXL_MAX_FRAME];
    uint16_t pong[2] = {SXL_OK, SXL_VERSION};
    sxl_frame_t req;
    session_t s;
    char out[1024];
    uint16_t n;
    (void)state;
    start(&s, "status");
    read_request(&s, &req);
    assert_int_equal(req.cmd, SXL_CMD_GET_STATUS);
    link_send_bytes(s.master, noise, 6u);
    n = sxl_encode(SXL_CMD_GET_STATUS | SXL_REPLY, pong, 2u, bad, SXL_MAX_FRAME);
    bad[n - 1u] ^= 0x5Au; /* a reply with a CRC error */
    link_send_bytes(s.master, bad, n);
    link_send_frame(s.master, SXL_CMD_PING | SXL_REPLY, pong, 2u); /* stale: an earlier request's */
    memset(status, 0, sizeof status);
    status[0] = SXL_OK;
    status[1u + SXL_ST_STATE] = 2u; /* READY */
    sxl_put_u16(&status[1u + SXL_ST_STACK_USED], 812u);
    sxl_put_u16(&status[1u + SXL_ST_STACK_WORDS], 1792u);
    link_send_frame(s.master, SXL_CMD_GET_STATUS | SXL_REPLY, status, (uint16_t)(1u + SXL_ST_SIZE));
    assert_int_equal(finish(&s, out, sizeof out), 0);
    assert_non_null(strstr(out, "state=READY"));
    assert_non_null(strstr(out, "\nstack: 812 of 1792 words used (45 %)\n"));
}

static void test_silent_drive_times_out(void **state)
{
    sxl_frame_t req;
    session_t s;
    char out[256];
    (void)state;
    start(&s, "ping");
    read_request(&s, &req);
    assert_int_equal(req.cmd, SXL_CMD_PING);
    assert_int_equal(finish(&s, out, sizeof out), 1);
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_noise_and_a_stale_reply_are_skipped),
        cmocka_unit_test(test_silent_drive_times_out),
    };
    if (argc != 2) {
        fprintf(stderr, "test_link_tool_resync: usage: test_link_tool_resync SIXPHASE_LINK\n");
        return 2;
    }
    tool = argv[1];
    return cmocka_run_group_tests(tests, NULL, NULL);
}
