/* The drive's handler of the test build's extra row (command_row_extra.h), included by
 * firmware/app/drive_link.c before its command table. */
#ifndef COMMAND_ROW_HANDLERS_H
#define COMMAND_ROW_HANDLERS_H

static uint16_t on_test_echo(drive_t *d, const sxl_frame_t *req, sxl_frame_t *reply,
                             uint16_t rx_errors)
{
    uint16_t k;
    (void)d;
    (void)rx_errors;
    for (k = 0u; k < req->len; k++) {
        reply->payload[1u + k] = req->payload[k];
    }
    reply->len = (uint16_t)(1u + req->len);
    return SXL_OK;
}

#endif /* COMMAND_ROW_HANDLERS_H */
