/*
 * One row added to the serial command list in a test build (command_row_extra.h), and every
 * artefact derived from the list follows it (issue 26: "add a row in a test build and see it
 * everywhere"): the code and the token rule (sxlink_commands.h), the drive's dispatch and
 * length check (firmware/app/drive_link.c, with the row's handler from
 * command_row_handlers.h), and the command table of docs/serial-protocol.md (the protocol-doc
 * program of this build, CTest command_row_doc).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "drive_fixture.h"
#include "service/drive_link.h"

static drive_t d;

static int setup(void **state)
{
    (void)state;
    fixture_init(&d);
    return 0;
}

static uint16_t send(uint16_t cmd, const uint16_t *payload, uint16_t len, bool with_token,
                     sxl_frame_t *reply)
{
    sxl_frame_t req = {0u, 0u, {0u}};
    uint16_t k, at = 0u;
    req.cmd = cmd;
    if (with_token) {
        sxl_frame_t arm = {SXL_CMD_ARM, 0u, {0u}};
        sxl_frame_t arm_reply;
        drive_link_handle(&d, &arm, &arm_reply, 0u);
        for (k = 0u; k < SXL_TOKEN_BYTES; k++) {
            req.payload[k] = arm_reply.payload[1u + SXL_AR_TOKEN + k];
        }
        at = SXL_TOKEN_BYTES;
    }
    for (k = 0u; k < len; k++) {
        req.payload[at + k] = payload[k];
    }
    req.len = (uint16_t)(at + len);
    drive_link_handle(&d, &req, reply, 0u);
    return reply->payload[0];
}

static void test_the_added_row_is_everywhere(void **state)
{
    const uint16_t request[SXL_CQ_SIZE] = {0x12u, 0x34u, 0x56u};
    sxl_frame_t reply;
    (void)state;
    fixture_ready(&d);
    assert_int_equal(SXL_CMD_TEST_ECHO, 0x7D);
    assert_true(SXL_ARMED_COMMAND(SXL_CMD_TEST_ECHO));
    assert_int_equal(send(SXL_CMD_TEST_ECHO, request, SXL_CQ_SIZE, false, &reply),
                     SXL_ERR_NOT_ARMED);
    assert_int_equal(send(SXL_CMD_TEST_ECHO, request, SXL_CQ_SIZE - 1u, true, &reply),
                     SXL_ERR_LENGTH);
    assert_int_equal(send(SXL_CMD_TEST_ECHO, request, SXL_CQ_SIZE, true, &reply), SXL_OK);
    assert_int_equal(reply.cmd, SXL_CMD_TEST_ECHO | SXL_REPLY);
    assert_int_equal(reply.len, 1u + SXL_CQ_SIZE);
    assert_memory_equal(&reply.payload[1], request, sizeof request);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_the_added_row_is_everywhere, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
