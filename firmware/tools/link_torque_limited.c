/* sixphase-link's torque-limited commands (docs/serial-protocol.md, docs/faults.md "When the
 * speed cannot be held"):
 *   torque-limited                               the choice in force (SXL_CMD_GET_TORQUE_LIMITED)
 *   torque-limited continue|stop [--stop-after S] what the drive does at its torque limit */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "link_tool.h"

/* Indexed by SXL_TL_CONTINUE and SXL_TL_STOP. */
static const char *const tl_actions[] = {"continue", "stop"};
#define TL_ACTIONS 2u

static int usage_error(const char *why)
{
    return fail(EXIT_USAGE, "%s (torque-limited | torque-limited continue|stop [--stop-after S])",
                why);
}

/* "--stop-after S" (S in seconds, rounded to the ms the link carries) into *stop_ms. */
static int parse_stop_after(int argc, char **argv, uint16_t *stop_ms)
{
    const double lo = (double)SXL_TL_STOP_MS_MIN / 1000.0;
    const double hi = (double)SXL_TL_STOP_MS_MAX / 1000.0;
    double s;
    if (strcmp(argv[0], "--stop-after") != 0) {
        return usage_error("unknown option after the action (only --stop-after S)");
    }
    if (argc != 2) {
        return usage_error("--stop-after needs one value in seconds, 0.001..60");
    }
    if (!parse_double(argv[1], lo, hi, &s)) {
        return fail(EXIT_USAGE, "bad value for --stop-after: '%s' (a plain decimal, %g..%g s)",
                    argv[1], lo, hi);
    }
    *stop_ms = (uint16_t)floor(s * 1000.0 + 0.5); /* within the range: 1..60000 */
    return 0;
}

int link_torque_limited_request(int argc, char **argv, uint16_t *cmd, uint16_t *payload,
                                uint16_t *len)
{
    uint16_t action = 0u;
    uint16_t stop_ms = SXL_TL_STOP_MS_DEFAULT;
    *len = 0u;
    if (strcmp(argv[0], "torque-limited") != 0) {
        return LINK_NOT_TORQUE_LIMITED;
    }
    if (argc == 1) {
        *cmd = SXL_CMD_GET_TORQUE_LIMITED;
        return 0;
    }
    while (action < TL_ACTIONS && strcmp(argv[1], tl_actions[action]) != 0) {
        action++;
    }
    if (action == TL_ACTIONS) {
        return usage_error("torque-limited needs continue or stop");
    }
    if (argc > 2) {
        const int rc = parse_stop_after(argc - 2, &argv[2], &stop_ms);
        if (rc != 0) {
            return rc;
        }
        if (action != SXL_TL_STOP) { /* continue never stops: the time would do nothing */
            return usage_error("--stop-after needs stop");
        }
    }
    *cmd = SXL_CMD_SET_TORQUE_LIMITED_ACTION;
    payload[SXL_TL_ACTION] = action;
    sxl_put_u16(&payload[SXL_TL_STOP_MS], stop_ms);
    *len = SXL_TL_SET_SIZE;
    return 0;
}

int link_torque_limited_print(const sxl_frame_t *r)
{
    const uint16_t *tl = &r->payload[1];
    if (r->len < 1u + SXL_TL_SIZE) {
        return fail(EXIT_IO, "short torque-limited reply (%u bytes)", (unsigned)r->len);
    }
    printf("action=%s stop_after=%.3fs stopped=%s\n",
           (tl[SXL_TL_ACTION] < TL_ACTIONS) ? tl_actions[tl[SXL_TL_ACTION]] : "?",
           (double)sxl_get_u16(&tl[SXL_TL_STOP_MS]) / 1000.0, tl[SXL_TL_STOPPED] ? "yes" : "no");
    return 0;
}
