/* Names of the drive states, drive fault codes and protection fault bits carried by the
 * protocol, from the application's lists (sxlink_faults.h, sxlink_states.h). */
#include "sxlink.h"

/* From the application's lists (sxlink_states.h), by number. */
#define NAME_BY_NUMBER(id, number, name) [number] = name,
static const char *const state_names[SXL_STATE_NAME_COUNT] = {SXL_STATE_LIST(NAME_BY_NUMBER)};
static const char *const run_refusal_names[SXL_RUN_REFUSAL_NAME_COUNT] = {
    SXL_RUN_REFUSAL_LIST(NAME_BY_NUMBER)};
#undef NAME_BY_NUMBER

/* From the one fault list (sxlink_faults.h), by code and by bit number. */
#define NAME_BY_CODE(name, code, bit_name, bit, text) [code] = #name,
#define TEXT_BY_CODE(name, code, bit_name, bit, text) [code] = text,
#define NAME_BY_BIT(name, code, bit_name, bit, text) [bit] = #bit_name,
static const char *const fault_names[SXL_FAULT_CODE_COUNT] = {[0] = "NONE",
                                                              SXL_FAULT_LIST(NAME_BY_CODE)};
static const char *const fault_texts[SXL_FAULT_CODE_COUNT] = {[0] = "",
                                                              SXL_FAULT_LIST(TEXT_BY_CODE)};
static const char *const fault_bit_names[SXL_FAULT_BIT_COUNT] = {SXL_FAULT_LIST(NAME_BY_BIT)};
#undef NAME_BY_CODE
#undef TEXT_BY_CODE
#undef NAME_BY_BIT

/* Commissioning's lists (sxlink_commission.h), by number. */
#define COMM_NAME(id, number, name, ...) [number] = name,
#define COMM_TEXT(id, number, name, text) [number] = text,
#define COMM_UNIT(id, number, name, step, unit, scale, xscale, extra) [number] = unit,
#define COMM_SCALE(id, number, name, step, unit, scale, xscale, extra) [number] = scale,
#define COMM_XSCALE(id, number, name, step, unit, scale, xscale, extra) [number] = xscale,
#define COMM_STEP(id, number, name, step, ...) [number] = SXL_COMM_STEP_##step,
static const char *const comm_step_names[SXL_COMM_STEP_COUNT] = {SXL_COMM_STEP_LIST(COMM_NAME)};
static const char *const comm_quantity_names[SXL_COMM_QUANTITY_COUNT] = {
    SXL_COMM_QUANTITY_LIST(COMM_NAME)};
static const char *const comm_quantity_units[SXL_COMM_QUANTITY_COUNT] = {
    SXL_COMM_QUANTITY_LIST(COMM_UNIT)};
static const double comm_quantity_scales[SXL_COMM_QUANTITY_COUNT] = {
    SXL_COMM_QUANTITY_LIST(COMM_SCALE)};
static const double comm_quantity_xscales[SXL_COMM_QUANTITY_COUNT] = {
    SXL_COMM_QUANTITY_LIST(COMM_XSCALE)};
static const uint16_t comm_quantity_steps[SXL_COMM_QUANTITY_COUNT] = {
    SXL_COMM_QUANTITY_LIST(COMM_STEP)};
static const char *const comm_quality_names[SXL_COMM_QUALITY_COUNT] = {
    SXL_COMM_QUALITY_LIST(COMM_NAME)};
static const char *const comm_reason_texts[SXL_COMM_REASON_COUNT] = {
    SXL_COMM_REASON_LIST(COMM_TEXT)};
static const char *const comm_reason_names[SXL_COMM_REASON_COUNT] = {
    SXL_COMM_REASON_LIST(COMM_NAME)};
static const char *const comm_state_names[SXL_COMM_STATE_COUNT] = {SXL_COMM_STATE_LIST(COMM_NAME)};
#undef COMM_NAME
#undef COMM_TEXT
#undef COMM_UNIT
#undef COMM_SCALE
#undef COMM_XSCALE
#undef COMM_STEP

static const char *name_in(const char *const *names, uint16_t count, uint16_t k)
{
    return (k < count && names[k]) ? names[k] : "?";
}

const char *sxl_comm_step_name(uint16_t step)
{
    return name_in(comm_step_names, SXL_COMM_STEP_COUNT, step);
}

const char *sxl_comm_quantity_name(uint16_t quantity)
{
    return name_in(comm_quantity_names, SXL_COMM_QUANTITY_COUNT, quantity);
}

const char *sxl_comm_quantity_unit(uint16_t quantity)
{
    return name_in(comm_quantity_units, SXL_COMM_QUANTITY_COUNT, quantity);
}

double sxl_comm_quantity_scale(uint16_t quantity)
{
    return (quantity < SXL_COMM_QUANTITY_COUNT) ? comm_quantity_scales[quantity] : 1.0;
}

double sxl_comm_quantity_extra_scale(uint16_t quantity)
{
    return (quantity < SXL_COMM_QUANTITY_COUNT) ? comm_quantity_xscales[quantity] : 1.0;
}

uint16_t sxl_comm_step_quantities(uint16_t step)
{
    uint16_t q, mask = 0u;
    for (q = 0u; q < SXL_COMM_QUANTITY_COUNT; q++) {
        mask = (uint16_t)(mask | ((comm_quantity_steps[q] == step) ? (1u << q) : 0u));
    }
    return mask;
}

const char *sxl_comm_quality_name(uint16_t quality)
{
    return name_in(comm_quality_names, SXL_COMM_QUALITY_COUNT, quality);
}

const char *sxl_comm_reason_text(uint16_t reason)
{
    return name_in(comm_reason_texts, SXL_COMM_REASON_COUNT, reason);
}

const char *sxl_comm_reason_name(uint16_t reason)
{
    return name_in(comm_reason_names, SXL_COMM_REASON_COUNT, reason);
}

const char *sxl_comm_state_name(uint16_t state)
{
    return name_in(comm_state_names, SXL_COMM_STATE_COUNT, state);
}

const char *sxl_run_refusal_name(uint16_t reason)
{
    return (reason < SXL_RUN_REFUSAL_NAME_COUNT) ? run_refusal_names[reason] : "?";
}

const char *sxl_state_name(uint16_t state)
{
    return (state < SXL_STATE_NAME_COUNT) ? state_names[state] : "?";
}

#define SXL_RESULT_TEXT(id, number, text) [number] = text,
static const char *const result_names[SXL_RESULT_COUNT] = {SXL_RESULT_LIST(SXL_RESULT_TEXT)};
#undef SXL_RESULT_TEXT

const char *sxl_result_name(uint16_t result)
{
    return (result < SXL_RESULT_COUNT && result_names[result]) ? result_names[result]
                                                               : "unknown result";
}

const char *sxl_fault_name(uint16_t code)
{
    return (code < SXL_FAULT_CODE_COUNT && fault_names[code]) ? fault_names[code] : "?";
}

const char *sxl_fault_description(uint16_t code)
{
    return (code < SXL_FAULT_CODE_COUNT && fault_texts[code]) ? fault_texts[code] : "?";
}

const char *sxl_fault_bit_name(uint16_t bit)
{
    return (bit < SXL_FAULT_BIT_COUNT && fault_bit_names[bit]) ? fault_bit_names[bit] : "?";
}

/* Append s at *n, keeping room for the terminator. */
static void append(char *out, uint16_t cap, uint16_t *n, const char *s)
{
    while (*s != '\0' && (uint16_t)(*n + 1u) < cap) {
        out[*n] = *s;
        (*n)++;
        s++;
    }
    out[*n] = '\0';
}

uint16_t sxl_fault_mask_str(uint16_t mask, char *out, uint16_t cap)
{
    uint16_t n = 0u;
    uint16_t bit;
    if (out == 0 || cap == 0u) {
        return 0u;
    }
    out[0] = '\0';
    if (mask == 0u) {
        append(out, cap, &n, "NONE");
        return n;
    }
    for (bit = 0u; bit < SXL_FAULT_BIT_COUNT; bit++) {
        if ((mask & (uint16_t)(1u << bit)) != 0u) {
            if (n > 0u) {
                append(out, cap, &n, "|");
            }
            append(out, cap, &n, fault_bit_names[bit]);
        }
    }
    return n;
}
