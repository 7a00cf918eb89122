/* Scenario plans, see scenario.h. */
#include "scenario.h"

#include <math.h>

#include "plant/sim_rng.h"
#include "commission/commission.h"

/* Speeds, load, length and window of each scenario (docs/simulator.md, Scenarios). */
static void sim_plan_scenario(const sim_config_t *c, sim_plan_t *pl)
{
    const bool speed_set = c->speed_rpm > -1e9;
    const bool load_set = c->load_nm > -1e9;
    switch (c->scenario) {
    case SIM_SCEN_LOAD_STEP:
        pl->speed = speed_set ? c->speed_rpm : 1500.0;
        pl->speed0 = pl->speed;
        pl->load0 = 0.0;
        pl->load = load_set ? c->load_nm : 7.0;
        pl->duration = 0.45;
        pl->t_event = 0.2;
        pl->window = 0.15;
        break;
    case SIM_SCEN_ACCEL:
        pl->speed = speed_set ? c->speed_rpm : 800.0;
        pl->speed0 = 0.0;
        pl->load0 = pl->load = load_set ? c->load_nm : 0.0;
        pl->duration = 0.5;
        pl->t_event = 0.05;
        pl->window = 0.25;
        break;
    case SIM_SCEN_REVERSAL:
        pl->speed = speed_set ? -fabs(c->speed_rpm) : -800.0;
        pl->speed0 = -pl->speed;
        pl->load0 = pl->load = load_set ? c->load_nm : 0.0;
        pl->duration = 0.65;
        pl->t_event = 0.1;
        pl->window = 0.25;
        break;
    case SIM_SCEN_COMMISSION: /* at standstill, no load; duration: a bound on the sequence */
        pl->speed = pl->speed0 = 0.0;
        pl->load0 = pl->load = load_set ? c->load_nm : 0.0;
        /* every step may run to its time bound: the sequence ends, never the simulation */
        pl->duration = (double)comm_time_bound_s((uint16_t)c->commission_steps) + 1.0;
        pl->t_event = 0.0;
        pl->window = 0.01;
        break;
    case SIM_SCEN_STEADY:
    default:
        pl->speed = speed_set ? c->speed_rpm : 1500.0;
        pl->speed0 = pl->speed;
        pl->load0 = pl->load = load_set ? c->load_nm : 7.0;
        pl->duration = 0.5;
        pl->t_event = 0.0;
        pl->window = 0.2;
        break;
    }
}

void sim_plan(const sim_config_t *c, sim_plan_t *pl)
{
    sim_plan_scenario(c, pl);
    if (c->fault != SIM_FAULT_NONE && c->scenario != SIM_SCEN_COMMISSION) {
        pl->duration = SIM_FAULT_DURATION_S; /* rated operation, injection, aftermath */
    }
    if ((c->fault == SIM_FAULT_OPEN_PHASE && c->open_phase_action == 1) || c->isolate_leg >= 0) {
        pl->duration = SIM_OPEN_PHASE_DURATION_S; /* and five-leg operation after it */
    }
    if (c->duration_s > 0.0) {
        pl->duration = c->duration_s;
    }
    /* A rated-load run needs torque headroom above the load plus friction: with
     * the limit at rated torque the speed loop saturates and the speed sags.
     * Loaded scenarios therefore get 1.2x rated (8.4 N*m); the no-load
     * transients keep the rated 7 N*m the paper's transient times imply. */
    if (c->torque_limit_nm > 0.0) {
        pl->torque_limit = c->torque_limit_nm;
    } else {
        pl->torque_limit = (fabs(pl->load) > 0.0 || fabs(pl->load0) > 0.0) ? 8.4 : 7.0;
    }
    if (pl->window > 0.5 * pl->duration) {
        pl->window = 0.5 * pl->duration;
    }
    pl->theta0_rad = 0.0;
    if (c->scenario == SIM_SCEN_COMMISSION) { /* its own stream: the ADC's draws stay as they are */
        sim_rng_t rng;
        sim_rng_seed(&rng, c->seed ^ 0x5EEDC0FFEEull);
        pl->theta0_rad = 2.0 * 3.14159265358979323846 * sim_rng_uniform(&rng);
    }
}

double sim_load_at(const sim_config_t *c, const sim_plan_t *pl, double t)
{
    if (c->scenario == SIM_SCEN_STEADY) {
        const double ramp = 0.02; /* rated load ramped in over 20 ms */
        return (t < ramp) ? pl->load * t / ramp : pl->load;
    }
    return (t < pl->t_event) ? pl->load0 : pl->load;
}
