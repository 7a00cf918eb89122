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
    /* Added for the drive's commissioning (docs/commissioning.md); the angle and speed above
     * are all the control step uses. */
    int32_t position; /* counts (4 per line) since init, unwrapped: continuous across the
                       * first index (which resets the interface's own counter) and across
                       * turns; up for the channels' positive direction; wraps at 2^31 */
    bool index_seen;  /* the index pulse has been seen since init (elec_angle is then the angle
                       * from the index plus the offset; before, from the power-up position) */
} hal_encoder_sample_t;

/* lines: encoder lines per mechanical turn; pole_pairs; elec_offset: angle of
 * the index pulse relative to the d axis, 2^32 = one electrical turn. */
bool hal_encoder_init(uint32_t lines, uint16_t pole_pairs, uint32_t elec_offset);

void hal_encoder_read(hal_encoder_sample_t *s);

/* Forget the homing: the count may be wrong (a cleared ENCODER fault). The encoder reports
 * unhealthy until the index has been seen again, which re-homes the count. */
void hal_encoder_rehome(void);
/* Counts per mechanical turn (4 x lines) of the initialised encoder; 0 before init. */
uint32_t hal_encoder_counts_per_turn(void);

/* The offset of the index to the d axis (2^32 = one electrical turn), as hal_encoder_init
 * took it: read it, or replace it (from the next read on; the commissioning's identified
 * offset, applied outside RUN). */
uint32_t hal_encoder_offset(void);
void hal_encoder_set_offset(uint32_t elec_offset);

#endif /* HAL_ENCODER_H */
