/*
 * sixphase-link capture: arm the drive's capture buffer, wait for the record, read it and
 * write it as CSV (time in s from the trigger, each channel in its SI unit) and, with
 * --plot, as a PNG through matplotlib (firmware/tools/plot_capture.py).
 *
 *   capture SIG[,SIG...] [--length N] [--decimate N] [--pre PCT] [--wait S]
 *           [--trigger immediate|fault|rising:SIG:LEVEL|falling:SIG:LEVEL]
 *           [--out FILE.csv] [--plot FILE.png]
 *   capture stop   (ends a capture an interrupted run left armed)
 *
 * Signals and their scaling: firmware/link/capture_signals.h. LEVEL is in the trigger
 * signal's SI unit. Defaults: 500 samples, every period, immediate trigger, 10 % before it,
 * 10 s wait, CSV on stdout.
 */
#define _DEFAULT_SOURCE /* usleep */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "capture_signals.h"
#include "link_tool.h"

#ifndef SIXPHASE_PLOT_CAPTURE
#define SIXPHASE_PLOT_CAPTURE ""
#endif
#ifndef SIXPHASE_PLOT_PYTHON
#define SIXPHASE_PLOT_PYTHON ""
#endif

#define CAP_NAME(id, name, unit, base, exponent) name,
#define CAP_UNIT(id, name, unit, base, exponent) unit,
#define CAP_SCALE(id, name, unit, base, exponent) ((base) / (double)(1L << (15 - (exponent)))),
static const char *const cap_names[] = {CAPTURE_SIGNAL_LIST(CAP_NAME)};
static const char *const cap_units[] = {CAPTURE_SIGNAL_LIST(CAP_UNIT)};
static const double cap_scale[] = {CAPTURE_SIGNAL_LIST(CAP_SCALE)}; /* SI per sample step */
#undef CAP_NAME
#undef CAP_UNIT
#undef CAP_SCALE

#define CAP_MAX_CHANNELS 4
#define CAP_MAX_SAMPLES 2048

typedef struct {
    uint16_t setup[SXL_CA_SIZE];
    int n_channels;
    int signal[CAP_MAX_CHANNELS];
    double wait_s;
    const char *out, *plot;
} capture_request_t;

static int cap_signal(const char *name, size_t len)
{
    int k;
    for (k = 0; k < CAPTURE_SIGNAL_COUNT; k++) {
        if (strlen(cap_names[k]) == len && strncmp(cap_names[k], name, len) == 0) {
            return k;
        }
    }
    return -1;
}

/* "unknown signal 'x' (one of i_a, i_b, ...)": the error names every valid signal. */
static int cap_unknown_signal(const char *name, size_t len)
{
    char valid[512];
    size_t used = 0;
    int k;
    valid[0] = '\0';
    for (k = 0; k < CAPTURE_SIGNAL_COUNT && used < sizeof valid; k++) {
        used += (size_t)snprintf(valid + used, sizeof valid - used, "%s%s", k ? ", " : "",
                                 cap_names[k]);
    }
    return fail(EXIT_USAGE, "unknown signal '%.*s' (one of %s)", (int)len, name, valid);
}

static int cap_parse_signals(const char *list, capture_request_t *q)
{
    const char *p = list;
    while (*p != '\0') {
        const char *end = strchr(p, ',');
        const size_t len = end ? (size_t)(end - p) : strlen(p);
        const int s = cap_signal(p, len);
        if (s < 0) {
            return cap_unknown_signal(p, len);
        }
        if (q->n_channels == CAP_MAX_CHANNELS) {
            return fail(EXIT_USAGE, "at most %d signals", CAP_MAX_CHANNELS);
        }
        q->signal[q->n_channels++] = s;
        p = end ? end + 1 : p + len;
    }
    return (q->n_channels == 0) ? fail(EXIT_USAGE, "no signal to capture") : 0;
}

/* immediate | fault | rising:SIG:LEVEL | falling:SIG:LEVEL into the setup. */
static int cap_parse_trigger(const char *t, uint16_t *setup)
{
    const char *sig = strchr(t, ':');
    const char *lvl = sig ? strchr(sig + 1, ':') : NULL;
    int s;
    double level;
    if (strcmp(t, "immediate") == 0 || strcmp(t, "fault") == 0) {
        setup[SXL_CA_TRIGGER] = (t[0] == 'i') ? 0u : 3u;
        return 0;
    }
    if (!sig || !lvl || (strncmp(t, "rising:", 7) != 0 && strncmp(t, "falling:", 8) != 0)) {
        return fail(EXIT_USAGE,
                    "bad trigger '%s' (immediate, fault, rising:SIG:LEVEL, "
                    "falling:SIG:LEVEL)",
                    t);
    }
    s = cap_signal(sig + 1, (size_t)(lvl - sig - 1));
    if (s < 0) {
        return cap_unknown_signal(sig + 1, (size_t)(lvl - sig - 1));
    }
    if (!parse_double(lvl + 1, -32767.0 * cap_scale[s], 32767.0 * cap_scale[s], &level)) {
        return fail(EXIT_USAGE, "bad trigger signal or level in '%s'", t);
    }
    setup[SXL_CA_TRIGGER] = (t[0] == 'r') ? 1u : 2u;
    setup[SXL_CA_TRIG_SIGNAL] = (uint16_t)s;
    sxl_put_u16(&setup[SXL_CA_TRIG_LEVEL], (uint16_t)(int16_t)lround(level / cap_scale[s]));
    return 0;
}

static int cap_option(capture_request_t *q, const char *opt, const char *v)
{
    long n;
    if (strcmp(opt, "--length") == 0 || strcmp(opt, "--decimate") == 0) {
        if (!parse_long(v, 1, 65535, &n)) {
            return fail(EXIT_USAGE, "bad value for %s: '%s'", opt, v);
        }
        sxl_put_u16(&q->setup[opt[2] == 'l' ? SXL_CA_LENGTH : SXL_CA_DECIMATION], (uint16_t)n);
    } else if (strcmp(opt, "--pre") == 0) {
        if (!parse_long(v, 0, 100, &n)) {
            return fail(EXIT_USAGE, "bad value for --pre: '%s' (0..100)", v);
        }
        q->setup[SXL_CA_PRE] = (uint16_t)n;
    } else if (strcmp(opt, "--wait") == 0) {
        if (!parse_long(v, 1, 3600, &n)) {
            return fail(EXIT_USAGE, "bad value for --wait: '%s' (1..3600 s)", v);
        }
        q->wait_s = (double)n;
    } else if (strcmp(opt, "--trigger") == 0) {
        return cap_parse_trigger(v, q->setup);
    } else if (strcmp(opt, "--out") == 0 || strcmp(opt, "--plot") == 0) {
        *(opt[2] == 'o' ? &q->out : &q->plot) = v;
    } else {
        return fail(EXIT_USAGE, "unknown capture option '%s'", opt);
    }
    return 0;
}

static int cap_parse(int argc, char **argv, capture_request_t *q)
{
    int i, k, rc;
    memset(q, 0, sizeof *q);
    q->wait_s = 10.0;
    sxl_put_u16(&q->setup[SXL_CA_LENGTH], 500u);
    sxl_put_u16(&q->setup[SXL_CA_DECIMATION], 1u);
    q->setup[SXL_CA_PRE] = 10u;
    if (argc < 1) {
        return fail(EXIT_USAGE, "capture needs signals (capture SIG[,SIG...] [options])");
    }
    if ((rc = cap_parse_signals(argv[0], q)) != 0) {
        return rc;
    }
    for (i = 1; i < argc; i += 2) {
        if (i + 1 >= argc) {
            return fail(EXIT_USAGE, "option %s needs a value", argv[i]);
        }
        if ((rc = cap_option(q, argv[i], argv[i + 1])) != 0) {
            return rc;
        }
    }
    q->setup[SXL_CA_CHANNELS] = (uint16_t)q->n_channels;
    for (k = 0; k < CAP_MAX_CHANNELS; k++) {
        q->setup[SXL_CA_SIGNAL + (uint16_t)k] =
            (k < q->n_channels) ? (uint16_t)q->signal[k] : 0xFFu;
    }
    if ((long)sxl_get_u16(&q->setup[SXL_CA_LENGTH]) * q->n_channels > CAP_MAX_SAMPLES) {
        return fail(EXIT_USAGE, "buffer too small: length x signals above %d", CAP_MAX_SAMPLES);
    }
    if (q->plot && !q->out) {
        return fail(EXIT_USAGE, "--plot needs --out (the figure is drawn from the CSV)");
    }
    return 0;
}

/* A status reply checked before any of it is used: its result, its length, and the setup it
 * reports against the one asked for (a drive's answer is not trusted). */
static int cap_status_valid(const capture_request_t *q, const sxl_frame_t *st)
{
    const uint16_t *s = &st->payload[1];
    int k;
    if (st->payload[0] != SXL_OK) {
        return fail(EXIT_IO, "capture status: %s", result_name(st->payload[0]));
    }
    if (st->len < 1u + SXL_CS_SIZE) {
        return fail(EXIT_IO, "capture status: short reply (%u bytes, %u expected)",
                    (unsigned)st->len, 1u + SXL_CS_SIZE);
    }
    if (s[SXL_CS_STATE] != 3u) {
        return 0; /* not done yet: only the state is read */
    }
    for (k = 0; k < q->n_channels && s[SXL_CS_CHANNELS] == (uint16_t)q->n_channels; k++) {
        if (s[SXL_CS_SIGNAL + (uint16_t)k] != (uint16_t)q->signal[k]) {
            break;
        }
    }
    if (k != q->n_channels || sxl_get_u16(&s[SXL_CS_DECIMATION]) == 0u ||
        sxl_get_u16(&s[SXL_CS_COUNT]) > CAP_MAX_SAMPLES ||
        sxl_get_u16(&s[SXL_CS_TRIGGER]) > sxl_get_u16(&s[SXL_CS_COUNT])) {
        return fail(EXIT_IO, "capture status: a record unlike the one asked for (channels, "
                             "decimation, count or trigger)");
    }
    return 0;
}

int cap_arm_reply(const sxl_frame_t *r)
{
    if (r->payload[0] == SXL_ERR_REFUSED) {
        return fail(EXIT_IO, "a capture is already running on the drive (`sixphase-link capture "
                             "stop` ends it)");
    }
    if (r->payload[0] != SXL_OK) {
        return fail(EXIT_IO, "drive refused the capture: %s", result_name(r->payload[0]));
    }
    return 0;
}

/* Arm, then poll the status until the record is done (or the wait runs out). */
static int cap_arm_and_wait(int fd, const options_t *o, const capture_request_t *q, sxl_frame_t *st)
{
    double waited = 0.0;
    int rc = exchange(fd, o, SXL_CMD_CAPTURE_ARM, q->setup, SXL_CA_SIZE, st);
    if (rc == 0) {
        rc = cap_arm_reply(st);
    }
    while (rc == 0) {
        rc = exchange(fd, o, SXL_CMD_CAPTURE_STATUS, NULL, 0, st);
        if (rc == 0) {
            rc = cap_status_valid(q, st);
        }
        if (rc != 0 || st->payload[1 + SXL_CS_STATE] == 3u) {
            return rc;
        }
        if (waited >= q->wait_s) {
            sxl_frame_t r;
            (void)exchange(fd, o, SXL_CMD_CAPTURE_STOP, NULL, 0, &r); /* leave the drive idle */
            return fail(EXIT_IO, "no complete record after %.0f s (trigger not met?); stopped",
                        waited);
        }
        usleep(50000);
        waited += 0.05;
    }
    return rc;
}

int cap_read_reply(const sxl_frame_t *r, int *j, int count, int16_t *out)
{
    int n, k;
    if (r->payload[0] != SXL_OK) {
        return fail(EXIT_IO, "capture read at sample %d: %s", *j, result_name(r->payload[0]));
    }
    n = (r->len >= 1u + SXL_CR_SAMPLES) ? (int)r->payload[1 + SXL_CR_COUNT] : -1;
    /* every sample the reply counts must be in it: no byte past its length is used */
    if (n <= 0 || n > (int)SXL_CR_MAX || (int)r->len < 1 + (int)SXL_CR_SAMPLES + 2 * n) {
        return fail(EXIT_IO, "capture read at sample %d: short or malformed reply (%u bytes)", *j,
                    (unsigned)r->len);
    }
    for (k = 0; k < n && *j < count; k++) {
        out[(*j)++] = sxl_get_i16(&r->payload[1u + SXL_CR_SAMPLES + 2u * (unsigned)k]);
    }
    return 0;
}

static int cap_read(int fd, const options_t *o, int ch, int count, int16_t *out)
{
    int j = 0;
    while (j < count) {
        uint16_t req[3];
        sxl_frame_t r;
        int rc;
        req[0] = (uint16_t)ch;
        sxl_put_u16(&req[1], (uint16_t)j);
        rc = exchange(fd, o, SXL_CMD_CAPTURE_READ, req, 3, &r);
        if (rc == 0) {
            rc = cap_read_reply(&r, &j, count, out);
        }
        if (rc != 0) {
            return rc;
        }
    }
    return 0;
}

static int cap_write_csv(FILE *f, const capture_request_t *q, const sxl_frame_t *st,
                         int16_t samples[][CAP_MAX_SAMPLES])
{
    const int count = (int)sxl_get_u16(&st->payload[1 + SXL_CS_COUNT]);
    const int trig = (int)sxl_get_u16(&st->payload[1 + SXL_CS_TRIGGER]);
    const double dt = 1e-9 * (double)sxl_get_u32(&st->payload[1 + SXL_CS_TS_NS]) *
                      (double)sxl_get_u16(&st->payload[1 + SXL_CS_DECIMATION]);
    int j, k;
    fprintf(f, "t_s");
    for (k = 0; k < q->n_channels; k++) {
        fprintf(f, ",%s_%s", cap_names[q->signal[k]], cap_units[q->signal[k]]);
    }
    fprintf(f, "\n");
    for (j = 0; j < count; j++) {
        fprintf(f, "%.7f", (double)(j - trig) * dt);
        for (k = 0; k < q->n_channels; k++) {
            fprintf(f, ",%.6g", (double)samples[k][j] * cap_scale[q->signal[k]]);
        }
        fprintf(f, "\n");
    }
    return ferror(f) ? fail(EXIT_IO, "cannot write the CSV") : 0;
}

static int cap_plot(const char *csv, const char *png)
{
    pid_t pid;
    int status = 0;
    if (SIXPHASE_PLOT_CAPTURE[0] == '\0' || SIXPHASE_PLOT_PYTHON[0] == '\0') {
        return fail(EXIT_IO, "no Python with matplotlib was found at configure time: no plot");
    }
    pid = fork();
    if (pid == 0) {
        execl(SIXPHASE_PLOT_PYTHON, SIXPHASE_PLOT_PYTHON, SIXPHASE_PLOT_CAPTURE, csv, png,
              (char *)NULL);
        _exit(127);
    }
    if (pid < 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        return fail(EXIT_IO, "the plot failed (python3 with matplotlib needed)");
    }
    return 0;
}

/* The CSV into f (stdout or --out, opened before the capture was armed) and the plot. */
static int cap_output(FILE *f, const capture_request_t *q, const sxl_frame_t *st,
                      int16_t samples[][CAP_MAX_SAMPLES])
{
    int rc = cap_write_csv(f, q, st, samples);
    if (q->out && fclose(f) != 0 && rc == 0) {
        rc = fail(EXIT_IO, "cannot write %s", q->out);
    }
    if (rc == 0 && q->plot) {
        rc = cap_plot(q->out, q->plot);
    }
    return rc;
}

/* No capture: the --out file opened for it is removed again; returns rc. */
static int cap_discard(const capture_request_t *q, FILE *out, int rc)
{
    if (q->out) {
        (void)fclose(out);
        (void)remove(q->out);
    }
    return rc;
}

/* capture stop: the drive's capture back to idle (after an interrupted capture). */
static int cap_stop(const options_t *o)
{
    sxl_frame_t r;
    int fd = -1;
    int rc = open_port(o, &fd);
    if (rc == 0) {
        rc = exchange(fd, o, SXL_CMD_CAPTURE_STOP, NULL, 0, &r);
        close(fd);
    }
    return rc;
}

int cmd_capture(const options_t *o, int argc, char **argv)
{
    static int16_t samples[CAP_MAX_CHANNELS][CAP_MAX_SAMPLES];
    capture_request_t q;
    sxl_frame_t st;
    FILE *out;
    int fd = -1, k, rc;
    if (argc == 1 && strcmp(argv[0], "stop") == 0) {
        return cap_stop(o);
    }
    rc = cap_parse(argc, argv, &q);
    if (rc != 0) {
        return rc;
    }
    if (o->print_only) {
        return fail(EXIT_USAGE, "capture is an exchange of several requests: no -n");
    }
    out = q.out ? fopen(q.out, "w") : stdout; /* a bad --out is found before the capture */
    if (!out) {
        return fail(EXIT_IO, "cannot write %s", q.out);
    }
    if ((rc = open_port(o, &fd)) != 0) {
        return cap_discard(&q, out, rc);
    }
    rc = cap_arm_and_wait(fd, o, &q, &st); /* a done status, checked (cap_status_valid) */
    for (k = 0; rc == 0 && k < q.n_channels; k++) {
        rc = cap_read(fd, o, k, (int)sxl_get_u16(&st.payload[1 + SXL_CS_COUNT]), samples[k]);
    }
    close(fd);
    return (rc != 0) ? cap_discard(&q, out, rc) : cap_output(out, &q, &st, samples);
}
