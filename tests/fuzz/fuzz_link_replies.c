/*
 * Fuzz target for the host tool's reading of a drive's replies (libFuzzer entry point): the
 * functions of firmware/tools that take one reply frame - the single commands' printout
 * (status, ping, open phase, torque-limited), a profile row, a fault record, the capture arm
 * and read replies, the commissioning status, result and apply replies - on arbitrary frames, as a
 * drive with other firmware, a damaged one or an impostor on the port could send them (the
 * CRC only says the frame arrived as sent). The sanitizers (ASan + UBSan, float-cast overflow
 * included) catch any read outside the frame or the tables, any overflow; what is printed
 * goes to /dev/null.
 *
 * Input: byte 0 picks the parser, byte 1 is the reply's command, byte 2 the parser's argument
 * (profile: first row; capture read: the first sample; result: the quantity), the rest the
 * payload (at most SXL_MAX_PAYLOAD bytes; as the decoder leaves it, zero beyond the length).
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "link_tool.h"
#include "sxlink_commission.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);

#define REPLIES_SAMPLES 2048 /* the tool's capture buffer per channel */

static void parse(uint16_t which, uint16_t arg, const sxl_frame_t *r)
{
    static int16_t samples[REPLIES_SAMPLES];
    uint16_t st[SXL_CT_SIZE];
    identify_results_t res;
    int present = 0;
    int j = (int)arg * 8;
    switch (which) {
    case 0:
        (void)print_reply(r);
        break;
    case 1:
        (void)print_profile_row(r, (int)(arg & 1u));
        break;
    case 2:
        (void)print_fault_record(r, &present);
        break;
    case 3:
        (void)cap_arm_reply(r);
        break;
    case 4:
        (void)cap_read_reply(r, &j, REPLIES_SAMPLES, samples);
        break;
    case 5:
        (void)identify_status_reply(r, st);
        break;
    case 6:
        motor_params_clear(&res.m);
        (void)identify_result_reply(r, (uint16_t)(arg % SXL_COMM_QUANTITY_COUNT), &res);
        break;
    case 7:
        (void)identify_apply_reply(r);
        break;
    default:
        (void)link_open_phase_print(r);
        break;
    }
}

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    static int quiet;
    sxl_frame_t r;
    size_t k;
    if (!quiet) {
        quiet = freopen("/dev/null", "w", stdout) != NULL;
    }
    if (size < 3u) {
        return 0;
    }
    memset(&r, 0, sizeof r);
    r.cmd = (uint16_t)(data[1] | SXL_REPLY);
    r.len = (uint16_t)((size - 3u < SXL_MAX_PAYLOAD) ? size - 3u : SXL_MAX_PAYLOAD);
    for (k = 0u; k < r.len; k++) {
        r.payload[k] = data[3u + k];
    }
    parse((uint16_t)(data[0] % 9u), data[2], &r);
    return 0;
}
