/*
 * The processor-in-the-loop service of a target (firmware/link/sxlink_pil.h): reads frames from
 * the serial port, configures the drive from the host's image, runs one control period per STEP
 * frame on the inputs it carries and answers with what the period wrote and its cycle counts.
 * Polled from the target's main loop; no interrupt, no heap.
 */
#ifndef PIL_TARGET_H
#define PIL_TARGET_H

#include <stdbool.h>
#include <stdint.h>

#include "bridge/sim_ctl.h"
#include "bridge/sim_ctl_wire.h"
#include "sxlink.h"

/* The bridge and arithmetic of the image being built (a platform's main hands them over). */
#if CTL_MATH_FLOAT
#define PIL_TARGET_OPS sim_ctl_ops_float
#define PIL_TARGET_ARITH SXL_PIL_ARITH_FLOAT
#else
#define PIL_TARGET_OPS sim_ctl_ops_fixed
#define PIL_TARGET_ARITH SXL_PIL_ARITH_FIXED
#endif

typedef struct {
    const sim_ctl_ops_t *ops; /* the drive, through the simulator's bridge */
    uint16_t arith;           /* SXL_PIL_ARITH_* of this image */
    uint16_t target;          /* SXL_PIL_TARGET_* */
    sxl_decoder_t decoder;
    sxl_frame_t request;
    sxl_frame_t reply;
    uint16_t image[SIM_CTL_CONFIG_IMAGE_BYTES]; /* the configuration as CONFIG frames left it */
    uint16_t tx[SXL_MAX_FRAME];
    bool initialised; /* INIT succeeded: STEP frames are taken */
    uint32_t steps;
} pil_target_t;

void pil_target_init(pil_target_t *t, const sim_ctl_ops_t *ops, uint16_t arith, uint16_t target);

/* Every byte the serial port holds; each complete frame answered before the next byte is read
 * (the host waits for each reply, so a STEP runs with nothing else arriving). */
void pil_target_poll(pil_target_t *t);

/* One request answered into t->reply (exposed for the host's tests). */
void pil_target_handle(pil_target_t *t, const sxl_frame_t *req);

#endif /* PIL_TARGET_H */
