/*
 * The bridge's configuration and a control period's peripheral bus on the wire, for a
 * processor-in-the-loop target (firmware/link/sxlink_pil.h): the host encodes, the target
 * (firmware/pil) decodes into the same types and runs the same bridge on them, so both sides
 * configure and step their drives from identical values. Portable C: no double wider than the
 * target's, no 8-bit storage (bytes held in uint16_t, as sxlink does).
 */
#ifndef SIM_CTL_WIRE_H
#define SIM_CTL_WIRE_H

#include <stdbool.h>
#include <stdint.h>

#include "hal_sim.h"
#include "sim_ctl.h"
#include "sxlink_pil.h"

/* Bytes per configuration field kind: INT as i16, REAL as IEEE single, BOOL as u8. */
#define SIM_CTL_WIRE_BYTES_INT 2u
#define SIM_CTL_WIRE_BYTES_REAL 4u
#define SIM_CTL_WIRE_BYTES_BOOL 1u
#define SIM_CTL_WIRE_SIZE_TERM(kind, name) +SIM_CTL_WIRE_BYTES_##kind
enum { SIM_CTL_CONFIG_IMAGE_BYTES = 0 SIM_CTL_CONFIG_FIELDS(SIM_CTL_WIRE_SIZE_TERM) };
#undef SIM_CTL_WIRE_SIZE_TERM

/* The configuration's image (SIM_CTL_CONFIG_IMAGE_BYTES bytes, the list's order), and back. An
 * INT outside int16 is held to it; a REAL is rounded to single precision (the drive takes
 * floats: the host configures its own drive from the decoded image, so both sides agree). */
void sim_ctl_config_encode(const sim_ctl_config_t *c, uint16_t *image);
void sim_ctl_config_decode(const uint16_t *image, sim_ctl_config_t *c);

/* A REAL as its IEEE single bits, and back. */
uint32_t sim_ctl_wire_real_bits(double v);
double sim_ctl_wire_real_of(uint32_t bits);

/* The peripherals' set-up (INIT request, SXL_PIL_INIT_BYTES) from a bus the host's main set up,
 * and applied on the target (hal_sim_reset, then the HAL's init calls): false when the HAL
 * refuses it. */
void sim_ctl_wire_put_setup(const hal_sim_bus_t *b, uint16_t *payload);
bool sim_ctl_wire_apply_setup(const uint16_t *payload);

/* A period's inputs (the plant's part of the bus) into a STEP payload (SXL_PIL_IN_BYTES), and
 * from one onto a bus; returns the sequence number. */
void sim_ctl_wire_put_inputs(const hal_sim_bus_t *b, uint16_t seq, uint16_t *payload);
uint16_t sim_ctl_wire_take_inputs(const uint16_t *payload, hal_sim_bus_t *b);

/* What a period left on the bus (the application's part) and what it cost on the target. */
typedef struct {
    uint16_t seq;
    uint16_t duty[HAL_PWM_LEGS];
    uint16_t flags; /* SXL_PIL_OUT_* bits */
    uint16_t isolated;
    uint32_t encoder_offset;
    uint16_t state;  /* drive_state_t */
    uint16_t faults; /* latched, ctl_fault_t bits */
    uint32_t cycles; /* the ISR, entry to end */
    uint32_t stage[SXL_PIL_OUT_STAGE_COUNT];
} sim_ctl_wire_out_t;

/* The bus's outputs into o (duties, flags, isolated legs, encoder offset), and o's onto a bus. */
void sim_ctl_wire_outputs_of_bus(const hal_sim_bus_t *b, sim_ctl_wire_out_t *o);
void sim_ctl_wire_outputs_to_bus(const sim_ctl_wire_out_t *o, hal_sim_bus_t *b);

/* A STEP reply's payload after the result byte (SXL_PIL_OUT_BYTES - 1 bytes from payload[1]),
 * and back. */
void sim_ctl_wire_put_outputs(const sim_ctl_wire_out_t *o, uint16_t *payload);
void sim_ctl_wire_get_outputs(const uint16_t *payload, sim_ctl_wire_out_t *o);

/* Argument bytes of a call record's code (SXL_PIL_CALL_LIST); -1 for an unknown code. */
int16_t sim_ctl_wire_call_args(uint16_t code);

#endif /* SIM_CTL_WIRE_H */
