#include "sim_ctl_wire.h"

#include "sxlink.h"

static uint16_t put_INT(uint16_t *image, uint16_t pos, int v)
{
    const int held = (v > INT16_MAX) ? INT16_MAX : ((v < INT16_MIN) ? INT16_MIN : v);
    sxl_put_i16(&image[pos], (int16_t)held);
    return (uint16_t)(pos + SIM_CTL_WIRE_BYTES_INT);
}
static uint16_t put_REAL(uint16_t *image, uint16_t pos, double v)
{
    sxl_put_u32(&image[pos], sim_ctl_wire_real_bits(v));
    return (uint16_t)(pos + SIM_CTL_WIRE_BYTES_REAL);
}
static uint16_t put_BOOL(uint16_t *image, uint16_t pos, bool v)
{
    image[pos] = v ? 1u : 0u;
    return (uint16_t)(pos + SIM_CTL_WIRE_BYTES_BOOL);
}
static uint16_t get_INT(const uint16_t *image, uint16_t pos, int *v)
{
    *v = (int)sxl_get_i16(&image[pos]);
    return (uint16_t)(pos + SIM_CTL_WIRE_BYTES_INT);
}
static uint16_t get_REAL(const uint16_t *image, uint16_t pos, double *v)
{
    *v = sim_ctl_wire_real_of(sxl_get_u32(&image[pos]));
    return (uint16_t)(pos + SIM_CTL_WIRE_BYTES_REAL);
}
static uint16_t get_BOOL(const uint16_t *image, uint16_t pos, bool *v)
{
    *v = image[pos] != 0u;
    return (uint16_t)(pos + SIM_CTL_WIRE_BYTES_BOOL);
}

void sim_ctl_config_encode(const sim_ctl_config_t *c, uint16_t *image)
{
    uint16_t pos = 0u;
#define SIM_CTL_WIRE_PUT(kind, name) pos = put_##kind(image, pos, c->name);
    SIM_CTL_CONFIG_FIELDS(SIM_CTL_WIRE_PUT)
#undef SIM_CTL_WIRE_PUT
    (void)pos;
}

void sim_ctl_config_decode(const uint16_t *image, sim_ctl_config_t *c)
{
    uint16_t pos = 0u;
#define SIM_CTL_WIRE_GET(kind, name) pos = get_##kind(image, pos, &c->name);
    SIM_CTL_CONFIG_FIELDS(SIM_CTL_WIRE_GET)
#undef SIM_CTL_WIRE_GET
    (void)pos;
}

uint32_t sim_ctl_wire_real_bits(double v)
{
    union {
        float f;
        uint32_t u;
    } x;
    x.f = (float)v;
    return x.u;
}

double sim_ctl_wire_real_of(uint32_t bits)
{
    union {
        float f;
        uint32_t u;
    } x;
    x.u = bits;
    return (double)x.f;
}

static uint16_t flag(bool on, uint16_t bit) { return on ? bit : 0u; }

void sim_ctl_wire_put_setup(const hal_sim_bus_t *b, uint16_t *payload)
{
    sxl_put_u32(&payload[SXL_PIL_INIT_CARRIER], b->carrier_hz);
    sxl_put_u32(&payload[SXL_PIL_INIT_DEAD_TIME], b->dead_time_ns);
    sxl_put_u32(&payload[SXL_PIL_INIT_LINES], b->encoder_lines);
    sxl_put_u16(&payload[SXL_PIL_INIT_POLE_PAIRS], b->encoder_pole_pairs);
    sxl_put_u32(&payload[SXL_PIL_INIT_OFFSET], b->encoder_elec_offset);
}

bool sim_ctl_wire_apply_setup(const uint16_t *payload)
{
    hal_sim_reset();
    return hal_pwm_init(sxl_get_u32(&payload[SXL_PIL_INIT_CARRIER]),
                        sxl_get_u32(&payload[SXL_PIL_INIT_DEAD_TIME])) &&
           hal_adc_init() &&
           hal_encoder_init(sxl_get_u32(&payload[SXL_PIL_INIT_LINES]),
                            sxl_get_u16(&payload[SXL_PIL_INIT_POLE_PAIRS]),
                            sxl_get_u32(&payload[SXL_PIL_INIT_OFFSET]));
}

void sim_ctl_wire_put_inputs(const hal_sim_bus_t *b, uint16_t seq, uint16_t *payload)
{
    uint16_t k;
    sxl_put_u16(&payload[SXL_PIL_IN_SEQ], seq);
    for (k = 0u; k < HAL_ADC_PHASES; k++) {
        sxl_put_u16(&payload[SXL_PIL_IN_ADC + 2u * k], b->adc.phase[k]);
    }
    sxl_put_u16(&payload[SXL_PIL_IN_ADC + 2u * HAL_ADC_PHASES], b->adc.vdc);
    sxl_put_u32(&payload[SXL_PIL_IN_ANGLE], b->encoder.elec_angle);
    sxl_put_i32(&payload[SXL_PIL_IN_SPEED], b->encoder.mech_speed_q16);
    sxl_put_i32(&payload[SXL_PIL_IN_POSITION], b->encoder.position);
    payload[SXL_PIL_IN_FLAGS] = (uint16_t)(flag(b->adc_fresh, SXL_PIL_IN_ADC_FRESH) |
                                           flag(b->encoder.healthy, SXL_PIL_IN_ENC_HEALTHY) |
                                           flag(b->encoder.index_seen, SXL_PIL_IN_ENC_INDEX_SEEN) |
                                           flag(b->hw_trip, SXL_PIL_IN_HW_TRIP) |
                                           flag(b->forced_off, SXL_PIL_IN_FORCED_OFF) |
                                           flag(b->encoder_homing_lost, SXL_PIL_IN_HOMING_LOST));
}

uint16_t sim_ctl_wire_take_inputs(const uint16_t *payload, hal_sim_bus_t *b)
{
    const uint16_t f = payload[SXL_PIL_IN_FLAGS];
    uint16_t k;
    for (k = 0u; k < HAL_ADC_PHASES; k++) {
        b->adc.phase[k] = sxl_get_u16(&payload[SXL_PIL_IN_ADC + 2u * k]);
    }
    b->adc.vdc = sxl_get_u16(&payload[SXL_PIL_IN_ADC + 2u * HAL_ADC_PHASES]);
    b->encoder.elec_angle = sxl_get_u32(&payload[SXL_PIL_IN_ANGLE]);
    b->encoder.mech_speed_q16 = sxl_get_i32(&payload[SXL_PIL_IN_SPEED]);
    b->encoder.position = sxl_get_i32(&payload[SXL_PIL_IN_POSITION]);
    b->adc_fresh = (f & SXL_PIL_IN_ADC_FRESH) != 0u;
    b->encoder.healthy = (f & SXL_PIL_IN_ENC_HEALTHY) != 0u;
    b->encoder.index_seen = (f & SXL_PIL_IN_ENC_INDEX_SEEN) != 0u;
    b->hw_trip = (f & SXL_PIL_IN_HW_TRIP) != 0u;
    b->forced_off = (f & SXL_PIL_IN_FORCED_OFF) != 0u;
    b->encoder_homing_lost = (f & SXL_PIL_IN_HOMING_LOST) != 0u;
    return sxl_get_u16(&payload[SXL_PIL_IN_SEQ]);
}

void sim_ctl_wire_outputs_of_bus(const hal_sim_bus_t *b, sim_ctl_wire_out_t *o)
{
    uint16_t k;
    for (k = 0u; k < HAL_PWM_LEGS; k++) {
        o->duty[k] = b->duty[k];
    }
    o->flags = (uint16_t)(flag(b->forced_off, SXL_PIL_OUT_FORCED_OFF) |
                          flag(b->adc_fresh, SXL_PIL_OUT_ADC_FRESH) |
                          flag(b->encoder_homing_lost, SXL_PIL_OUT_HOMING_LOST) |
                          flag(b->pwm_initialised, SXL_PIL_OUT_PWM_INIT) |
                          flag(b->hw_trip, SXL_PIL_OUT_HW_TRIP));
    o->isolated = (uint16_t)(b->isolated & 0x3Fu);
    o->encoder_offset = b->encoder_elec_offset;
}

void sim_ctl_wire_outputs_to_bus(const sim_ctl_wire_out_t *o, hal_sim_bus_t *b)
{
    uint16_t k;
    for (k = 0u; k < HAL_PWM_LEGS; k++) {
        b->duty[k] = o->duty[k];
    }
    b->forced_off = (o->flags & SXL_PIL_OUT_FORCED_OFF) != 0u;
    b->adc_fresh = (o->flags & SXL_PIL_OUT_ADC_FRESH) != 0u;
    b->encoder_homing_lost = (o->flags & SXL_PIL_OUT_HOMING_LOST) != 0u;
    b->pwm_initialised = (o->flags & SXL_PIL_OUT_PWM_INIT) != 0u;
    b->hw_trip = (o->flags & SXL_PIL_OUT_HW_TRIP) != 0u;
    b->isolated = o->isolated;
    b->encoder_elec_offset = o->encoder_offset;
}

static void put_u24(uint16_t *p, uint32_t v)
{
    const uint32_t held = (v > 0xFFFFFFu) ? 0xFFFFFFu : v;
    p[0] = (uint16_t)(held & 0xFFu);
    p[1] = (uint16_t)((held >> 8) & 0xFFu);
    p[2] = (uint16_t)((held >> 16) & 0xFFu);
}

static uint32_t get_u24(const uint16_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16);
}

void sim_ctl_wire_put_outputs(const sim_ctl_wire_out_t *o, uint16_t *payload)
{
    uint16_t k;
    sxl_put_u16(&payload[SXL_PIL_OUT_SEQ], o->seq);
    for (k = 0u; k < HAL_PWM_LEGS; k++) {
        sxl_put_u16(&payload[SXL_PIL_OUT_DUTY + 2u * k], o->duty[k]);
    }
    payload[SXL_PIL_OUT_FLAGS] = (uint16_t)(o->flags & 0xFFu);
    payload[SXL_PIL_OUT_ISOLATED] = (uint16_t)(o->isolated & 0xFFu);
    sxl_put_u32(&payload[SXL_PIL_OUT_OFFSET], o->encoder_offset);
    payload[SXL_PIL_OUT_STATE] = (uint16_t)(o->state & 0xFFu);
    sxl_put_u16(&payload[SXL_PIL_OUT_FAULTS], o->faults);
    sxl_put_u32(&payload[SXL_PIL_OUT_CYCLES], o->cycles);
    for (k = 0u; k < SXL_PIL_OUT_STAGE_COUNT; k++) {
        put_u24(&payload[SXL_PIL_OUT_STAGES + 3u * k], o->stage[k]);
    }
}

void sim_ctl_wire_get_outputs(const uint16_t *payload, sim_ctl_wire_out_t *o)
{
    uint16_t k;
    o->seq = sxl_get_u16(&payload[SXL_PIL_OUT_SEQ]);
    for (k = 0u; k < HAL_PWM_LEGS; k++) {
        o->duty[k] = sxl_get_u16(&payload[SXL_PIL_OUT_DUTY + 2u * k]);
    }
    o->flags = payload[SXL_PIL_OUT_FLAGS];
    o->isolated = payload[SXL_PIL_OUT_ISOLATED];
    o->encoder_offset = sxl_get_u32(&payload[SXL_PIL_OUT_OFFSET]);
    o->state = payload[SXL_PIL_OUT_STATE];
    o->faults = sxl_get_u16(&payload[SXL_PIL_OUT_FAULTS]);
    o->cycles = sxl_get_u32(&payload[SXL_PIL_OUT_CYCLES]);
    for (k = 0u; k < SXL_PIL_OUT_STAGE_COUNT; k++) {
        o->stage[k] = get_u24(&payload[SXL_PIL_OUT_STAGES + 3u * k]);
    }
}

int16_t sim_ctl_wire_call_args(uint16_t code)
{
#define SIM_CTL_WIRE_ARGS(name, c, bytes)                                                          \
    if (code == (uint16_t)(c)) {                                                                   \
        return (int16_t)(bytes);                                                                   \
    }
    SXL_PIL_CALL_LIST(SIM_CTL_WIRE_ARGS)
#undef SIM_CTL_WIRE_ARGS
    return -1;
}
