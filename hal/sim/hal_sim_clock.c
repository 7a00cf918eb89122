/* Simulator HAL: hal_cycles.h on simulated time or the host's clock (hal_sim.h). */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */

#include <stdbool.h>
#include <time.h>

#include "hal_cycles.h"
#include "hal_sim.h"

/* ---- hal_cycles.h: nanoseconds of simulated time, or of the host's monotonic clock ---- */

static bool hal_sim_host_clock;

void hal_sim_use_host_clock(bool host) { hal_sim_host_clock = host; }

void hal_sim_clock_advance(uint32_t ns) { hal_sim_bus.clock_ns += ns; }

void hal_cycles_init(void) {}

uint32_t hal_cycles_now(void)
{
    struct timespec ts;
    if (!hal_sim_host_clock) {
        return hal_sim_bus.clock_ns;
    }
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint32_t)((uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec);
}

uint32_t hal_cycles_per_second(void) { return 1000000000u; }
