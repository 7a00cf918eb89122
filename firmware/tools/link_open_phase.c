/* sixphase-link's open-phase commands (docs/serial-protocol.md, docs/faults.md):
 *   open-phase                              the details (SXL_CMD_GET_OPEN_PHASE)
 *   open-phase-action stop|ride-through [min-loss|max-torque]
 *   isolate A..F                            turn one leg off for good (READY or RUN)
 *   restore                                 end the isolation (READY) */
#include <stdio.h>
#include <string.h>

#include "link_tool.h"

static const char *const actions[] = {"stop", "ride-through"};
static const char *const strategies[] = {"min-loss", "max-torque"};
static const char *const causes[] = {"none", "fault", "command"};

/* Index of s in names[0..n), or -1. */
static int index_of(const char *s, const char *const *names, int n)
{
    int i;
    for (i = 0; i < n; i++) {
        if (strcmp(s, names[i]) == 0) {
            return i;
        }
    }
    return -1;
}

static int usage_error(const char *why)
{
    return fail(EXIT_USAGE,
                "%s (open-phase | open-phase-action stop|ride-through "
                "[min-loss|max-torque] | isolate A..F | restore)",
                why);
}

int link_open_phase_request(int argc, char **argv, uint16_t *cmd, uint16_t *payload, uint16_t *len)
{
    const char *c = argv[0];
    *len = 0u;
    if (strcmp(c, "open-phase") == 0 || strcmp(c, "restore") == 0) {
        *cmd = (c[0] == 'o') ? SXL_CMD_GET_OPEN_PHASE : SXL_CMD_RESTORE_LEGS;
        return (argc == 1) ? 0 : usage_error("this command takes no arguments");
    }
    if (strcmp(c, "open-phase-action") == 0) {
        const int action = (argc >= 2) ? index_of(argv[1], actions, 2) : -1;
        const int strategy = (argc == 3) ? index_of(argv[2], strategies, 2) : 0;
        if (argc < 2 || argc > 3 || action < 0 || strategy < 0) {
            return usage_error("open-phase-action needs stop or ride-through, then optionally "
                               "min-loss or max-torque");
        }
        *cmd = SXL_CMD_SET_OPEN_PHASE_ACTION;
        payload[0] = (uint16_t)action;
        payload[1] = (uint16_t)strategy;
        *len = 2u;
        return 0;
    }
    if (strcmp(c, "isolate") == 0) {
        if (argc != 2 || strlen(argv[1]) != 1u || argv[1][0] < 'A' || argv[1][0] > 'F') {
            return usage_error("isolate needs one leg, A..F");
        }
        *cmd = SXL_CMD_ISOLATE_LEG;
        payload[0] = (uint16_t)(argv[1][0] - 'A');
        *len = 1u;
        return 0;
    }
    return LINK_NOT_OPEN_PHASE;
}

int link_open_phase_print(const sxl_frame_t *r)
{
    const uint16_t *op = &r->payload[1];
    if (r->len < 1u + SXL_OP_SIZE) {
        return fail(EXIT_IO, "short open-phase reply (%u bytes)", (unsigned)r->len);
    }
    printf("action=%s strategy=%s isolated=",
           (op[SXL_OP_ACTION] < 2u) ? actions[op[SXL_OP_ACTION]] : "?",
           (op[SXL_OP_STRATEGY] < 2u) ? strategies[op[SXL_OP_STRATEGY]] : "?");
    if (op[SXL_OP_LEG] < 6u) {
        printf("%c", 'A' + (int)op[SXL_OP_LEG]);
    } else {
        printf("none");
    }
    printf(" cause=%s in_force=%s torque_limit=%.3fNm isolation_period=%lu\n",
           (op[SXL_OP_CAUSE] < 3u) ? causes[op[SXL_OP_CAUSE]] : "?",
           op[SXL_OP_IN_FORCE] ? "yes" : "no",
           (double)sxl_get_i32(&op[SXL_OP_TORQUE_LIMIT]) / 1000.0,
           (unsigned long)sxl_get_u32(&op[SXL_OP_PERIOD]));
    return 0;
}
