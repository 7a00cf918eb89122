/*
 * Commissioning on the link (docs/commissioning.md, docs/serial-protocol.md): the application's
 * lists (firmware/app/lists/commission_lists.h: steps, quantities, qualities, reasons, states)
 * under the link's names, their numbers by name for host programs, and the commands' payloads. The
 * protocol's name tables and the host tool's printing come from these lists.
 */
#ifndef SXLINK_COMMISSION_H
#define SXLINK_COMMISSION_H

#include "lists/commission_lists.h"

/* The application's lists (commission_lists.h) under the link's names. */
#define SXL_COMM_CURRENT_DEFAULT_PERMILLE COMM_CURRENT_DEFAULT_PERMILLE
#define SXL_COMM_CURRENT_MAX_PERMILLE COMM_CURRENT_MAX_PERMILLE
#define SXL_COMM_CURRENT_MIN_PERMILLE COMM_CURRENT_MIN_PERMILLE
#define SXL_COMM_FLUX_GROUP COMM_FLUX_GROUP
#define SXL_COMM_KEPT_CONTRADICTS COMM_KEPT_CONTRADICTS
#define SXL_COMM_MODEL_QUANTITIES COMM_MODEL_QUANTITIES
#define SXL_COMM_QUALITY_COUNT COMM_QUALITY_COUNT
#define SXL_COMM_QUALITY_LIST COMM_QUALITY_LIST
#define SXL_COMM_QUANTITY_COUNT COMM_QUANTITY_COUNT
#define SXL_COMM_QUANTITY_LIST COMM_QUANTITY_LIST
#define SXL_COMM_REASON_COUNT COMM_REASON_COUNT
#define SXL_COMM_REASON_LIST COMM_REASON_LIST
#define SXL_COMM_STATE_COUNT COMM_STATE_COUNT
#define SXL_COMM_STATE_LIST COMM_STATE_LIST
#define SXL_COMM_STEPS_ALL COMM_STEPS_ALL
#define SXL_COMM_STEPS_VALID COMM_STEPS_VALID
#define SXL_COMM_STEP_COUNT COMM_STEP_COUNT
#define SXL_COMM_STEP_LIST COMM_STEP_LIST

/* The lists' numbers by name, for host programs (the firmware has its own enums, ident.h). */
#define SXL_COMM_NUMBER(id, number, ...) SXL_COMM_STEP_##id = number,
enum { SXL_COMM_STEP_ID_FIRST = -1, SXL_COMM_STEP_LIST(SXL_COMM_NUMBER) SXL_COMM_STEP_ID_END };
#undef SXL_COMM_NUMBER
#define SXL_COMM_NUMBER(id, number, ...) SXL_COMM_Q_##id = number,
enum { SXL_COMM_Q_FIRST = -1, SXL_COMM_QUANTITY_LIST(SXL_COMM_NUMBER) SXL_COMM_Q_END };
#undef SXL_COMM_NUMBER
#define SXL_COMM_NUMBER(id, number, ...) SXL_COMM_QUALITY_##id = number,
enum { SXL_COMM_QUALITY_FIRST = -1, SXL_COMM_QUALITY_LIST(SXL_COMM_NUMBER) SXL_COMM_QUALITY_END };
#undef SXL_COMM_NUMBER
#define SXL_COMM_NUMBER(id, number, ...) SXL_COMM_REASON_##id = number,
enum { SXL_COMM_REASON_FIRST = -1, SXL_COMM_REASON_LIST(SXL_COMM_NUMBER) SXL_COMM_REASON_END };
#undef SXL_COMM_NUMBER
#define SXL_COMM_NUMBER(id, number, ...) SXL_COMM_STATE_##id = number,
enum { SXL_COMM_STATE_FIRST = -1, SXL_COMM_STATE_LIST(SXL_COMM_NUMBER) SXL_COMM_STATE_END };
#undef SXL_COMM_NUMBER

/* COMMISSION_START payload. */
#define SXL_CC_MASK 0u    /* uint8 steps */
#define SXL_CC_CURRENT 1u /* uint16 test current, per mille of rated */
#define SXL_CC_SIZE 3u
/* COMMISSION_STATUS reply (after the result byte). */
#define SXL_CT_STATE 0u    /* uint8 SXL_COMM_STATE */
#define SXL_CT_STEP 1u     /* uint8 step running (or the last one run) */
#define SXL_CT_PROGRESS 2u /* uint8 % of the whole sequence */
#define SXL_CT_REASON 3u   /* uint8 SXL_COMM_REASON: the last refusal or the end's reason */
#define SXL_CT_MASK 4u     /* uint8 steps of the sequence */
#define SXL_CT_CURRENT 5u  /* uint16 test current, per mille of rated */
#define SXL_CT_PERIODS 7u  /* uint32 control periods since the start */
#define SXL_CT_SIZE 11u
/* COMMISSION_RESULT request: uint8 quantity; reply (after the result byte): */
#define SXL_CR2_QUANTITY 0u /* uint8 */
#define SXL_CR2_QUALITY 1u  /* uint8 SXL_COMM_QUALITY */
#define SXL_CR2_REASON 2u   /* uint8 SXL_COMM_REASON */
#define SXL_CR2_VALUE 3u    /* int32 value x scale */
#define SXL_CR2_SIGMA 7u    /* int32 1-sigma uncertainty x scale */
#define SXL_CR2_EXTRA 11u   /* int32 the quantity's extra */
#define SXL_CR2_SIZE 15u
/* COMMISSION_APPLY reply (after the result byte): uint16 quantities applied, bit per id. */
#define SXL_CA2_APPLIED 0u
#define SXL_CA2_SIZE 2u

#endif /* SXLINK_COMMISSION_H */
