/*
 * The frames of a PIL session (firmware/link/sxlink_pil.h) over a pil_port_t: each request
 * waits for its reply; a reply that does not come, or says other than ok, ends the session
 * with a one-line reason in err.
 */
#ifndef PIL_SESSION_H
#define PIL_SESSION_H

#include <stdint.h>

#include "bridge/sim_ctl.h"
#include "bridge/sim_ctl_wire.h"
#include "hal_sim.h"
#include "pil_port.h"
#include "sxlink.h"

#define PIL_SESSION_TIMEOUT_MS 30000 /* a parameter build on a slow target included */
#define PIL_SESSION_HELLO_MS 5000    /* the first frame: no target there answers within it */

typedef struct {
    pil_port_t port;
    sxl_decoder_t decoder;
    unsigned version, arith, target; /* HELLO's */
    uint32_t counter_hz;
    char err[512];
} pil_session_t;

/* Opens the target and asks it HELLO; its arithmetic must be arith ("fixed" or "float"). */
int pil_session_open(pil_session_t *s, const char *target, const char *arith);

/* The configuration's image (CONFIG frames) and INIT with the peripherals of bus; *rc the
 * target's init result. */
int pil_session_init(pil_session_t *s, const sim_ctl_config_t *cfg, const hal_sim_bus_t *bus,
                     int *rc);

/* Call records (n bytes) in CALLS frames, split at records. */
int pil_session_calls(pil_session_t *s, const uint16_t *calls, uint16_t n);

/* One period: the inputs of bus, the call records that fit (n bytes, at most
 * SXL_MAX_PAYLOAD - SXL_PIL_IN_BYTES), the outputs into out. */
int pil_session_step(pil_session_t *s, const hal_sim_bus_t *bus, uint16_t seq,
                     const uint16_t *calls, uint16_t n, sim_ctl_wire_out_t *out);

void pil_session_close(pil_session_t *s);

#endif /* PIL_SESSION_H */
