/*
 * The drive's capture buffer (an oscilloscope in the firmware, like C2000Ware's DATALOG):
 * up to CAPTURE_CHANNELS signals of firmware/link/capture_signals.h, 16-bit samples at the
 * control rate or every Nth period, a trigger (immediate, a level crossed rising or falling
 * by any signal, or the drive entering FAULT) with a pre-trigger share of the record. With
 * the fault trigger and a large pre-trigger share it is a post-mortem recorder: it keeps
 * recording until the trip and freezes the last samples before it.
 *
 * The control ISR records (capture_sample: a few stores and one compare per period); the
 * background side arms, polls and reads (the serial commands in drive_link.c). The buffer
 * is one static block of CAPTURE_BUFFER_WORDS words (docs/porting.md section 7).
 */
#ifndef CAPTURE_H
#define CAPTURE_H

#include <stdbool.h>
#include <stdint.h>

#include "capture_signals.h"

#define CAPTURE_CHANNELS 4
#define CAPTURE_BUFFER_WORDS 2048 /* samples of all channels together */

typedef enum {
    CAPTURE_IDLE = 0,      /* nothing recorded, or stopped */
    CAPTURE_ARMED = 1,     /* recording, waiting for the trigger */
    CAPTURE_TRIGGERED = 2, /* recording the post-trigger samples */
    CAPTURE_DONE = 3       /* the record is complete and frozen */
} capture_state_t;

typedef enum {
    CAPTURE_TRIGGER_IMMEDIATE = 0,
    CAPTURE_TRIGGER_RISING = 1,  /* the trigger signal goes from below the level to at/above */
    CAPTURE_TRIGGER_FALLING = 2, /* from above the level to at/below */
    CAPTURE_TRIGGER_FAULT = 3,   /* the drive enters FAULT (post-mortem) */
    CAPTURE_TRIGGER_MODES = 4
} capture_trigger_t;

/* Why an arm request was refused (the serial result codes map them). */
typedef enum {
    CAPTURE_OK = 0,
    CAPTURE_ERR_SIGNAL,  /* unknown signal, or no channel, or more than CAPTURE_CHANNELS */
    CAPTURE_ERR_SETTING, /* decimation 0, length 0, pre-trigger above 100 %, unknown trigger */
    CAPTURE_ERR_NO_ROOM, /* length x channels above CAPTURE_BUFFER_WORDS */
    CAPTURE_ERR_BUSY     /* armed or triggered: stop it first */
} capture_error_t;

typedef struct {
    int16_t n_channels;
    int16_t signal[CAPTURE_CHANNELS];
    uint16_t length;     /* samples per channel */
    uint16_t decimation; /* one sample every this many control periods */
    capture_trigger_t trigger;
    int16_t trigger_signal;
    int16_t trigger_level; /* in the trigger signal's sample units */
    uint16_t pre_percent;  /* share of the record before the trigger */
} capture_setup_t;

typedef struct {
    volatile int16_t state; /* capture_state_t: written by the ISR once armed */
    capture_setup_t setup;
    uint16_t pre;           /* samples before the trigger */
    uint16_t dec_count;     /* periods since the last sample */
    uint16_t write;         /* next slot (sample index in the ring) */
    uint16_t count;         /* valid samples (at most length) */
    uint16_t post_left;     /* samples still to record after the trigger */
    uint16_t trigger_index; /* position of the trigger sample in the record */
    uint32_t first_period;  /* control-period count of the record's first sample */
    int16_t last_trigger_value;
    int16_t last_faulted; /* the fault trigger fires on the step into FAULT */
    bool have_last;
    int16_t buf[CAPTURE_BUFFER_WORDS];
} capture_t;

void capture_init(capture_t *c);

/* Background: arm with a new setup (the old record is discarded). */
capture_error_t capture_arm(capture_t *c, const capture_setup_t *s);

/* Background: back to IDLE, the record discarded. */
void capture_stop(capture_t *c);

/* ISR, every period: true when this period records (armed or triggered, and the decimation
 * count reached); only then the caller converts the channels' signals and calls
 * capture_sample. */
bool capture_due(capture_t *c);

/* ISR: record this period's samples: channel[k] of setup.signal[k], the trigger signal's
 * sample, the control-period count, and whether the drive is in FAULT. */
void capture_sample(capture_t *c, const int16_t channel[CAPTURE_CHANNELS], int16_t trigger_value,
                    uint32_t period, bool faulted);

/* Background, after DONE (or while recording: what is there): sample j (0 = oldest) of
 * channel ch; 0 outside the record. */
int16_t capture_read(const capture_t *c, int16_t ch, uint16_t j);

#endif /* CAPTURE_H */
