/*
 * The drive's states and run refusals on the link: the application's lists
 * (firmware/app/lists/drive_states.h), numbered as the wire carries them and named as the tools
 * print them (sxlink_names.c).
 */
#ifndef SXLINK_STATES_H
#define SXLINK_STATES_H

#include <stdint.h>

#include "lists/drive_states.h"

#define SXL_STATE_LIST(X) DRIVE_STATE_LIST(X)
#define SXL_RUN_REFUSAL_LIST(X) DRIVE_RUN_REFUSAL_LIST(X)
#define SXL_STATE_NAME_COUNT ((uint16_t)DRIVE_STATE_COUNT)
#define SXL_RUN_REFUSAL_NAME_COUNT ((uint16_t)DRIVE_RUN_REFUSAL_COUNT)

#endif /* SXLINK_STATES_H */
