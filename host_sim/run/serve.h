/*
 * `sixphase-sim serve`: the virtual board. The firmware application runs as on the board -
 * the drive's control ISR every period against the plant, and the background loop's serial
 * link (firmware/app/service/link_service.c) - with the SCI modelled at its baud rate (10 bits per
 * byte, 16-byte FIFOs) and its line connected to a pseudo-terminal, whose path is printed on
 * stdout. sixphase-link talks to it as to a board (`sixphase-link --port PATH ...`).
 *
 * Nothing is commanded by the simulator: the drive powers up, calibrates its current offsets
 * (about 0.1 s) and waits in READY for the host; --speed sets the speed reference a RUN will
 * follow. The rotor starts at standstill; --load puts a passive load on it (the torque opposes
 * motion, like a brake: a rotor at rest stays at rest); a fault-<name> scenario injects that
 * fault at --fault-time. It serves until --duration (default 10 h), SIGINT / SIGTERM, or the
 * host's SXL_CMD_SIM_SHUTDOWN (`sixphase-link shutdown`), which it answers first.
 */
#ifndef SIM_SERVE_H
#define SIM_SERVE_H

#include <stdbool.h>

#include "sim.h"

typedef struct {
    double rate; /* simulated seconds per wall second (1: real time) */
    bool fast;   /* as fast as the host can */
    long baud;
    bool quiet; /* no summary on stderr at the end */
} sim_serve_options_t;

/* Serves until the configured duration (default 10 h), SIGINT / SIGTERM or the host's
 * shutdown request; returns the process exit status (0 after a clean stop, 1 when the set-up
 * failed, with a message). */
int sim_serve(const sim_config_t *c, const sim_serve_options_t *o);

#endif /* SIM_SERVE_H */
