/* Names of the drive states, drive fault codes and protection fault bits carried by the
 * protocol. Tables in the order of the firmware's enums (drive.h, ctl_protect.h);
 * drive_link.c checks the counts at compile time. */
#include "sxlink.h"

static const char *const state_names[SXL_STATE_NAME_COUNT] = {"INIT", "CALIBRATE", "READY", "RUN",
                                                              "FAULT"};

static const char *const fault_names[SXL_FAULT_NAME_COUNT] = {
    "NONE",     "PARAMS",    "ADC_OFFSET",  "ADC_MISSING",    "HW_TRIP",         "OVERRUN",
    "ENCODER",  "STARTUP",   "OVERCURRENT", "DC_OVERVOLTAGE", "DC_UNDERVOLTAGE", "OVERSPEED",
    "ADC_RAIL", "ADC_STUCK", "CURRENT_SUM", "OPEN_PHASE",     "MEASUREMENT"};

static const char *const fault_bit_names[SXL_FAULT_BIT_COUNT] = {
    "OVERCURRENT", "DC_OVERVOLTAGE", "DC_UNDERVOLTAGE", "OVERSPEED",   "ENCODER",    "ADC_RAIL",
    "ADC_STUCK",   "ADC_OFFSET",     "OVERRUN",         "CURRENT_SUM", "OPEN_PHASE", "HW_TRIP",
    "PARAMS",      "MEASUREMENT",    "ADC_MISSING",     "PLATFORM"};

static const char *const run_refusal_names[SXL_RUN_REFUSAL_NAME_COUNT] = {
    "NONE", "NOT_READY", "ENCODER", "UNDERVOLTAGE"};

const char *sxl_run_refusal_name(uint16_t reason)
{
    return (reason < SXL_RUN_REFUSAL_NAME_COUNT) ? run_refusal_names[reason] : "?";
}

const char *sxl_state_name(uint16_t state)
{
    return (state < SXL_STATE_NAME_COUNT) ? state_names[state] : "?";
}

const char *sxl_fault_name(uint16_t code)
{
    return (code < SXL_FAULT_NAME_COUNT) ? fault_names[code] : "?";
}

const char *sxl_fault_bit_name(uint16_t bit)
{
    return (bit < SXL_FAULT_BIT_COUNT) ? fault_bit_names[bit] : "?";
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
