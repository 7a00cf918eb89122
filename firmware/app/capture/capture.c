/* The capture buffer, see capture.h. */
#include "capture.h"

#include "ctl_barrier.h"
#include "sixphase_placement.h"

void capture_init(capture_t *c)
{
    c->state = CAPTURE_IDLE;
    c->count = 0u;
    c->write = 0u;
    c->setup.n_channels = 0;
    c->setup.length = 0u;
}

static capture_error_t capture_check(const capture_setup_t *s)
{
    int16_t k;
    if (s->n_channels < 1 || s->n_channels > CAPTURE_CHANNELS || s->trigger_signal < 0 ||
        s->trigger_signal >= CAPTURE_SIGNAL_COUNT) {
        return CAPTURE_ERR_SIGNAL;
    }
    for (k = 0; k < s->n_channels; k++) {
        if (s->signal[k] < 0 || s->signal[k] >= CAPTURE_SIGNAL_COUNT) {
            return CAPTURE_ERR_SIGNAL;
        }
    }
    if (s->decimation == 0u || s->length == 0u || s->pre_percent > 100u ||
        (int16_t)s->trigger < 0 || s->trigger >= CAPTURE_TRIGGER_MODES) {
        return CAPTURE_ERR_SETTING;
    }
    if ((uint32_t)s->length * (uint32_t)s->n_channels > (uint32_t)CAPTURE_BUFFER_WORDS) {
        return CAPTURE_ERR_NO_ROOM;
    }
    return CAPTURE_OK;
}

capture_error_t capture_arm(capture_t *c, const capture_setup_t *s)
{
    const capture_error_t e = capture_check(s);
    if (e != CAPTURE_OK) {
        return e;
    }
    if (c->state == CAPTURE_ARMED || c->state == CAPTURE_TRIGGERED) {
        return CAPTURE_ERR_BUSY;
    }
    c->setup = *s;
    /* the trigger sample itself is the first after the pre-trigger share */
    c->pre = (uint16_t)(((uint32_t)s->length * s->pre_percent) / 100u);
    if (c->pre >= s->length) {
        c->pre = (uint16_t)(s->length - 1u);
    }
    if (s->trigger == CAPTURE_TRIGGER_IMMEDIATE) {
        c->pre = 0u;
    }
    c->dec_count = (uint16_t)(s->decimation - 1u); /* the next period records */
    c->write = 0u;
    c->count = 0u;
    c->trigger_index = 0u;
    c->have_last = false;
    CTL_COMPILER_BARRIER(); /* the setup is complete before the ISR sees ARMED */
    c->state = CAPTURE_ARMED;
    return CAPTURE_OK;
}

void capture_stop(capture_t *c) { c->state = CAPTURE_IDLE; }

SIXPHASE_RAMFUNC bool capture_due(capture_t *c)
{
    if (c->state != CAPTURE_ARMED && c->state != CAPTURE_TRIGGERED) {
        return false;
    }
    if (++c->dec_count < c->setup.decimation) {
        return false;
    }
    c->dec_count = 0u;
    return true;
}

SIXPHASE_RAMFUNC static bool capture_triggered(capture_t *c, int16_t v, bool faulted)
{
    const capture_setup_t *s = &c->setup;
    bool hit = false;
    if (s->trigger == CAPTURE_TRIGGER_FAULT) {
        /* entering FAULT, whether or not the pre-trigger share is full: never miss a trip (a
         * drive already in FAULT when armed triggers at its next trip) */
        hit = faulted && c->have_last && c->last_faulted == 0;
        c->last_faulted = faulted ? 1 : 0;
        c->have_last = true;
        return hit;
    }
    if (c->count > c->pre || s->trigger == CAPTURE_TRIGGER_IMMEDIATE) {
        if (s->trigger == CAPTURE_TRIGGER_IMMEDIATE) {
            hit = true;
        } else if (c->have_last && s->trigger == CAPTURE_TRIGGER_RISING) {
            hit = c->last_trigger_value < s->trigger_level && v >= s->trigger_level;
        } else if (c->have_last) {
            hit = c->last_trigger_value > s->trigger_level && v <= s->trigger_level;
        }
    }
    c->last_trigger_value = v;
    c->have_last = true;
    return hit;
}

SIXPHASE_RAMFUNC void capture_sample(capture_t *c, const int16_t channel[CAPTURE_CHANNELS],
                                     int16_t trigger_value, uint32_t period, bool faulted)
{
    const capture_setup_t *s = &c->setup;
    int16_t k;
    for (k = 0; k < s->n_channels; k++) {
        c->buf[(uint32_t)c->write * (uint32_t)s->n_channels + (uint32_t)k] = channel[k];
    }
    c->write = (uint16_t)((c->write + 1u) % s->length);
    if (c->count < s->length) {
        c->count++;
    }
    if (c->state == CAPTURE_ARMED && capture_triggered(c, trigger_value, faulted)) {
        c->trigger_index = (uint16_t)(c->count - 1u);
        c->post_left = (uint16_t)(s->length - 1u - c->pre);
        if (c->trigger_index > c->pre) { /* more history than the pre-trigger share: */
            c->trigger_index = c->pre;   /* the oldest of it is overwritten by the post part */
        }
        c->first_period = period - (uint32_t)c->trigger_index * s->decimation;
        c->state = CAPTURE_TRIGGERED;
    } else if (c->state == CAPTURE_TRIGGERED && c->post_left > 0u) {
        c->post_left--;
    }
    if (c->state == CAPTURE_TRIGGERED && c->post_left == 0u) {
        c->state = CAPTURE_DONE;
    }
}

int16_t capture_read(const capture_t *c, int16_t ch, uint16_t j)
{
    const capture_setup_t *s = &c->setup;
    uint16_t oldest;
    if (ch < 0 || ch >= s->n_channels || j >= c->count || s->length == 0u) {
        return 0;
    }
    oldest = (uint16_t)((c->write + s->length - c->count) % s->length);
    return c->buf[(uint32_t)((oldest + j) % s->length) * (uint32_t)s->n_channels + (uint32_t)ch];
}
