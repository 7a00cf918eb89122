/* The byte stream to a PIL target, see pil_port.h. */
#define _DEFAULT_SOURCE /* cfmakeraw, kill */

#include "pil_port.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#ifndef SIXPHASE_PIL_IMAGE_DIR
#define SIXPHASE_PIL_IMAGE_DIR "" /* the build left the PIL image out (no arm-none-eabi-gcc) */
#endif

#define PIL_QEMU_START_MS 20000 /* for QEMU to name its pseudo-terminal */

static const struct {
    long baud;
    speed_t code;
} pil_bauds[] = {{9600, B9600},       {19200, B19200},     {38400, B38400},
                 {57600, B57600},     {115200, B115200},   {230400, B230400},
                 {460800, B460800},   {921600, B921600},   {1000000, B1000000},
                 {1500000, B1500000}, {2000000, B2000000}, {3000000, B3000000}};
#define PIL_BAUDS (sizeof pil_bauds / sizeof pil_bauds[0])

static int port_fail(char *err, size_t len, const char *what, const char *detail)
{
    (void)snprintf(err, len, "%s%s", what, detail);
    return -1;
}

/* "serial:PATH[@BAUD]": the path into path, the speed's code into code. */
static int parse_serial(const char *target, char *path, size_t cap, speed_t *code, char *err,
                        size_t len)
{
    const char *spec = target + strlen("serial:");
    const char *at = strrchr(spec, '@');
    const size_t n = at ? (size_t)(at - spec) : strlen(spec);
    long baud = 921600; /* the F28335 PIL image's (firmware/pil/f28335_pil_main.c) */
    size_t k;
    if (n == 0u || n >= cap) {
        return port_fail(err, len, "--pil serial:PATH[@BAUD]: the path is missing or too long", "");
    }
    memcpy(path, spec, n);
    path[n] = '\0';
    if (at) {
        char *end = NULL;
        baud = strtol(at + 1, &end, 10);
        if (!end || *end != '\0' || end == at + 1) {
            return port_fail(err, len, "--pil serial:PATH@BAUD: BAUD is not a number: ", at + 1);
        }
    }
    for (k = 0u; k < PIL_BAUDS; k++) {
        if (pil_bauds[k].baud == baud) {
            *code = pil_bauds[k].code;
            return 0;
        }
    }
    return port_fail(err, len,
                     "--pil serial: BAUD must be one of 9600, 19200, 38400, 57600, 115200, 230400, "
                     "460800, 921600, 1000000, 1500000, 2000000, 3000000",
                     "");
}

int pil_port_check_spec(const char *target, char *err, size_t len)
{
    char path[256];
    speed_t code;
    if (strcmp(target, "qemu") == 0) {
        return 0;
    }
    if (strncmp(target, "serial:", 7) == 0) {
        return parse_serial(target, path, sizeof path, &code, err, len);
    }
    return port_fail(err, len, "--pil takes qemu or serial:PATH[@BAUD], not ", target);
}

/* Raw 8N1 at speed, reads that return at once. */
static int port_raw(int fd, speed_t speed)
{
    struct termios t;
    if (tcgetattr(fd, &t) != 0) {
        return -1;
    }
    cfmakeraw(&t);
    t.c_cflag |= (tcflag_t)(CLOCAL | CREAD);
    t.c_cflag &= (tcflag_t)~CRTSCTS;
    t.c_cc[VMIN] = 0;
    t.c_cc[VTIME] = 0;
    if (cfsetispeed(&t, speed) != 0 || cfsetospeed(&t, speed) != 0 ||
        tcsetattr(fd, TCSANOW, &t) != 0) {
        return -1;
    }
    return tcflush(fd, TCIOFLUSH);
}

static int port_open_line(pil_port_t *p, speed_t speed, char *err, size_t len)
{
    p->fd = open(p->path, O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (p->fd < 0) {
        (void)snprintf(err, len, "--pil: cannot open %s: %s", p->path, strerror(errno));
        return -1;
    }
    if (port_raw(p->fd, speed) != 0) {
        (void)snprintf(err, len, "--pil: %s is not a serial line: %s", p->path, strerror(errno));
        close(p->fd);
        p->fd = -1;
        return -1;
    }
    return 0;
}

/* QEMU's "char device redirected to /dev/pts/N" from its output (out_fd), within the time. */
static int qemu_pty(int out_fd, char *path, size_t cap)
{
    char text[1024];
    size_t n = 0u;
    struct timespec t0;
    (void)clock_gettime(CLOCK_MONOTONIC, &t0);
    for (;;) {
        struct pollfd pfd = {out_fd, POLLIN, 0};
        struct timespec now;
        const char *m;
        ssize_t got;
        (void)clock_gettime(CLOCK_MONOTONIC, &now);
        if ((now.tv_sec - t0.tv_sec) * 1000 + (now.tv_nsec - t0.tv_nsec) / 1000000 >
            PIL_QEMU_START_MS) {
            return -1;
        }
        if (poll(&pfd, 1, 100) <= 0) {
            continue;
        }
        got = read(out_fd, text + n, sizeof text - 1u - n);
        if (got <= 0) {
            return -1; /* QEMU ended */
        }
        n += (size_t)got;
        text[n] = '\0';
        m = strstr(text, "redirected to ");
        if (m && cap > 0u && sscanf(m, "redirected to %255s", path) == 1) {
            return 0;
        }
    }
}

static int port_spawn_qemu(pil_port_t *p, const char *image, char *err, size_t len)
{
    int out[2];
    char icount[32];
    const char *qemu =
        getenv("SIXPHASE_PIL_QEMU") ? getenv("SIXPHASE_PIL_QEMU") : "qemu-system-arm";
    (void)snprintf(icount, sizeof icount, "shift=%u", p->icount_shift);
    if (pipe(out) != 0) {
        return port_fail(err, len, "--pil qemu: no pipe: ", strerror(errno));
    }
    p->child = fork();
    if (p->child == 0) {
        /* the emulator ends with the simulator, however it ends (a signal, a test's timeout) */
        (void)prctl(PR_SET_PDEATHSIG, SIGTERM);
        if (getppid() == 1) {
            _exit(1);
        }
        (void)dup2(out[1], STDOUT_FILENO);
        (void)dup2(out[1], STDERR_FILENO);
        (void)close(out[0]);
        execlp(qemu, qemu, "-machine", "mps2-an386", "-nographic", "-monitor", "none", "-serial",
               "pty", "-icount", icount, "-kernel", image, (char *)NULL);
        (void)fprintf(stderr, "exec failed\n");
        _exit(127);
    }
    (void)close(out[1]);
    if (p->child < 0 || qemu_pty(out[0], p->path, sizeof p->path) != 0) {
        (void)close(out[0]);
        if (p->child < 0) {
            p->child = 0;
        }
        pil_port_close(p);
        return port_fail(err, len,
                         "--pil qemu: QEMU did not start with a pseudo-terminal (is "
                         "qemu-system-arm installed? tools/install-deps.sh): ",
                         qemu);
    }
    p->child_fd = out[0]; /* drained by pil_port_read: a full pipe would stop QEMU */
    return 0;
}

static int port_open_qemu(pil_port_t *p, const char *arith, char *err, size_t len)
{
    const char *dir = getenv("SIXPHASE_PIL_IMAGE_DIR") ? getenv("SIXPHASE_PIL_IMAGE_DIR")
                                                       : SIXPHASE_PIL_IMAGE_DIR;
    char image[1024];
    if (dir[0] == '\0') {
        return port_fail(err, len,
                         "--pil qemu: this sixphase-sim was built without the PIL image "
                         "(arm-none-eabi-gcc was not found at configure time)",
                         "");
    }
    (void)snprintf(image, sizeof image, "%s/pil-mps2-%s.elf", dir, arith);
    if (access(image, R_OK) != 0) {
        return port_fail(err, len, "--pil qemu: the PIL image is missing: ", image);
    }
    p->emulated = 1;
    p->icount_shift = PIL_PORT_ICOUNT_SHIFT;
    if (port_spawn_qemu(p, image, err, len) != 0) {
        return -1;
    }
    return port_open_line(p, B115200, err, len); /* a pseudo-terminal: the speed is notional */
}

int pil_port_open(pil_port_t *p, const char *target, const char *arith, char *err, size_t len)
{
    speed_t speed = B115200;
    memset(p, 0, sizeof *p);
    p->fd = -1;
    p->child_fd = -1;
    if (pil_port_check_spec(target, err, len) != 0) {
        return -1;
    }
    if (strcmp(target, "qemu") == 0) {
        return port_open_qemu(p, arith, err, len);
    }
    (void)parse_serial(target, p->path, sizeof p->path, &speed, err, len);
    return port_open_line(p, speed, err, len);
}

int pil_port_write(pil_port_t *p, const uint16_t *bytes, uint16_t n)
{
    uint8_t buf[256];
    size_t done = 0u;
    uint16_t k;
    if (n > sizeof buf) {
        return -1;
    }
    for (k = 0u; k < n; k++) {
        buf[k] = (uint8_t)bytes[k];
    }
    while (done < n) {
        const ssize_t w = write(p->fd, buf + done, n - done);
        if (w < 0 && errno != EINTR && errno != EAGAIN) {
            return -1;
        }
        if (w > 0) {
            done += (size_t)w;
        }
    }
    return 0;
}

/* What the emulator printed, its last words kept. */
static void port_drain_child(pil_port_t *p)
{
    char text[256];
    const ssize_t got = read(p->child_fd, text, sizeof text - 1u);
    if (got <= 0) {
        (void)close(p->child_fd);
        p->child_fd = -1;
        return;
    }
    text[got] = '\0';
    (void)snprintf(p->child_said, sizeof p->child_said, "%s", text);
}

int pil_port_read(pil_port_t *p, uint8_t *buf, size_t cap, int timeout_ms)
{
    struct pollfd pfd[2] = {{p->fd, POLLIN, 0}, {p->child_fd, POLLIN, 0}};
    const int r = poll(pfd, (p->child_fd >= 0) ? 2u : 1u, timeout_ms);
    ssize_t got;
    if (r < 0) {
        return (errno == EINTR) ? 0 : -1;
    }
    if (p->child_fd >= 0 && (pfd[1].revents & (POLLIN | POLLHUP)) != 0) {
        port_drain_child(p);
    }
    if ((pfd[0].revents & (POLLIN | POLLHUP | POLLERR)) == 0) {
        return 0;
    }
    got = read(p->fd, buf, cap);
    if (got < 0) {
        return (errno == EINTR || errno == EAGAIN) ? 0 : -1;
    }
    if (got == 0 && (pfd[0].revents & (POLLHUP | POLLERR)) != 0) {
        return -1;
    }
    return (int)got;
}

void pil_port_close(pil_port_t *p)
{
    if (p->fd >= 0) {
        (void)close(p->fd);
        p->fd = -1;
    }
    if (p->child_fd >= 0) {
        (void)close(p->child_fd);
        p->child_fd = -1;
    }
    if (p->child > 0) {
        (void)kill(p->child, SIGTERM);
        (void)waitpid(p->child, NULL, 0);
        p->child = 0;
    }
}
