/*
 * Identification step 2, the encoder. A current vector (the test current) at a commanded
 * angle pulls the rotor's d axis along (docs/commissioning.md):
 *   align  the current rises at a fixed angle (raised cosine) and holds, then the angle moves
 *          a quarter turn and holds (a rotor at the first angle's unstable point, the field
 *          opposite its d axis, is pulled off it) until the rotor is still (at most 1 s);
 *   spin   the angle turns forward at 1 electrical turn/s. After the first commanded turn the
 *          count's change gives the direction and a first counts-per-electrical-turn (no
 *          count: NO_MOTION); from then on the rotor's swing about the commanded angle is
 *          damped (q current against the speed error). Once the index has been seen (within
 *          2 Pn + 3 commanded turns or 1.25 counted mechanical turns, else NO_INDEX) the
 *          counts per electrical turn are measured over two whole turns in quarter-turn
 *          blocks: negative is REVERSED (A and B swapped), more than 10 % from 4 lines / Pn
 *          is POLE_PAIRS (the result's extra: the pole pairs the count implies);
 *   offset the angle keeps turning forward two turns, then backward two turns, at the same
 *          speed after a settling half turn; the commanded angle minus the HAL's angle is
 *          averaged in quarter-turn blocks each way. The mean of the two directions is the
 *          offset (friction and the swing cancel); half their difference is the lag;
 *   load   forward and then backward again at half the current: a lag that does not change
 *          sign with the direction (a load torque, which friction's does) grows there by the
 *          stiffness ratio, which friction's lag itself measures (the set's ratio when there is
 *          too little friction to tell); beyond 2 electrical degrees the step fails
 *          (LOAD_TORQUE: the offset, and psi_f with it, would be off by the lag; the result's
 *          extra is the load's lag).
 * Throughout, a load the field cannot hold drags the rotor through its poles: a rotor that
 * turns more than the field can have pulled it (a mechanical turn beyond the commanded travel
 * until the counts per electrical turn are measured, then half an electrical turn away from
 * the field's travel) fails the step at once with LOAD_TORQUE (the extra: the slip,
 * electrical degrees), before the protection's open-phase check, which sees a standing
 * current vector under a turning rotor, takes the phase across the vector for an open one.
 * The HAL's angle is the floor of the count: half a count is added. About 17.5 s.
 */
#ifndef IDENT_ENCODER_H
#define IDENT_ENCODER_H

#include "ident.h"

typedef struct {
    int32_t p0;          /* position at the spin's start */
    ident_still_t still; /* the alignment's settling */
    int32_t p_mark;      /* position at the start of a measuring quarter turn */
    float travel_mark;   /* commanded travel there, turns */
    float travel_index;  /* commanded travel when the index was first seen; < 0: not yet */
    float travel_known;  /* commanded travel when the direction was found */
    bool measuring;      /* counts per electrical turn being measured */
    ident_blocks_t cpe;  /* counts per electrical turn, quarter-turn blocks */
    ident_blocks_t fwd;  /* offset turning forward, turns, quarter-turn blocks */
    ident_blocks_t bwd;  /* and backward */
    ident_blocks_t fwd2; /* forward again at half the current (the load check) */
    ident_blocks_t bwd2; /* and backward at half the current */
    float ref;           /* the offset's unwrapping reference, turns */
    bool have_ref;
    float travel_start; /* travel at the start of the running direction's part */
    int32_t p_begin;    /* position at the step's first period (the slip check's reference) */
    bool have_begin;
    int32_t p_slip; /* position and commanded travel when the counts were measured */
    float travel_slip;
    bool have_slip_ref;
} ident_encoder_t;

void ident_encoder_begin(ident_ctx_t *x, ident_encoder_t *s);
ident_status_t ident_encoder_step(ident_ctx_t *x, ident_encoder_t *s, const ident_input_t *in);

#define IDENT_ENCODER_SECONDS 17.5f

#endif /* IDENT_ENCODER_H */
