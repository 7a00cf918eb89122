#include "sxlink.h"

/* Every payload of the lists (sxlink_payloads.h) fits a frame after the result byte, and
 * every request after the token where the command takes one (C99 has no static_assert: a
 * false condition gives an array of size -1). */
#define SXL_PAYLOAD_FITS(prefix)                                                                   \
    typedef char prefix##_fits_a_frame[((uint32_t)prefix##_SIZE + 1u <= SXL_MAX_PAYLOAD) ? 1 : -1];
SXL_PAYLOAD_LIST(SXL_PAYLOAD_FITS)
#undef SXL_PAYLOAD_FITS
#define SXL_REQUEST_FITS(name, code, handler, armed, request, reply, notes)                        \
    typedef char sxl_request_fits_##name                                                           \
        [((uint32_t)request##_SIZE + ((armed) ? SXL_TOKEN_BYTES : 0u) <= SXL_MAX_PAYLOAD) ? 1      \
                                                                                          : -1];
SXL_COMMAND_LIST(SXL_REQUEST_FITS)
#undef SXL_REQUEST_FITS

/* CRC-32C (Castagnoli), reflected, bit by bit: no table (512 words on the C28x) for at most
 * SXL_MAX_FRAME bytes, in the background. */
uint32_t sxl_crc32_byte(uint32_t crc, uint16_t byte)
{
    uint16_t i;
    crc ^= (uint32_t)(byte & 0xFFu);
    for (i = 0u; i < 8u; i++) {
        crc = ((crc & 1u) != 0u) ? ((crc >> 1) ^ SXL_CRC32C_POLY_REFLECTED) : (crc >> 1);
    }
    return crc;
}

uint32_t sxl_crc32(const uint16_t *bytes, uint16_t n)
{
    uint32_t crc = 0xFFFFFFFFu;
    uint16_t i;
    for (i = 0u; i < n; i++) {
        crc = sxl_crc32_byte(crc, bytes[i]);
    }
    return crc ^ 0xFFFFFFFFu;
}

/* The CRC's bytes, most significant first, at out[0..3]. */
static void put_crc(uint16_t *out, uint32_t crc)
{
    uint16_t i;
    for (i = 0u; i < SXL_CRC_BYTES; i++) {
        out[i] = (uint16_t)((crc >> (8u * (SXL_CRC_BYTES - 1u - i))) & 0xFFu);
    }
}

static uint32_t get_crc(const uint16_t *in)
{
    uint32_t crc = 0u;
    uint16_t i;
    for (i = 0u; i < SXL_CRC_BYTES; i++) {
        crc = (crc << 8) | (uint32_t)(in[i] & 0xFFu);
    }
    return crc;
}

uint16_t sxl_encode(uint16_t cmd, const uint16_t *payload, uint16_t len, uint16_t *out,
                    uint16_t cap)
{
    uint16_t i;
    const uint16_t total = (uint16_t)(len + SXL_FRAME_OVERHEAD);
    if (len > SXL_MAX_PAYLOAD || cmd > 0xFFu || cap < total || (len > 0u && payload == 0)) {
        return 0u;
    }
    for (i = 0u; i < len; i++) {
        if (payload[i] > 0xFFu) {
            return 0u;
        }
    }
    out[0] = SXL_SOF;
    out[1] = (uint16_t)(len + 1u);
    out[2] = cmd;
    for (i = 0u; i < len; i++) {
        out[3u + i] = payload[i];
    }
    put_crc(&out[3u + len], sxl_crc32(&out[1], (uint16_t)(len + 2u)));
    return total;
}

void sxl_decoder_reset(sxl_decoder_t *d) { d->n = 0u; }

bool sxl_decoder_idle(const sxl_decoder_t *d) { return d->n == 0u; }

void sxl_decoder_init(sxl_decoder_t *d)
{
    sxl_decoder_reset(d);
    d->errors = 0u;
}

static void count_error(sxl_decoder_t *d)
{
    if (d->errors < UINT16_MAX) {
        d->errors++;
    }
}

void sxl_decoder_abandon(sxl_decoder_t *d)
{
    if (d->n != 0u) {
        count_error(d);
        d->n = 0u;
    }
}

static bool length_valid(uint16_t len) { return len != 0u && len <= SXL_MAX_PAYLOAD + 1u; }

/* Bytes of a whole frame whose LEN field is len: start byte, LEN, CMD + payload, CRC. */
static uint16_t frame_bytes(uint16_t len) { return (uint16_t)(len + 2u + SXL_CRC_BYTES); }

/* Drop the held bytes before index k, then anything up to the next start byte. */
static void drop_before(sxl_decoder_t *d, uint16_t k)
{
    uint16_t i;
    while (k < d->n && d->held[k] != SXL_SOF) {
        k++;
    }
    for (i = 0u; k + i < d->n; i++) {
        d->held[i] = d->held[k + i];
    }
    d->n = i;
}

/* The frame starting at held[start] ends with the last held byte and checks out. */
static bool frame_ends_here(const sxl_decoder_t *d, uint16_t start)
{
    uint16_t len;
    if (d->held[start] != SXL_SOF || (uint16_t)(d->n - start) < SXL_FRAME_OVERHEAD) {
        return false;
    }
    len = d->held[start + 1u];
    if (!length_valid(len) || (uint16_t)(d->n - start) != frame_bytes(len)) {
        return false;
    }
    return sxl_crc32(&d->held[start + 1u], (uint16_t)(len + 1u)) ==
           get_crc(&d->held[d->n - SXL_CRC_BYTES]);
}

static void take_frame(sxl_decoder_t *d, uint16_t start, sxl_frame_t *out)
{
    uint16_t i;
    out->cmd = d->held[start + 2u];
    out->len = (uint16_t)(d->held[start + 1u] - 1u);
    for (i = 0u; i < out->len; i++) {
        out->payload[i] = d->held[start + 3u + i];
    }
    d->n = 0u;
}

/* Give up held starts that can no longer begin a frame: an impossible length, or a frame
 * complete by its length (it was checked when its last byte came) that did not check out. */
static sxl_rx_t drop_dead_starts(sxl_decoder_t *d)
{
    sxl_rx_t result = SXL_RX_NONE;
    while (d->n >= 2u) {
        const uint16_t len = d->held[1];
        if (length_valid(len) && d->n < frame_bytes(len)) {
            break; /* still waiting for its bytes */
        }
        result = length_valid(len) ? SXL_RX_ERR_CRC : SXL_RX_ERR_LENGTH;
        count_error(d);
        drop_before(d, 1u);
    }
    return result;
}

sxl_rx_t sxl_decoder_push(sxl_decoder_t *d, uint16_t byte, sxl_frame_t *out)
{
    uint16_t start;
    if (byte > 0xFFu) {
        sxl_decoder_reset(d);
        count_error(d);
        return SXL_RX_ERR_BYTE;
    }
    if (d->n == 0u && byte != SXL_SOF) {
        return SXL_RX_NONE; /* line noise between frames */
    }
    d->held[d->n] = byte;
    d->n++;
    for (start = 0u; start < d->n; start++) {
        if (frame_ends_here(d, start)) {
            if (start > 0u) {
                count_error(d); /* a false start before it */
            }
            take_frame(d, start, out);
            return SXL_RX_FRAME;
        }
    }
    return drop_dead_starts(d);
}

void sxl_put_u16(uint16_t *p, uint16_t v)
{
    p[0] = (uint16_t)(v & 0xFFu);
    p[1] = (uint16_t)(v >> 8);
}

void sxl_put_u32(uint16_t *p, uint32_t v)
{
    p[0] = (uint16_t)(v & 0xFFu);
    p[1] = (uint16_t)((v >> 8) & 0xFFu);
    p[2] = (uint16_t)((v >> 16) & 0xFFu);
    p[3] = (uint16_t)((v >> 24) & 0xFFu);
}

void sxl_put_i32(uint16_t *p, int32_t v) { sxl_put_u32(p, (uint32_t)v); }

uint16_t sxl_get_u16(const uint16_t *p)
{
    return (uint16_t)((p[0] & 0xFFu) | ((p[1] & 0xFFu) << 8));
}

uint32_t sxl_get_u32(const uint16_t *p)
{
    return (uint32_t)(p[0] & 0xFFu) | ((uint32_t)(p[1] & 0xFFu) << 8) |
           ((uint32_t)(p[2] & 0xFFu) << 16) | ((uint32_t)(p[3] & 0xFFu) << 24);
}

int32_t sxl_get_i32(const uint16_t *p)
{
    const uint32_t u = sxl_get_u32(p);
    /* two's complement without implementation-defined conversion */
    if (u <= (uint32_t)INT32_MAX) {
        return (int32_t)u;
    }
    return (int32_t)(u - 0x80000000u) - INT32_MAX - 1;
}

void sxl_put_i16(uint16_t *p, int16_t v) { sxl_put_u16(p, (uint16_t)v); }

int16_t sxl_get_i16(const uint16_t *p)
{
    const uint16_t u = sxl_get_u16(p);
    /* two's complement without implementation-defined conversion */
    if (u <= (uint16_t)INT16_MAX) {
        return (int16_t)u;
    }
    return (int16_t)((int32_t)u - 65536);
}
