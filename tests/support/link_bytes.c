/* Serial bytes over a file descriptor (link_bytes.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <unistd.h>

#include <cmocka.h>

#include "link_bytes.h"
#include "sxlink.h"

void link_send_bytes(int fd, const uint16_t *bytes, uint16_t n)
{
    uint16_t i;
    for (i = 0u; i < n; i++) {
        const unsigned char b = (unsigned char)bytes[i];
        assert_int_equal(write(fd, &b, 1), 1);
    }
}

void link_send_frame(int fd, uint16_t cmd, const uint16_t *payload, uint16_t len)
{
    uint16_t frame[SXL_MAX_FRAME];
    const uint16_t n = sxl_encode(cmd, payload, len, frame, SXL_MAX_FRAME);
    assert_true(n > 0u);
    link_send_bytes(fd, frame, n);
}
