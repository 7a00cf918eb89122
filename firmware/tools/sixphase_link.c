/*
 * sixphase-link: talk to the drive over its serial port (SCI-A protocol,
 * docs/serial-protocol.md).
 *
 *   sixphase-link [-d DEVICE | --port DEVICE] [-b BAUD] [-t MS] [-n] COMMAND [ARGS]
 *
 * The commands are one list, link_cli below (sixphase-link --help prints it). -n prints the
 * request frame in hex instead of sending it.
 * Every error is one line on stderr and a non-zero exit status
 * (2: usage, 1: device or protocol).
 */
#define _DEFAULT_SOURCE 1

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "ctl_params.h"
#include "decimal_arg.h"
#include "link_tool.h"
#include "sxlink.h"

#define LINK_CONTROLLER_NAME(id, number, name, what) " " name
#define LINK_CONTROLLER_NAMES CTL_CONTROLLER_LIST(LINK_CONTROLLER_NAME)

/* Bound on the records "faults" reads, so a misbehaving device cannot loop it forever
 * (the drive's log holds 8). */
#define FAULTS_MAX_RECORDS 256
const char *result_name(uint16_t result) { return sxl_result_name(result); }

int fail(int code, const char *fmt, ...)
{
    va_list ap;
    fputs("sixphase-link: error: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    return code;
}

static void link_cli_synopsis(char *out, size_t cap);
static void link_cli_print_help(void);

static int usage(const char *why)
{
    char commands[512];
    link_cli_synopsis(commands, sizeof commands);
    return fail(EXIT_USAGE,
                "%s (usage: sixphase-link [-d|--port DEVICE] [-b BAUD] [-t MS] [-n] %s [ARGS]; "
                "sixphase-link --help lists the arguments)",
                why, commands);
}

/* Numbers are plain decimals, sixphase-sim's rule (decimal_arg.h): 010, 0x10, " 5", "5ms" and
 * an overflow are refused, not read as octal, hexadecimal or a prefix. */
/* A refused number, named: "bad value for -t: '010' (a plain decimal, 1..60000 ms)". */
static int bad_number(const char *what, const char *v, const char *range)
{
    return fail(EXIT_USAGE, "bad value for %s: '%s' (a plain decimal, %s)", what, v, range);
}

int parse_long(const char *s, long lo, long hi, long *out)
{
    double v;
    if (decimal_parse(s, 1, (double)lo, (double)hi, &v) != 0) {
        return 0;
    }
    *out = (long)v;
    return 1;
}

int parse_double(const char *s, double lo, double hi, double *out)
{
    return decimal_parse(s, 0, lo, hi, out) == 0;
}

/* One frame byte for decode: one or two hex digits, nothing else. */
static int parse_hex_byte(const char *s, long *out)
{
    char *end = NULL;
    if (!isxdigit((unsigned char)s[0]) || (s[1] != '\0' && !isxdigit((unsigned char)s[1])) ||
        (s[1] != '\0' && s[2] != '\0')) {
        return 0;
    }
    *out = strtol(s, &end, 16);
    return *end == '\0';
}

static int32_t round_i32(double x)
{
    return (int32_t)((x >= 0.0) ? floor(x + 0.5) : ceil(x - 0.5));
}

static speed_t baud_constant(long baud)
{
    switch (baud) {
    case 9600:
        return B9600;
    case 19200:
        return B19200;
    case 38400:
        return B38400;
    case 57600:
        return B57600;
    case 115200:
        return B115200;
    case 230400:
        return B230400;
    default:
        return (speed_t)0;
    }
}

int open_port(const options_t *o, int *fd_out)
{
    struct termios tio;
    const speed_t sp = baud_constant(o->baud);
    int fd;
    if (sp == (speed_t)0) {
        return fail(EXIT_USAGE, "unsupported baud rate %ld", o->baud);
    }
    fd = open(o->device, O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd < 0) {
        return fail(EXIT_IO, "cannot open %s: %s", o->device, strerror(errno));
    }
    if (tcgetattr(fd, &tio) != 0) {
        const int e = errno;
        close(fd);
        return fail(EXIT_IO, "%s is not a serial port: %s", o->device, strerror(e));
    }
    tio.c_iflag &=
        (tcflag_t) ~(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL | IXON | IXOFF);
    tio.c_oflag &= (tcflag_t)~OPOST;
    tio.c_lflag &= (tcflag_t) ~(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    tio.c_cflag &= (tcflag_t) ~(CSIZE | PARENB | CSTOPB);
    tio.c_cflag |= (tcflag_t)(CS8 | CREAD | CLOCAL);
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    if (cfsetispeed(&tio, sp) != 0 || cfsetospeed(&tio, sp) != 0 ||
        tcsetattr(fd, TCSANOW, &tio) != 0) {
        const int e = errno;
        close(fd);
        return fail(EXIT_IO, "cannot configure %s: %s", o->device, strerror(e));
    }
    (void)tcflush(fd, TCIOFLUSH);
    *fd_out = fd;
    return 0;
}

static long now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long)ts.tv_sec * 1000L + ts.tv_nsec / 1000000L;
}

static int write_all(int fd, const uint16_t *frame, uint16_t n)
{
    unsigned char buf[SXL_MAX_FRAME];
    size_t off = 0;
    uint16_t i;
    for (i = 0u; i < n; i++) {
        buf[i] = (unsigned char)(frame[i] & 0xFFu);
    }
    while (off < n) {
        const ssize_t w = write(fd, buf + off, (size_t)n - off);
        if (w < 0) {
            if (errno == EAGAIN || errno == EINTR) {
                struct pollfd p = {fd, POLLOUT, 0};
                (void)poll(&p, 1, 100);
                continue;
            }
            return fail(EXIT_IO, "write failed: %s", strerror(errno));
        }
        off += (size_t)w;
    }
    return 0;
}

/* Wait for the reply to cmd; 0 and *reply filled on success. Noise and malformed frames are
 * skipped (the decoder resynchronises on the next frame), and so is a stale reply to an
 * earlier request that timed out; only the deadline ends the wait. */
static int read_reply(int fd, uint16_t cmd, long timeout_ms, sxl_frame_t *reply)
{
    sxl_decoder_t dec;
    const long deadline = now_ms() + timeout_ms;
    unsigned stale = 0u;
    sxl_decoder_init(&dec);
    for (;;) {
        unsigned char buf[64];
        struct pollfd p = {fd, POLLIN, 0};
        const long left = deadline - now_ms();
        ssize_t r;
        ssize_t i;
        if (left <= 0) {
            return fail(EXIT_IO,
                        "no reply within %ld ms (%u malformed frames, %u stale replies "
                        "skipped)",
                        timeout_ms, (unsigned)dec.errors, stale);
        }
        if (poll(&p, 1, (int)left) < 0 && errno != EINTR) {
            return fail(EXIT_IO, "poll failed: %s", strerror(errno));
        }
        r = read(fd, buf, sizeof buf);
        if (r < 0 && errno != EAGAIN && errno != EINTR) {
            return fail(EXIT_IO, "read failed: %s", strerror(errno));
        }
        for (i = 0; i < r; i++) {
            const sxl_rx_t res = sxl_decoder_push(&dec, (uint16_t)buf[i], reply);
            if (res != SXL_RX_FRAME) {
                continue;
            }
            if (reply->cmd == (uint16_t)(cmd | SXL_REPLY) && reply->len >= 1u) {
                return 0;
            }
            stale++;
        }
    }
}

/* The status's second line (protocol 6): the stack's high-water mark against its size. */
static void print_stack(uint16_t used, uint16_t words)
{
    if (words == SXL_STACK_NOT_MEASURED) {
        printf("stack: not measured (virtual board)\n");
        return;
    }
    printf("stack: %u of %u words used (%.0f %%)\n", (unsigned)used, (unsigned)words,
           100.0 * (double)used / (double)words);
}

int print_reply(const sxl_frame_t *r)
{
    const uint16_t result = r->payload[0];
    const uint16_t *st = &r->payload[1];
    if (result == SXL_ERR_UNKNOWN && (r->cmd & 0x7Fu) == SXL_CMD_SIM_SHUTDOWN) {
        return fail(EXIT_IO, "drive answered: unknown command (shutdown stops only the virtual "
                             "board, sixphase-sim serve)");
    }
    if (result != SXL_OK) {
        return fail(EXIT_IO, "drive answered: %s", sxl_result_name(result));
    }
    switch (r->cmd & 0x7Fu) {
    case SXL_CMD_GET_PROFILE:
        return print_profile_row(r, 1);
    case SXL_CMD_GET_OPEN_PHASE:
        return link_open_phase_print(r);
    case SXL_CMD_GET_TORQUE_LIMITED:
        return link_torque_limited_print(r);
    case SXL_CMD_PING:
        if (r->len < 2u) {
            return fail(EXIT_IO, "short ping reply");
        }
        printf("pong protocol=%u\n", (unsigned)r->payload[1]);
        return 0;
    case SXL_CMD_GET_STATUS:
        /* protocol 1 firmware sends the block without the fault fields */
        if (r->len < 1u + SXL_ST_SIZE_V1) {
            return fail(EXIT_IO, "short status reply (%u bytes)", (unsigned)r->len);
        }
        printf("state=%s fault=%s controller=%s speed=%.1frpm speed_ref=%.1frpm torque=%.3fNm "
               "torque_ref=%.3fNm lambda=%.3f encoder=%s pwm=%s params_pending=%s isr_count=%lu "
               "isr_max_cycles=%lu rx_errors=%u",
               sxl_state_name(st[SXL_ST_STATE]), sxl_fault_name(st[SXL_ST_FAULT]),
               ctl_controller_name(st[SXL_ST_CONTROLLER]),
               (double)sxl_get_i32(&st[SXL_ST_SPEED]) / 10.0,
               (double)sxl_get_i32(&st[SXL_ST_SPEED_REF]) / 10.0,
               (double)sxl_get_i32(&st[SXL_ST_TORQUE]) / 1000.0,
               (double)sxl_get_i32(&st[SXL_ST_TORQUE_REF]) / 1000.0,
               (double)sxl_get_u32(&st[SXL_ST_LAMBDA]) / 1000.0,
               (st[SXL_ST_FLAGS] & SXL_FLAG_ENCODER_OK) ? "ok" : "bad",
               (st[SXL_ST_FLAGS] & SXL_FLAG_PWM_OFF) ? "off" : "on",
               (st[SXL_ST_FLAGS] & SXL_FLAG_PARAMS_PENDING) ? "yes" : "no",
               (unsigned long)sxl_get_u32(&st[SXL_ST_ISR_COUNT]),
               (unsigned long)sxl_get_u32(&st[SXL_ST_ISR_MAX]),
               (unsigned)sxl_get_u16(&st[SXL_ST_RX_ERRORS]));
        if (r->len >= 1u + SXL_ST_SIZE_V2) {
            char mask[256];
            (void)sxl_fault_mask_str(sxl_get_u16(&st[SXL_ST_FAULTS]), mask, (uint16_t)sizeof mask);
            printf(" faults=%s fault_records=%u", mask, (unsigned)sxl_get_u16(&st[SXL_ST_RECORDS]));
        }
        if (r->len >= 1u + SXL_ST_SIZE_V5) {
            char blocked[256];
            (void)sxl_fault_mask_str(sxl_get_u16(&st[SXL_ST_CLEAR_BLOCKED]), blocked,
                                     (uint16_t)sizeof blocked);
            printf(" last_run_refusal=%s last_clear_blocked_by=%s",
                   sxl_run_refusal_name(st[SXL_ST_RUN_REFUSAL]), blocked);
        }
        printf(" leg_isolated=%s", (st[SXL_ST_FLAGS] & SXL_FLAG_LEG_ISOLATED) ? "yes" : "no");
        printf(" torque_limited=%s", (st[SXL_ST_FLAGS] & SXL_FLAG_TORQUE_LIMITED) ? "yes" : "no");
        printf("\n");
        if (r->len >= 1u + SXL_ST_SIZE) {
            print_stack(sxl_get_u16(&st[SXL_ST_STACK_USED]), sxl_get_u16(&st[SXL_ST_STACK_WORDS]));
        }
        return 0;
    default:
        printf("ok\n");
        return 0;
    }
}

static const char *const stage_names[SXL_PF_STAGES] = {"latency (period start to ISR)",
                                                       "ADC read and scaling",
                                                       "transforms and references",
                                                       "prediction to k+1",
                                                       "sector and table lookup",
                                                       "candidate search",
                                                       "PWM write",
                                                       "ISR total"};

int print_profile_row(const sxl_frame_t *r, int first)
{
    const uint16_t *pf = &r->payload[1];
    double cpu;
    if (r->payload[0] != SXL_OK) {
        return fail(EXIT_IO, "drive answered: %s", sxl_result_name(r->payload[0]));
    }
    if (r->len < 1u + SXL_PF_SIZE || pf[SXL_PF_STAGE] >= SXL_PF_STAGES) {
        return fail(EXIT_IO, "short or malformed profile reply (%u bytes)", (unsigned)r->len);
    }
    cpu = (double)sxl_get_u16(&pf[SXL_PF_CYCLES_PER_US]);
    if (cpu <= 0.0) {
        cpu = 1.0;
    }
    if (first) {
        printf("period %lu cycles, %.1f cycles/us, measurement cost %lu cycles (subtracted), "
               "CPU load %.1f %% (max %.1f %%), overruns %lu\n",
               (unsigned long)sxl_get_u32(&pf[SXL_PF_PERIOD]), cpu,
               (unsigned long)sxl_get_u32(&pf[SXL_PF_READ_COST]),
               (double)sxl_get_u16(&pf[SXL_PF_LOAD_LAST]) / 10.0,
               (double)sxl_get_u16(&pf[SXL_PF_LOAD_MAX]) / 10.0,
               (unsigned long)sxl_get_u32(&pf[SXL_PF_OVERRUNS]));
        printf("%-30s %10s %10s %10s %10s %9s %9s\n", "stage", "last", "min", "max", "mean",
               "mean us", "max us");
    }
    printf("%-30s %10lu %10lu %10lu %10lu %9.2f %9.2f\n", stage_names[pf[SXL_PF_STAGE]],
           (unsigned long)sxl_get_u32(&pf[SXL_PF_LAST]),
           (unsigned long)sxl_get_u32(&pf[SXL_PF_MIN]), (unsigned long)sxl_get_u32(&pf[SXL_PF_MAX]),
           (unsigned long)sxl_get_u32(&pf[SXL_PF_MEAN]),
           (double)sxl_get_u32(&pf[SXL_PF_MEAN]) / cpu, (double)sxl_get_u32(&pf[SXL_PF_MAX]) / cpu);
    return 0;
}

int print_fault_record(const sxl_frame_t *r, int *present)
{
    static const char *const phase_names[SXL_FR_PHASES] = {"ia", "ib", "ic", "id", "ie", "if"};
    const uint16_t *fr = &r->payload[1];
    char mask[256];
    uint16_t k;
    if (r->payload[0] != SXL_OK) {
        return fail(EXIT_IO, "drive answered: %s", sxl_result_name(r->payload[0]));
    }
    if (r->len < 1u + SXL_FR_HEADER_SIZE || fr[SXL_FR_PRESENT] > 1u ||
        (fr[SXL_FR_PRESENT] == 1u && r->len < 1u + SXL_FR_SIZE)) {
        return fail(EXIT_IO, "short or malformed fault record reply (%u bytes)", (unsigned)r->len);
    }
    *present = (int)fr[SXL_FR_PRESENT];
    if (!*present) {
        return 0;
    }
    (void)sxl_fault_mask_str(sxl_get_u16(&fr[SXL_FR_FAULTS]), mask, (uint16_t)sizeof mask);
    printf("period=%lu faults=%s", (unsigned long)sxl_get_u32(&fr[SXL_FR_PERIOD]), mask);
    for (k = 0u; k < SXL_FR_PHASES; k++) {
        printf(" %s=%.2fA", phase_names[k],
               (double)sxl_get_i16(&fr[SXL_FR_I_PHASE + 2u * k]) / 100.0);
    }
    printf(" vdc=%.1fV theta=%.1fdeg speed=%.1frpm te=%.3fNm tref=%.3fNm vector=%d duty=%.3f\n",
           (double)sxl_get_i16(&fr[SXL_FR_VDC]) / 10.0,
           (double)sxl_get_u16(&fr[SXL_FR_THETA]) * (360.0 / 65536.0),
           (double)sxl_get_i32(&fr[SXL_FR_SPEED]) / 10.0,
           (double)sxl_get_i32(&fr[SXL_FR_TORQUE]) / 1000.0,
           (double)sxl_get_i32(&fr[SXL_FR_TORQUE_REF]) / 1000.0,
           (int)sxl_get_i16(&fr[SXL_FR_VECTOR]), (double)sxl_get_u16(&fr[SXL_FR_DUTY]) / 32768.0);
    return 0;
}

static void print_frame(const uint16_t *frame, uint16_t n)
{
    uint16_t k;
    for (k = 0u; k < n; k++) {
        printf("%02X%s", (unsigned)frame[k], (k + 1u < n) ? " " : "\n");
    }
}

/* A "busy" reply (a parameter set still on its way to the control ISR, which takes it within
 * a control period) is sent again this many times, this far apart. */
#define BUSY_RETRIES 5
#define BUSY_RETRY_US 2000

/* Send one frame and wait for its reply (a BUSY reply is retried); 0 on success. */
static int send_and_wait(int fd, const options_t *o, uint16_t cmd, const uint16_t *payload,
                         uint16_t len, sxl_frame_t *reply)
{
    uint16_t frame[SXL_MAX_FRAME];
    const uint16_t flen = sxl_encode(cmd, payload, len, frame, (uint16_t)SXL_MAX_FRAME);
    int attempt;
    if (flen == 0u) {
        return fail(EXIT_USAGE, "cannot encode the request");
    }
    for (attempt = 0;; attempt++) {
        int rc = write_all(fd, frame, flen);
        if (rc == 0) {
            rc = read_reply(fd, cmd, o->timeout_ms, reply);
        }
        if (rc != 0 || reply->payload[0] != SXL_ERR_BUSY || attempt == BUSY_RETRIES) {
            return rc;
        }
        usleep(BUSY_RETRY_US);
    }
}

/* Arms a session (SXL_CMD_ARM) and puts its token in front of the payload. */
static int arm(int fd, const options_t *o, const uint16_t *payload, uint16_t len, uint16_t *armed)
{
    sxl_frame_t reply;
    uint16_t i;
    int rc = send_and_wait(fd, o, SXL_CMD_ARM, NULL, 0u, &reply);
    if (rc != 0) {
        return rc;
    }
    if (reply.payload[0] != SXL_OK || reply.len != 1u + SXL_TOKEN_BYTES) {
        return fail(EXIT_IO, "the drive did not arm a session (%s)", result_name(reply.payload[0]));
    }
    for (i = 0u; i < SXL_TOKEN_BYTES; i++) {
        armed[i] = reply.payload[1u + i];
    }
    for (i = 0u; i < len; i++) {
        armed[SXL_TOKEN_BYTES + i] = payload[i];
    }
    return 0;
}

/* Send one request and wait for its reply; 0 on success. A command that moves the motor
 * (SXL_ARMED_COMMAND) goes out in a session armed just before it. */
int exchange(int fd, const options_t *o, uint16_t cmd, const uint16_t *payload, uint16_t len,
             sxl_frame_t *reply)
{
    uint16_t armed[SXL_MAX_PAYLOAD];
    int rc;
    if (!SXL_ARMED_COMMAND(cmd)) {
        return send_and_wait(fd, o, cmd, payload, len, reply);
    }
    if (len > SXL_MAX_PAYLOAD - SXL_TOKEN_BYTES) {
        return fail(EXIT_USAGE, "cannot encode the request");
    }
    rc = arm(fd, o, payload, len, armed);
    return (rc != 0) ? rc
                     : send_and_wait(fd, o, cmd, armed, (uint16_t)(len + SXL_TOKEN_BYTES), reply);
}

/* Read the fault log until the drive reports it empty. */
static int cmd_faults(const options_t *o)
{
    sxl_frame_t reply;
    int fd = -1;
    int n = 0;
    int present = 1;
    int rc = open_port(o, &fd);
    if (rc != 0) {
        return rc;
    }
    while (rc == 0 && present && n < FAULTS_MAX_RECORDS) {
        rc = exchange(fd, o, SXL_CMD_GET_FAULT_RECORD, NULL, 0u, &reply);
        if (rc == 0) {
            rc = print_fault_record(&reply, &present);
        }
        if (rc == 0 && present) {
            n++;
        }
    }
    close(fd);
    if (rc != 0) {
        return rc;
    }
    if (present) {
        return fail(EXIT_IO, "fault log still not empty after %d records", n);
    }
    if (n == 0) {
        printf("no fault records\n");
    }
    {
        const uint16_t dropped = sxl_get_u16(&reply.payload[1 + SXL_FR_DROPPED]);
        if (dropped != 0u) {
            printf("dropped=%u (log was full; the oldest records were kept)\n", (unsigned)dropped);
        }
    }
    return 0;
}

static int cmd_decode(int argc, char **argv)
{
    sxl_decoder_t dec;
    sxl_frame_t f;
    int i;
    sxl_decoder_init(&dec);
    if (argc < 1) {
        return usage("decode needs hex bytes");
    }
    for (i = 0; i < argc; i++) {
        long v;
        sxl_rx_t r;
        if (!parse_hex_byte(argv[i], &v)) {
            return fail(EXIT_USAGE, "bad byte '%s' (hex 00..FF)", argv[i]);
        }
        r = sxl_decoder_push(&dec, (uint16_t)v, &f);
        if (r == SXL_RX_ERR_CRC) {
            return fail(EXIT_IO, "CRC error at byte %d", i);
        }
        if (r == SXL_RX_ERR_LENGTH) {
            return fail(EXIT_IO, "bad length field at byte %d", i);
        }
        if (r == SXL_RX_FRAME) {
            uint16_t k;
            if (i != argc - 1) {
                return fail(EXIT_IO, "trailing bytes after the frame");
            }
            printf("frame cmd=0x%02X len=%u payload=", (unsigned)f.cmd, (unsigned)f.len);
            for (k = 0u; k < f.len; k++) {
                printf("%02X", (unsigned)f.payload[k]);
            }
            printf("\n");
            return 0;
        }
    }
    return fail(EXIT_IO, "incomplete frame");
}

/* The request builders of the commands that take arguments (argv[0] is the command's name):
 * 0 when built, else an exit status after a one-line error. */
static int build_speed(int argc, char **argv, uint16_t *cmd, uint16_t *payload, uint16_t *len)
{
    const double max_rpm = (double)SXL_SPEED_REF_MAX_RPM;
    double rpm;
    if (argc != 2) {
        return usage("speed needs one value in r/min");
    }
    if (!parse_double(argv[1], -max_rpm, max_rpm, &rpm)) {
        return bad_number(
            "speed", argv[1],
            "-" SXL_STR(SXL_SPEED_REF_MAX_RPM) "..." SXL_STR(SXL_SPEED_REF_MAX_RPM) " r/min");
    }
    *cmd = SXL_CMD_SET_SPEED;
    sxl_put_i32(&payload[SXL_SPEED_REF], round_i32(rpm * 10.0));
    *len = SXL_SPEED_SIZE;
    return 0;
}

static int build_torque(int argc, char **argv, uint16_t *cmd, uint16_t *payload, uint16_t *len)
{
    const double max_nm = (double)SXL_TORQUE_REF_MAX_NM;
    double nm;
    if (argc != 2) {
        return usage("torque needs one value in N*m");
    }
    if (!parse_double(argv[1], -max_nm, max_nm, &nm)) {
        return bad_number(
            "torque", argv[1],
            "-" SXL_STR(SXL_TORQUE_REF_MAX_NM) "..." SXL_STR(SXL_TORQUE_REF_MAX_NM) " N*m");
    }
    *cmd = SXL_CMD_SET_TORQUE;
    sxl_put_i32(&payload[SXL_TORQUE_REF], round_i32(nm * 1000.0));
    *len = SXL_TORQUE_SIZE;
    return 0;
}

static int build_controller(int argc, char **argv, uint16_t *cmd, uint16_t *payload, uint16_t *len)
{
    double lambda;
    uint16_t id;
    if (argc != 3) {
        return usage("controller needs a name and lambda");
    }
    for (id = 0u; id < (uint16_t)CTL_CONTROLLER_COUNT; id++) {
        if (strcmp(argv[1], ctl_controller_name(id)) == 0) {
            break;
        }
    }
    if (id == (uint16_t)CTL_CONTROLLER_COUNT) {
        return usage("controller must be one of:" LINK_CONTROLLER_NAMES);
    }
    if (!parse_double(argv[2], CTL_LAMBDA_MIN, CTL_LAMBDA_MAX, &lambda)) {
        return bad_number(
            "lambda", argv[2],
            CTL_RANGE_STR(CTL_LAMBDA_MIN) ".." CTL_RANGE_STR(CTL_LAMBDA_MAX) " N*m/Wb");
    }
    *cmd = SXL_CMD_SET_CONTROLLER;
    payload[SXL_SC_CONTROLLER] = id;
    sxl_put_u32(&payload[SXL_SC_LAMBDA], (uint32_t)round_i32(lambda * 1000.0));
    *len = SXL_SC_SIZE;
    return 0;
}

/* The options before the command; *next is the command's index. -1 to go on, else the exit
 * status (help or version printed, or a usage error). */
static int parse_options(int argc, char **argv, options_t *o, int *next)
{
    int i = 1;
    while (i < argc && argv[i][0] == '-' && argv[i][1] != '\0') {
        const char *opt = argv[i];
        if (strcmp(opt, "-n") == 0) {
            o->print_only = 1;
            i++;
            continue;
        }
        if (strcmp(opt, "-h") == 0 || strcmp(opt, "--help") == 0) {
            link_cli_print_help();
            return 0;
        }
        if (strcmp(opt, "--version") == 0) {
            printf("sixphase-link %s (protocol %u)\n", SIXPHASE_VERSION, (unsigned)SXL_VERSION);
            return 0;
        }
        if (i + 1 >= argc) {
            return usage("option needs a value");
        }
        if (strcmp(opt, "-d") == 0 || strcmp(opt, "--port") == 0) {
            o->device = argv[i + 1];
        } else if (strcmp(opt, "-b") == 0) {
            if (!parse_long(argv[i + 1], 1, 4000000, &o->baud)) {
                return bad_number("-b", argv[i + 1], "a baud rate");
            }
        } else if (strcmp(opt, "-t") == 0) {
            if (!parse_long(argv[i + 1], 1, 60000, &o->timeout_ms)) {
                return bad_number("-t", argv[i + 1], "1..60000 ms");
            }
        } else {
            return usage("unknown option");
        }
        i += 2;
    }
    *next = i;
    return -1;
}

int print_request(uint16_t cmd, const uint16_t *payload, uint16_t len)
{
    uint16_t frame[SXL_MAX_FRAME];
    uint16_t armed[SXL_MAX_PAYLOAD] = {0};
    uint16_t flen, i;
    if (SXL_ARMED_COMMAND(cmd)) { /* the ARM request, then the command: token 00 00 00 00 */
        if (len > SXL_MAX_PAYLOAD - SXL_TOKEN_BYTES) {
            return fail(EXIT_USAGE, "cannot encode the request");
        }
        print_frame(frame, sxl_encode(SXL_CMD_ARM, NULL, 0u, frame, (uint16_t)SXL_MAX_FRAME));
        for (i = 0u; i < len; i++) {
            armed[SXL_TOKEN_BYTES + i] = payload[i];
        }
        payload = armed;
        len = (uint16_t)(len + SXL_TOKEN_BYTES);
    }
    flen = sxl_encode(cmd, payload, len, frame, (uint16_t)SXL_MAX_FRAME);
    if (flen == 0u) {
        return fail(EXIT_USAGE, "cannot encode the request");
    }
    print_frame(frame, flen);
    return 0;
}

/* profile: one request per stage, printed as a table. */
static int cmd_profile(const options_t *o)
{
    uint16_t payload[1];
    sxl_frame_t reply;
    uint16_t stage;
    int fd = -1;
    int rc = open_port(o, &fd);
    for (stage = 0u; stage < SXL_PF_STAGES && rc == 0; stage++) {
        payload[0] = stage;
        rc = exchange(fd, o, SXL_CMD_GET_PROFILE, payload, 1u, &reply);
        if (rc == 0) {
            rc = print_profile_row(&reply, stage == 0u);
        }
    }
    if (fd >= 0) {
        close(fd);
    }
    return rc;
}

/* Any other command: one request, one reply printed (in an armed session where the command
 * moves the motor, as exchange does for every command). */
static int cmd_single(const options_t *o, uint16_t cmd, const uint16_t *payload, uint16_t len)
{
    sxl_frame_t reply;
    int fd = -1;
    int rc = open_port(o, &fd);
    if (rc != 0) {
        return rc;
    }
    rc = exchange(fd, o, cmd, payload, len, &reply);
    close(fd);
    return (rc != 0) ? rc : print_reply(&reply);
}

static int run_faults(const options_t *o, int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return o->print_only ? print_request(SXL_CMD_GET_FAULT_RECORD, NULL, 0u) : cmd_faults(o);
}

static int run_profile(const options_t *o, int argc, char **argv)
{
    const uint16_t first_stage[SXL_PQ_SIZE] = {0u};
    (void)argc;
    (void)argv;
    return o->print_only ? print_request(SXL_CMD_GET_PROFILE, first_stage, SXL_PQ_SIZE)
                         : cmd_profile(o);
}

static int run_decode(const options_t *o, int argc, char **argv)
{
    (void)o;
    return cmd_decode(argc - 1, &argv[1]);
}

static int run_capture(const options_t *o, int argc, char **argv)
{
    return cmd_capture(o, argc - 1, &argv[1]);
}

static int run_identify(const options_t *o, int argc, char **argv)
{
    return cmd_identify(o, argc - 1, &argv[1]);
}

/* The tool's commands, one list: from it come the dispatch, the usage line, --help and each
 * command's --help (docs/serial-protocol.md shows --help, tools/usage_doc.py). A command is
 * plain (no arguments, one request: cmd), built (build makes its request from the arguments) or
 * run (its own exchanges). */
typedef int (*link_build_t)(int argc, char **argv, uint16_t *cmd, uint16_t *payload, uint16_t *len);
typedef int (*link_run_t)(const options_t *o, int argc, char **argv);
typedef struct {
    const char *name, *args, *help;
    uint16_t cmd;
    link_build_t build;
    link_run_t run;
} link_cli_t;

static const link_cli_t link_cli[] = {
    {"ping", "", "the drive's protocol version", SXL_CMD_PING, NULL, NULL},
    {"status", "", "state, fault, speed, torque, counters, stack", SXL_CMD_GET_STATUS, NULL, NULL},
    {"profile", "", "the control ISR's timing, one row per stage", 0u, NULL, run_profile},
    {"faults", "", "read the fault log until it is empty, one line per record", 0u, NULL,
     run_faults},
    {"run", "", "start (READY -> RUN), in a session armed just before", SXL_CMD_RUN, NULL, NULL},
    {"stop", "", "stop (RUN or COMMISSION -> READY)", SXL_CMD_STOP, NULL, NULL},
    {"clear", "", "clear a fault (FAULT -> READY when healthy)", SXL_CMD_CLEAR_FAULT, NULL, NULL},
    {"shutdown", "", "virtual board only: sixphase-sim serve answers, then stops",
     SXL_CMD_SIM_SHUTDOWN, NULL, NULL},
    {"speed", "RPM",
     "speed reference, r/min, -" SXL_STR(SXL_SPEED_REF_MAX_RPM) ".." SXL_STR(
         SXL_SPEED_REF_MAX_RPM) "; selects the speed loop",
     0u, build_speed, NULL},
    {"torque", "NM",
     "torque reference, N*m, -" SXL_STR(SXL_TORQUE_REF_MAX_NM) ".." SXL_STR(
         SXL_TORQUE_REF_MAX_NM) "; selects the torque loop",
     0u, build_torque, NULL},
    {"controller", "NAME LAMBDA",
     "controller, one of" LINK_CONTROLLER_NAMES
     ", with lambda " CTL_RANGE_STR(CTL_LAMBDA_MIN) ".." CTL_RANGE_STR(CTL_LAMBDA_MAX) " N*m/Wb",
     0u, build_controller, NULL},
    {"capture",
     "SIG[,SIG...] [--length N] [--decimate N] [--pre PCT] "
     "[--trigger immediate|fault|rising:SIG:LEVEL|falling:SIG:LEVEL] [--wait S] [--out FILE.csv] "
     "[--plot FILE.png]",
     "record up to 4 signals in the drive's capture buffer, read them as CSV and a plot", 0u, NULL,
     run_capture},
    {"identify",
     "[--steps all|phases,encoder,r,ldq,lxy,psi_f,mech] [--current F] [--apply] [--partial] "
     "[--out FILE.h] [--wait S]",
     "commission the motor: run the steps, print the results, apply or write them", 0u, NULL,
     run_identify},
    {"open-phase", "", "the open-phase action, strategy and isolated leg", 0u,
     link_open_phase_request, NULL},
    {"open-phase-action", "stop|ride-through [min-loss|max-torque]",
     "what the drive does on an open phase", 0u, link_open_phase_request, NULL},
    {"isolate", "A..F", "switch a leg off for good and run on five", 0u, link_open_phase_request,
     NULL},
    {"restore", "", "end a leg's isolation (READY)", 0u, link_open_phase_request, NULL},
    {"torque-limited", "[continue|stop [--stop-after S]]",
     "what the drive does when the speed loop sits at its torque limit: print, or set", 0u,
     link_torque_limited_request, NULL},
    {"decode", "HEXBYTE...", "check and print a frame given as hex bytes (no device)", 0u, NULL,
     run_decode},
};
#define LINK_CLI_COUNT ((int)(sizeof link_cli / sizeof link_cli[0]))

static const link_cli_t *link_cli_find(const char *name)
{
    int k;
    for (k = 0; k < LINK_CLI_COUNT; k++) {
        if (strcmp(link_cli[k].name, name) == 0) {
            return &link_cli[k];
        }
    }
    return NULL;
}

static void link_cli_print_help(void)
{
    int k;
    printf("usage: sixphase-link [-d DEVICE | --port DEVICE] [-b BAUD] [-t MS] [-n] COMMAND "
           "[ARGS]\n"
           "       sixphase-link COMMAND --help | --help | --version\n"
           "  -d, --port DEVICE  serial device (default /dev/ttyUSB0)\n"
           "  -b BAUD            baud rate (default 115200)\n"
           "  -t MS              reply timeout, 1..60000 ms (default 500)\n"
           "  -n                 print the request frame in hex instead of sending it\n"
           "commands:\n");
    for (k = 0; k < LINK_CLI_COUNT; k++) {
        printf("  %s%s%s\n      %s\n", link_cli[k].name, link_cli[k].args[0] ? " " : "",
               link_cli[k].args, link_cli[k].help);
    }
}

/* The usage line's commands, NAME|NAME|..., into out (cap chars); --help gives their arguments. */
static void link_cli_synopsis(char *out, size_t cap)
{
    size_t n = 0u;
    int k;
    out[0] = '\0';
    for (k = 0; k < LINK_CLI_COUNT && n < cap; k++) {
        const int w = snprintf(&out[n], cap - n, "%s%s", (k > 0) ? "|" : "", link_cli[k].name);
        n += (w > 0) ? (size_t)w : 0u;
    }
}

/* One command line from its name on; the exit status. */
static int link_cli_dispatch(const options_t *o, const link_cli_t *c, int argc, char **argv)
{
    uint16_t payload[SXL_MAX_PAYLOAD];
    uint16_t cmd = c->cmd;
    uint16_t len = 0u;
    if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
        printf("usage: sixphase-link [options] %s%s%s\n  %s\n", c->name, c->args[0] ? " " : "",
               c->args, c->help);
        return 0;
    }
    if (c->args[0] == '\0' && argc != 1) { /* the table lists no arguments for it */
        return usage("this command takes no arguments");
    }
    if (c->run != NULL) {
        return c->run(o, argc, argv);
    }
    if (c->build != NULL) {
        const int rc = c->build(argc, argv, &cmd, payload, &len);
        if (rc != 0) {
            return rc;
        }
    }
    return o->print_only ? print_request(cmd, payload, len) : cmd_single(o, cmd, payload, len);
}

#ifndef SIXPHASE_LINK_NO_MAIN /* the reply-parsing fuzz harness links the rest */
int main(int argc, char **argv)
{
    options_t o = {"/dev/ttyUSB0", 115200L, 500L, 0};
    const link_cli_t *c;
    int i = 1;
    int rc = parse_options(argc, argv, &o, &i);
    if (rc >= 0) {
        return rc;
    }
    if (i >= argc) {
        return usage("missing command");
    }
    c = link_cli_find(argv[i]);
    return (c != NULL) ? link_cli_dispatch(&o, c, argc - i, &argv[i]) : usage("unknown command");
}
#endif
