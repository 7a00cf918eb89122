/*
 * Incremental encoder: electrical angle and mechanical speed.
 */
#ifndef HAL_ENCODER_H
#define HAL_ENCODER_H

#include <stdbool.h>
#include <stdint.h>

typedef struct {
    uint32_t elec_angle;    /* electrical angle, 2^32 = one turn (wraps naturally) */
    int32_t mech_speed_q16; /* mechanical speed, rev/s in Q16 (65536 = 1 rev/s) */
    bool healthy;           /* false: index not yet seen, counter error or timeout */
} hal_encoder_sample_t;

/* lines: encoder lines per mechanical turn; pole_pairs; elec_offset: angle of
 * the index pulse relative to the d axis, 2^32 = one electrical turn. */
bool hal_encoder_init(uint32_t lines, uint16_t pole_pairs, uint32_t elec_offset);

void hal_encoder_read(hal_encoder_sample_t *s);

/* Forget the homing: the count may be wrong (a cleared ENCODER fault). The encoder reports
 * unhealthy until the index has been seen again, which re-homes the count. */
void hal_encoder_rehome(void);

#endif /* HAL_ENCODER_H */
