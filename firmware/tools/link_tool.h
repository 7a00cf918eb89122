/*
 * What the host tool's commands share (firmware/tools/sixphase_link.c): the port options,
 * opening it, one request-reply exchange, the one-line error report.
 */
#ifndef LINK_TOOL_H
#define LINK_TOOL_H

#include "sxlink.h"

#define EXIT_USAGE 2
#define EXIT_IO 1

typedef struct {
    const char *device;
    long baud;
    long timeout_ms;
    int print_only;
} options_t;

/* "sixphase-link: error: ..." on stderr; returns code. */
int fail(int code, const char *fmt, ...);
int parse_long(const char *s, long lo, long hi, long *out);
int open_port(const options_t *o, int *fd_out);
/* One request and its reply (a BUSY reply is retried); 0 or the exit status. */
int exchange(int fd, const options_t *o, uint16_t cmd, const uint16_t *payload, uint16_t len,
             sxl_frame_t *reply);
/* The meaning of a reply's result byte. */
const char *result_name(uint16_t result);

/* capture SIGNALS [options]: firmware/tools/link_capture.c. */
int cmd_capture(const options_t *o, int argc, char **argv);

#endif /* LINK_TOOL_H */
