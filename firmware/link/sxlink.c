#include "sxlink.h"

enum { RX_SOF = 0, RX_LEN, RX_BODY, RX_CRC_HI, RX_CRC_LO };

uint16_t sxl_crc16_byte(uint16_t crc, uint16_t byte)
{
    uint16_t i;
    crc = (uint16_t)(crc ^ (uint16_t)((byte & 0xFFu) << 8));
    for (i = 0u; i < 8u; i++) {
        if ((crc & 0x8000u) != 0u) {
            crc = (uint16_t)((uint16_t)(crc << 1) ^ 0x1021u);
        } else {
            crc = (uint16_t)(crc << 1);
        }
    }
    return crc;
}

uint16_t sxl_crc16(const uint16_t *bytes, uint16_t n, uint16_t crc)
{
    uint16_t i;
    for (i = 0u; i < n; i++) {
        crc = sxl_crc16_byte(crc, bytes[i]);
    }
    return crc;
}

uint16_t sxl_encode(uint16_t cmd, const uint16_t *payload, uint16_t len, uint16_t *out,
                    uint16_t cap)
{
    uint16_t crc = 0xFFFFu;
    uint16_t i;
    const uint16_t total = (uint16_t)(len + 5u);
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
    crc = sxl_crc16(&out[1], (uint16_t)(len + 2u), crc);
    out[3u + len] = (uint16_t)(crc >> 8);
    out[4u + len] = (uint16_t)(crc & 0xFFu);
    return total;
}

void sxl_decoder_reset(sxl_decoder_t *d)
{
    d->state = RX_SOF;
    d->len = 0u;
    d->count = 0u;
    d->crc_rx = 0u;
}

bool sxl_decoder_idle(const sxl_decoder_t *d) { return d->state == RX_SOF; }

void sxl_decoder_init(sxl_decoder_t *d)
{
    sxl_decoder_reset(d);
    d->errors = 0u;
}

static sxl_rx_t rx_error(sxl_decoder_t *d, sxl_rx_t e)
{
    sxl_decoder_reset(d);
    d->errors++;
    return e;
}

sxl_rx_t sxl_decoder_push(sxl_decoder_t *d, uint16_t byte, sxl_frame_t *out)
{
    if (byte > 0xFFu) {
        return rx_error(d, SXL_RX_ERR_BYTE);
    }
    switch (d->state) {
    case RX_SOF:
        if (byte == SXL_SOF) {
            d->state = RX_LEN;
        }
        return SXL_RX_NONE;
    case RX_LEN:
        if (byte == 0u || byte > SXL_MAX_PAYLOAD + 1u) {
            return rx_error(d, SXL_RX_ERR_LENGTH);
        }
        d->len = byte;
        d->count = 0u;
        d->state = RX_BODY;
        return SXL_RX_NONE;
    case RX_BODY:
        d->body[d->count] = byte;
        d->count++;
        if (d->count >= d->len) {
            d->state = RX_CRC_HI;
        }
        return SXL_RX_NONE;
    case RX_CRC_HI:
        d->crc_rx = (uint16_t)(byte << 8);
        d->state = RX_CRC_LO;
        return SXL_RX_NONE;
    case RX_CRC_LO: {
        uint16_t crc = sxl_crc16_byte(0xFFFFu, d->len);
        uint16_t i;
        crc = sxl_crc16(d->body, d->len, crc);
        d->crc_rx = (uint16_t)(d->crc_rx | byte);
        if (crc != d->crc_rx) {
            return rx_error(d, SXL_RX_ERR_CRC);
        }
        out->cmd = d->body[0];
        out->len = (uint16_t)(d->len - 1u);
        for (i = 0u; i < out->len; i++) {
            out->payload[i] = d->body[1u + i];
        }
        sxl_decoder_reset(d);
        return SXL_RX_FRAME;
    }
    default:
        return rx_error(d, SXL_RX_ERR_LENGTH);
    }
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
