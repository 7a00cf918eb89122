/*
 * What the host tool's commands share (firmware/tools/sixphase_link.c): the port options,
 * opening it, one request-reply exchange, the one-line error report.
 */
#ifndef LINK_TOOL_H
#define LINK_TOOL_H

#include "motor_params_file.h"
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
/* A plain decimal in [lo, hi] (decimal_arg.h); 1, or 0 when refused. */
int parse_long(const char *s, long lo, long hi, long *out);
int parse_double(const char *s, double lo, double hi, double *out);
int open_port(const options_t *o, int *fd_out);
/* One request and its reply (a BUSY reply is retried); 0 or the exit status. */
int exchange(int fd, const options_t *o, uint16_t cmd, const uint16_t *payload, uint16_t len,
             sxl_frame_t *reply);
/* The meaning of a reply's result byte. */
const char *result_name(uint16_t result);

/* -n: the request's frame on stdout instead of sending it. */
int print_request(uint16_t cmd, const uint16_t *payload, uint16_t len);

/* capture SIGNALS [options]: firmware/tools/link_capture.c. */
int cmd_capture(const options_t *o, int argc, char **argv);

/* The open-phase commands' requests (firmware/tools/link_open_phase.c): 0 when built, an exit
 * status for a usage error, LINK_NOT_OPEN_PHASE when argv[0] is none of them. */
#define LINK_NOT_OPEN_PHASE (-1)
int link_open_phase_request(int argc, char **argv, uint16_t *cmd, uint16_t *payload, uint16_t *len);
/* The reply to SXL_CMD_GET_OPEN_PHASE on one line; 0 or an exit status. */
int link_open_phase_print(const sxl_frame_t *r);

/* The torque-limited commands' requests (firmware/tools/link_torque_limited.c): 0 when built,
 * an exit status for a usage error, LINK_NOT_TORQUE_LIMITED when argv[0] is not one. */
#define LINK_NOT_TORQUE_LIMITED (-1)
int link_torque_limited_request(int argc, char **argv, uint16_t *cmd, uint16_t *payload,
                                uint16_t *len);
/* The reply to SXL_CMD_GET_TORQUE_LIMITED on one line; 0 or an exit status. */
int link_torque_limited_print(const sxl_frame_t *r);

/* identify [options]: firmware/tools/link_identify.c. */
int cmd_identify(const options_t *o, int argc, char **argv);

/* What the commands make of one reply frame, without a port (tests/fuzz/fuzz_link_replies.c
 * feeds them arbitrary frames); each returns 0 or an exit status after a one-line error. */
/* A single command's reply (status, ping, open phase, torque-limited, profile, or "ok"),
 * printed. */
int print_reply(const sxl_frame_t *r);
/* One stage's profile reply as a table row; the first call also prints the header. */
int print_profile_row(const sxl_frame_t *r, int first);
/* One fault record reply as a line; *present is 0 when the log was empty. */
int print_fault_record(const sxl_frame_t *r, int *present);
/* The reply to a capture arm: accepted, or why not. */
int cap_arm_reply(const sxl_frame_t *r);
/* A capture read reply: its samples into out[*j..count-1], *j advanced. */
int cap_read_reply(const sxl_frame_t *r, int *j, int count, int16_t *out);
/* A commissioning status reply: its SXL_CT_SIZE fields into st. */
int identify_status_reply(const sxl_frame_t *r, uint16_t *st);
/* The results as identify read them: every quantity's quality, reason, value and sigma (SI,
 * degrees for the offset), and the OK ones as the motor parameter file holds them. */
typedef struct {
    uint16_t quality[SXL_COMM_QUANTITY_COUNT];
    uint16_t reason[SXL_COMM_QUANTITY_COUNT];
    double value[SXL_COMM_QUANTITY_COUNT];
    double sigma[SXL_COMM_QUANTITY_COUNT];
    motor_params_t m;
} identify_results_t;
/* A commissioning result reply for quantity q (below SXL_COMM_QUANTITY_COUNT): printed, kept
 * in *res, and filed into res->m when OK. */
int identify_result_reply(const sxl_frame_t *r, uint16_t q, identify_results_t *res);
/* An apply reply: the quantities applied, printed. */
int identify_apply_reply(const sxl_frame_t *r);

#endif /* LINK_TOOL_H */
