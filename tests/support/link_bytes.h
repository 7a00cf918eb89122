/* Serial bytes to a host tool or the simulator over a file descriptor (a pseudo-terminal's
 * master), as the tests play the other end of the link. Bytes are one a uint16_t, as sxlink's
 * frames hold them. */
#ifndef LINK_BYTES_H
#define LINK_BYTES_H

#include <stdint.h>

/* n bytes written one at a time; the test fails on a short write. */
void link_send_bytes(int fd, const uint16_t *bytes, uint16_t n);
/* A frame encoded by sxl_encode (the test fails when it does not fit) and sent. */
void link_send_frame(int fd, uint16_t cmd, const uint16_t *payload, uint16_t len);

#endif /* LINK_BYTES_H */
