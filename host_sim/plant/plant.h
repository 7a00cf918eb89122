/*
 * Host plant: asymmetrical six-phase PMSM (VSD model, brief §2) fed by a
 * two-level six-leg inverter with dead time, plus mechanics. Double precision,
 * SI units. Knows nothing of the controller or the HAL.
 *
 * Electrical state in the rotor frame (i_d, i_q) and the stationary x-y plane
 * (i_x, i_y); PM flux harmonics (5th, 7th) appear in x-y as
 *   psi_pm,xy = psi_5 [cos 5th, sin 5th] + psi_7 [cos 7th, -sin 7th].
 * Between switching instants the phase voltages are constant. Such an
 * interval is solved exactly at the speed held over the control period
 * (plant_exact.h, the default) or integrated with classical RK4 in sub-steps
 * no longer than plant_params_t.max_step_s (the reference, and the fallback
 * where the exact solution does not apply); plant_stepper.h chooses.
 *
 * Open-phase fault: phase_extra_r_ohm[k] adds a series resistance to phase k
 * (its drop projected onto the VSD planes; the zero-sequence part is taken by
 * the isolated neutral). A large value makes the model stiff: the fastest
 * eigenvalue is about 2 R_extra / (3 L) (at most that with L the smallest of
 * L_d, L_q, L_xy), and RK4 diverges once max_step_s times it exceeds ~2.8
 * (the default 50 us step does at 2 kohm). Callers injecting an open phase
 * must therefore reduce max_step_s themselves, e.g. to 2e-6 s for 2 kohm with
 * L_xy = 10 mH; the plant does not change it.
 *
 * Open phase: phase_open[k] makes phase k carry no current at all (a broken connection, or a
 * leg whose switches are off for good while its terminal stays within the rails). The open
 * terminal's voltage is whatever holds i_k = c_k . i at zero: a Lagrange multiplier along c_k
 * (c_k the phase's VSD row), solved with the derivative, so the currents evolve on the
 * constraint (plus a projection after each RK4 step against drift). Not stiff: RK4 with the
 * ordinary step. plant_open_commutate puts a state onto the constraint at once.
 */
#ifndef SIM_PLANT_H
#define SIM_PLANT_H

#include <stdbool.h>
#include <stdint.h>

#define PLANT_PHASES 6

typedef enum {
    PLANT_INTEGRATOR_EXACT = 0, /* exact interval solution at the period's held speed */
    PLANT_INTEGRATOR_RK4 = 1    /* classical RK4, free mechanics (reference) */
} plant_integrator_t;

typedef struct {
    /* machine (brief §6) */
    double r_ohm; /* stator resistance */
    double ld_h;
    double lq_h;
    double lxy_h;    /* x-y (leakage) inductance */
    double psi_f_wb; /* PM flux, fundamental */
    double psi5_wb;  /* PM flux 5th harmonic, seen in x-y */
    double psi7_wb;  /* PM flux 7th harmonic, seen in x-y */
    int pole_pairs;
    double j_kgm2; /* inertia */
    double b_nms;  /* viscous friction, N*m*s/rad */
    /* inverter */
    double vdc_v;
    double dead_time_s;
    /* faults: series resistance added to one phase (a loose terminal; ~2 kohm =
     * open circuit); 0 in normal runs. See the stiffness note above. */
    double phase_extra_r_ohm[PLANT_PHASES];
    bool phase_open[PLANT_PHASES]; /* the phase carries no current (see above) */
    /* numerics */
    plant_integrator_t integrator;
    double max_step_s; /* longest RK4 sub-step inside a constant-voltage interval */
    /* non-idealities, each on/off */
    bool dead_time_on;
    bool harmonics_on;
    bool adc_offset_on; /* random per-channel offset, uniform in +-adc_offset_counts */
    double adc_offset_counts;
    bool adc_gain_on; /* random per-channel gain error, uniform in +-adc_gain_error */
    double adc_gain_error;
    bool adc_noise_on; /* Gaussian noise, adc_noise_counts standard deviation */
    double adc_noise_counts;
    double current_sensor_span_a; /* phase-current sensors read -span .. +span A over the ADC's
                                   * range (the reference board's 20 A, hal_board.h); the drive
                                   * is told the same span (drive_set_current_span) */
    bool encoder_quant_on;        /* angle quantised to 1/(4*lines) turn; speed by edge timing */
    uint32_t encoder_lines;
    /* how the encoder sits on the shaft (docs/commissioning.md); defaults: index at the d axis,
     * counting up for a positive turn, seen from power-up */
    double encoder_offset_rad; /* electrical angle of the index to the d axis: the offset the
                                * drive must learn (FW_ENCODER_OFFSET); the index pulse comes at
                                * the mechanical angle encoder_offset_rad / pole_pairs */
    bool encoder_reversed;     /* channels A and B swapped: counts down for a positive turn */
    bool encoder_stuck;        /* the count never moves (a seized coupling, a dead encoder) */
} plant_params_t;

/* The sensor spans a board may have (the drive's DRIVE_CURRENT_SPAN_MIN_A..MAX_A, halved). */
#define PLANT_SENSOR_SPAN_MIN_A 2.0
#define PLANT_SENSOR_SPAN_MAX_A 200.0

/* Brief §6 values and the documented non-ideality defaults (all on). */
void plant_params_default(plant_params_t *p);

/* Empty string if usable, otherwise a short description of the first bad field. */
const char *plant_params_check(const plant_params_t *p);

typedef struct {
    double i_d, i_q, i_x, i_y; /* A */
    double omega_m;            /* mechanical speed, rad/s */
    double theta_m;            /* mechanical angle, rad, unwrapped */
    /* cos / sin of the electrical angle Pn * theta_m, carried along by the
     * integrator (small-angle rotations) to avoid libm calls per step.
     * Call plant_sync_angle() after writing theta_m directly. */
    double cos_e, sin_e;
} plant_state_t;

/* Recompute cos_e / sin_e from theta_m. */
void plant_sync_angle(const plant_params_t *p, plant_state_t *s);

/* Per-state derived quantities. */
typedef struct {
    double i_phase[PLANT_PHASES]; /* A..F */
    double i_alpha, i_beta;
    double psi_d, psi_q, psi_s; /* stator flux (fundamental plane) */
    double torque_nm;           /* total electromagnetic torque incl. x-y term */
    double theta_e;             /* electrical angle wrapped to [0, 2 pi) */
} plant_out_t;

/* Stationary-frame voltage [alpha, beta, x, y] (V) of switching state
 * `state` (S_A = bit 5, two isolated neutrals, amplitude-invariant VSD). */
void plant_vector_voltage(unsigned state, double vdc, double u[4]);

/* Angles of the six phases in the fundamental and the x-y plane. */
extern const double plant_phase_angle_rad[PLANT_PHASES];

void plant_outputs(const plant_params_t *p, const plant_state_t *s, plant_out_t *o);

/* Phase currents only (cheaper than plant_outputs; uses cos_e / sin_e). */
void plant_phase_currents(const plant_params_t *p, const plant_state_t *s, double i[PLANT_PHASES]);

/* Electromagnetic torque (dq part plus x-y harmonic part; uses cos_e / sin_e). */
double plant_torque(const plant_params_t *p, const plant_state_t *s);

/* Integrate for h seconds with the constant stationary-frame voltage
 * u = [u_alpha, u_beta, u_x, u_y] (V) and load torque t_load. With
 * lock_mech the speed is held (rotor driven by a stiff dynamometer).
 * Uses ceil(h / max_step) RK4 sub-steps; re-synchronises cos_e / sin_e
 * from theta_m first. Returns the torque integral
 * (N*m*s) over the interval (Simpson on the RK4 stages). */
double plant_integrate(const plant_params_t *p, plant_state_t *s, const double u[4], double t_load,
                       bool lock_mech, double h);

/* As plant_integrate, without the angle re-synchronisation (inner loops). */
double plant_integrate_nosync(const plant_params_t *p, plant_state_t *s, const double u[4],
                              double t_load, bool lock_mech, double h);

/* With the phases of p->phase_open open: removes their currents from s at once, along the
 * directions their terminals' voltages act in (M^-1 c_k), as a commutation through the
 * freewheeling diodes would, in zero time. Uses cos_e / sin_e. */
void plant_open_commutate(const plant_params_t *p, plant_state_t *s);

/* The terminal voltage (V, against the negative DC rail) that holds an open phase at zero
 * current while the legs apply the stationary-frame voltage u computed with the open leg's
 * switch state 0 (plant_vector_voltage): 3 times the multiplier along c_k. Single open phase
 * only (the drive runs with one); the state must lie on the constraint. */
double plant_open_terminal_voltage(const plant_params_t *p, const plant_state_t *s, int phase,
                                   const double u[4]);

/* One RK4 step exactly (no sub-stepping, no re-synchronisation). */
double plant_rk4_step(const plant_params_t *p, plant_state_t *s, const double u[4], double t_load,
                      bool lock_mech, double h);

#endif /* SIM_PLANT_H */
