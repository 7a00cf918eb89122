/* Fault injection, see fault_inject.h. */
#include "fault_inject.h"

#include <string.h>

#include "drive/drive.h"

/* Injection magnitudes: each well past its threshold (docs/faults.md), none absurd. */
#define FAULT_OVERVOLTAGE_V 760.0    /* regenerative surge, limit 720 V */
#define FAULT_UNDERVOLTAGE_V 300.0   /* supply sag, limit 350 V */
#define FAULT_OVERHAULING_NM (-25.0) /* load drives the shaft: 3x rated, against 8.4 N*m */
#define FAULT_ENCODER_JUMP_TURN 0.25 /* electrical turns the position reading slips */
#define FAULT_OFFSET_COUNTS 300      /* phase B offset at power-up, tolerance 200 */
#define FAULT_SENSOR_GAIN 0.5        /* phase B sensor reads half (burden resistor fault) */
#define FAULT_OPEN_R_OHM 2000.0      /* phase C connection open: 2 kohm in series */
#define FAULT_OPEN_STEP_S 2e-6       /* RK4 sub-step that keeps the 2 kohm phase stable */

static void sim_fault_active_plant(const sim_fault_state_t *s, plant_params_t *p);

static const sim_fault_info_t fault_table[SIM_FAULT_COUNT] = {
    {NULL, NULL, DRIVE_FAULT_NONE, 0.0},
    {"overcurrent",
     "gate of leg A stuck on (a gate-driver input fault; the trip disables the drivers)",
     DRIVE_FAULT_OVERCURRENT, 5.0},
    {"dc-overvoltage", "DC link surges from 540 V to 760 V", DRIVE_FAULT_DC_OVERVOLTAGE, 1.0},
    {"dc-undervoltage", "DC link sags from 540 V to 300 V", DRIVE_FAULT_DC_UNDERVOLTAGE, 2.0},
    {"overspeed", "overhauling load: -25 N*m on the shaft", DRIVE_FAULT_OVERSPEED, 80.0},
    {"encoder-loss", "encoder signals stop at speed (cable cut); no index or counter error",
     DRIVE_FAULT_ENCODER, 15.0},
    {"encoder-jump", "position reading slips a quarter electrical turn", DRIVE_FAULT_ENCODER, 1.0},
    {"encoder-index", "encoder interface reports a counting error (lost index)",
     DRIVE_FAULT_ENCODER, 1.0},
    {"adc-rail", "DC-link voltage channel reads full scale (sensor output shorted to its supply)",
     DRIVE_FAULT_ADC_RAIL, 1.0},
    {"adc-stuck", "ADC result registers stop updating while conversions are still flagged",
     DRIVE_FAULT_ADC_STUCK, 10.0},
    {"adc-offset", "phase B sensor offset +300 counts from power-up (found by the calibration)",
     DRIVE_FAULT_ADC_OFFSET, 110.0},
    {"current-sum", "phase B current sensor gain drops to 0.5", DRIVE_FAULT_CURRENT_SUM, 20.0},
    {"open-phase", "phase C connection opens (2 kohm in series)", DRIVE_FAULT_OPEN_PHASE, 100.0},
    {"overrun", "control ISR runs past its period from the injection on", DRIVE_FAULT_OVERRUN, 0.5},
};

const sim_fault_info_t *sim_fault_info(sim_fault_t f)
{
    if (f <= SIM_FAULT_NONE || f >= SIM_FAULT_COUNT) {
        return NULL;
    }
    return &fault_table[f];
}

sim_fault_t sim_fault_from_scenario(const char *scenario)
{
    int k;
    if (!scenario || strncmp(scenario, "fault-", 6) != 0) {
        return SIM_FAULT_NONE;
    }
    for (k = 1; k < (int)SIM_FAULT_COUNT; k++) {
        if (strcmp(scenario + 6, fault_table[k].name) == 0) {
            return (sim_fault_t)k;
        }
    }
    return SIM_FAULT_NONE;
}

bool sim_fault_at_power_up(sim_fault_t f) { return f == SIM_FAULT_ADC_OFFSET; }

void sim_fault_begin(sim_fault_state_t *s, sim_fault_t kind, double t_inject)
{
    memset(s, 0, sizeof *s);
    s->kind = kind;
    s->t_inject = t_inject;
    s->active = (kind != SIM_FAULT_NONE) && sim_fault_at_power_up(kind);
    s->open_phase = 2;
    s->second_phase = -1;
}

void sim_fault_open_phases(sim_fault_state_t *s, int phase, int second_phase, double t_second,
                           bool exact)
{
    s->open_phase = phase;
    s->second_phase = second_phase;
    s->t_second = t_second;
    s->open_exact = exact;
}

/* A phase connection opens: 2 kohm in series (RK4 steps short enough for the stiff circuit), or
 * an open circuit. */
static void sim_fault_open_connection(const sim_fault_state_t *s, int phase, plant_params_t *p)
{
    if (s->open_exact) {
        p->phase_open[phase] = true;
        return;
    }
    p->phase_extra_r_ohm[phase] = FAULT_OPEN_R_OHM;
    if (p->max_step_s > FAULT_OPEN_STEP_S) {
        p->max_step_s = FAULT_OPEN_STEP_S;
    }
}

bool sim_fault_update(sim_fault_state_t *s, double t)
{
    if (s->active && s->second_phase >= 0 && !s->second_active && t >= s->t_second) {
        s->second_active = true;
        return true;
    }
    if (s->active || s->kind == SIM_FAULT_NONE || t < s->t_inject) {
        return false;
    }
    s->active = true;
    return true;
}

/* Legs switched off for good: where the fault broke the connection the phase is open (its
 * resistance then carries nothing; without one left the stiff small step is not needed); the
 * others float on their diodes (returned). */
static uint16_t sim_fault_isolated(const plant_params_t *healthy, uint16_t isolated,
                                   plant_params_t *p)
{
    uint16_t floating = 0u;
    bool extra = false;
    int k;
    for (k = 0; k < PLANT_PHASES; k++) {
        if ((((unsigned)isolated >> k) & 1u) != 0u &&
            (p->phase_extra_r_ohm[k] != 0.0 || p->phase_open[k])) {
            p->phase_open[k] = true;
            p->phase_extra_r_ohm[k] = 0.0;
        } else if ((((unsigned)isolated >> k) & 1u) != 0u) {
            floating |= (uint16_t)(1u << k);
        }
        extra = extra || p->phase_extra_r_ohm[k] != 0.0;
    }
    if (!extra) {
        p->max_step_s = healthy->max_step_s;
    }
    if (floating != 0u) {
        p->integrator = PLANT_INTEGRATOR_RK4;
    }
    return floating;
}

uint16_t sim_fault_plant(const sim_fault_state_t *s, const plant_params_t *healthy,
                         uint16_t isolated, plant_params_t *p)
{
    *p = *healthy;
    if (s->active) {
        sim_fault_active_plant(s, p);
    }
    return (isolated != 0u) ? sim_fault_isolated(healthy, isolated, p) : 0u;
}

static void sim_fault_active_plant(const sim_fault_state_t *s, plant_params_t *p)
{
    switch (s->kind) {
    case SIM_FAULT_DC_OVERVOLTAGE:
        p->vdc_v = FAULT_OVERVOLTAGE_V;
        break;
    case SIM_FAULT_DC_UNDERVOLTAGE:
        p->vdc_v = FAULT_UNDERVOLTAGE_V;
        break;
    case SIM_FAULT_OPEN_PHASE:
        sim_fault_open_connection(s, s->open_phase, p);
        if (s->second_active) {
            sim_fault_open_connection(s, s->second_phase, p);
        }
        break;
    default:
        break;
    }
}

double sim_fault_load(const sim_fault_state_t *s, double load_nm)
{
    return (s->active && s->kind == SIM_FAULT_OVERSPEED) ? FAULT_OVERHAULING_NM : load_nm;
}

void sim_fault_adc(sim_fault_state_t *s, hal_adc_sample_t *a)
{
    if (!s->active) {
        s->frozen_adc = *a; /* the last good words, for a freeze */
        return;
    }
    switch (s->kind) {
    case SIM_FAULT_ADC_RAIL:
        a->vdc = 4095u;
        break;
    case SIM_FAULT_ADC_STUCK:
        *a = s->frozen_adc;
        break;
    case SIM_FAULT_ADC_OFFSET: {
        const int32_t v = (int32_t)a->phase[1] + FAULT_OFFSET_COUNTS;
        a->phase[1] = (uint16_t)((v > 4095) ? 4095 : v);
        break;
    }
    case SIM_FAULT_CURRENT_SUM: {
        const double zero = 2048.0;
        const double v = zero + ((double)a->phase[1] - zero) * FAULT_SENSOR_GAIN;
        a->phase[1] = (uint16_t)(v + 0.5);
        break;
    }
    default:
        break;
    }
}

double sim_fault_encoder_angle(sim_fault_state_t *s, double theta_m)
{
    if (!(s->active && s->kind == SIM_FAULT_ENCODER_LOSS)) {
        return theta_m;
    }
    if (!s->encoder_frozen) {
        s->encoder_frozen = true;
        s->frozen_theta_m = theta_m;
    }
    return s->frozen_theta_m;
}

void sim_fault_encoder(const sim_fault_state_t *s, hal_encoder_sample_t *e)
{
    if (!s->active) {
        return;
    }
    if (s->kind == SIM_FAULT_ENCODER_JUMP && !s->encoder_rehomed) {
        e->elec_angle += (uint32_t)(FAULT_ENCODER_JUMP_TURN * 4294967296.0);
    } else if (s->kind == SIM_FAULT_ENCODER_INDEX) {
        e->healthy = false;
    }
}

void sim_fault_encoder_rehomed(sim_fault_state_t *s)
{
    if (s->active) {
        s->encoder_rehomed = true;
    }
}

void sim_fault_duty(const sim_fault_state_t *s, bool forced_off, double duty[6])
{
    if (s->active && s->kind == SIM_FAULT_OVERCURRENT && !forced_off) {
        duty[0] = 1.0;
    }
}

bool sim_fault_overrun(const sim_fault_state_t *s)
{
    return s->active && s->kind == SIM_FAULT_OVERRUN;
}
