/*
 * The commissioning sequence (docs/commissioning.md): the drive identifies its motor and
 * aligns its encoder in the state COMMISSION, one call per control period from the ISR. The
 * steps run in order (commission_lists.h): phase check, encoder, resistance, L_d and L_q,
 * L_xy, magnet flux, inertia and friction; each leaves the machine as the next expects it, each has
 * its own result checks and a time bound (three times its nominal duration plus 2 s: TIMEOUT). A
 * failed step ends the sequence (the later ones are SKIPPED); the results so far stay readable. The
 * drive forces the outputs off whenever the sequence ends.
 *
 * The background asks for a start (comm_request); the ISR starts it from READY (comm_start).
 */
#ifndef COMMISSION_H
#define COMMISSION_H

#include <stdbool.h>
#include <stdint.h>

#include "ident.h"
#include "ident_encoder.h"
#include "ident_flux.h"
#include "ident_inductance.h"
#include "ident_mech.h"
#include "ident_phase.h"
#include "ident_resistance.h"

/* The test current is also kept within this fraction of the over-current trip (peaks reach
 * 1.25 times it during the inductance step). */
#define COMM_TRIP_FRACTION 0.25f

typedef union {
    ident_phase_t phase;
    ident_encoder_t encoder;
    ident_resistance_t resistance;
    ident_inductance_t inductance;
    ident_flux_t flux;
    ident_mech_t mech;
} comm_step_state_t;

/* Every step's open-phase watch: over each window, each phase's |measured| and |commanded|
 * current (the regulator's references in the phase), summed. */
typedef struct {
    float meas[IDENT_PHASES];
    float ref[IDENT_PHASES];
    uint32_t n; /* periods in the window */
} comm_watch_t;

typedef struct {
    /* a start asked by the background, taken by the ISR in READY */
    volatile int16_t start_requested;
    uint16_t req_mask;
    uint16_t req_permille;
    /* the sequence */
    int16_t state;  /* comm_state_t */
    int16_t step;   /* comm_step_t running, or the last one run */
    int16_t reason; /* comm_reason_t: of the last refused start, or of the end */
    uint16_t mask;
    uint16_t permille;
    uint32_t periods;    /* control periods since the start */
    uint32_t step_start; /* periods at the running step's start */
    float done_seconds;  /* nominal time of the steps finished */
    float total_seconds; /* nominal time of the selected steps */
    ident_ctx_t x;
    comm_step_state_t s;
    comm_watch_t watch;
} comm_t;

void comm_init(comm_t *c);

/* A step mask with the phase check, known bits only, and the encoder step before any step
 * that needs the rotor aligned and its angle. */
bool comm_mask_valid(uint16_t mask);
/* A test current in COMM_CURRENT_MIN_PERMILLE .. MAX_PERMILLE of rated. */
bool comm_current_valid(uint16_t permille);

/* Background: ask for a start (mask and current valid; the caller checked the state). */
void comm_request(comm_t *c, uint16_t mask, uint16_t permille);

/* ISR: start the sequence with the machine as the parameter set in force describes it. */
void comm_start(comm_t *c, const ident_machine_t *m, uint16_t mask, uint16_t permille);

/* ISR, one period: true with the voltage request u (alpha, beta, x, y, V) while it runs;
 * false once it has ended (DONE or FAILED; the outputs must go off). */
bool comm_period(comm_t *c, const ident_input_t *in, float u[4]);

/* End it now (a stop command, a protection fault). */
void comm_abort(comm_t *c, int16_t reason);

/* Progress of the whole sequence, 0..100 %. */
uint16_t comm_progress_percent(const comm_t *c);

/* The quantities each step identifies (bit per comm_quantity_t). */
uint16_t comm_step_quantities(int16_t step);

/* The longest the steps of mask can take before their time bounds end them, s (a caller that
 * waits for the sequence waits at least this). */
float comm_time_bound_s(uint16_t mask);

#endif /* COMMISSION_H */
