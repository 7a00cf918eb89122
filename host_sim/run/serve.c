/* The virtual board, see serve.h. */
#define _DEFAULT_SOURCE   /* cfmakeraw */
#define _XOPEN_SOURCE 600 /* posix_openpt, grantpt, unlockpt, ptsname */

#include "serve.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "hal_sim.h"
#include "sim_run_state.h"

#define SERVE_BITS_PER_BYTE 10.0 /* 8N1: start, 8 data, stop */
#define SERVE_PACE_PERIODS 10    /* pacing checked every 10 periods (1 ms at 10 kHz) */
#define SERVE_ARRIVAL_S 0.05     /* shutdown: the reply reaches the host's side within this */
#define SERVE_LINGER_S 1.0       /* longest wait for the host to read the shutdown reply */

static volatile sig_atomic_t serve_stop_requested;

static void serve_on_signal(int sig)
{
    (void)sig;
    serve_stop_requested = 1;
}

/* The line between the pseudo-terminal and the drive's serial port. */
typedef struct {
    int master, slave;
    char path[128];
    double bytes_per_period;
    double rx_credit, tx_credit;
    unsigned long bytes_in, bytes_out, write_losses;
} serve_line_t;

/* The pseudo-terminal, its slave side held open in raw mode: the line keeps its settings and
 * does not echo between two clients, and reading the master never reports a hang-up. */
static int serve_line_open(serve_line_t *l, long baud, double ts)
{
    struct termios t;
    const char *name;
    memset(l, 0, sizeof *l);
    l->slave = -1;
    l->bytes_per_period = (double)baud / SERVE_BITS_PER_BYTE * ts;
    l->master = posix_openpt(O_RDWR | O_NOCTTY);
    if (l->master < 0 || grantpt(l->master) != 0 || unlockpt(l->master) != 0 ||
        (name = ptsname(l->master)) == NULL) {
        return -1;
    }
    (void)snprintf(l->path, sizeof l->path, "%s", name);
    l->slave = open(l->path, O_RDWR | O_NOCTTY);
    if (l->slave < 0 || tcgetattr(l->slave, &t) != 0) {
        return -1;
    }
    cfmakeraw(&t);
    if (tcsetattr(l->slave, TCSANOW, &t) != 0) {
        return -1;
    }
    return fcntl(l->master, F_SETFL, fcntl(l->master, F_GETFL) | O_NONBLOCK);
}

static void serve_line_close(serve_line_t *l)
{
    if (l->slave >= 0) {
        (void)close(l->slave);
    }
    if (l->master >= 0) {
        (void)close(l->master);
    }
}

/* One period of the line at its baud rate: bytes from the host into the receive FIFO, bytes
 * from the transmit FIFO to the host (a byte that finds the receive FIFO full is lost, as on
 * the SCI; hal_sim counts it). Credit does not pile up while the line is idle. */
static void serve_line_period(serve_line_t *l)
{
    unsigned char in[64];
    uint16_t byte;
    long n, i;
    l->rx_credit += l->bytes_per_period;
    n = (long)l->rx_credit;
    if (n > (long)sizeof in) {
        n = (long)sizeof in;
    }
    n = (n > 0) ? (long)read(l->master, in, (size_t)n) : 0;
    for (i = 0; i < n; i++) {
        (void)hal_sim_uart_arrive(in[i]);
    }
    if (n > 0) {
        l->bytes_in += (unsigned long)n;
        l->rx_credit -= (double)n;
    } else if (l->rx_credit > 1.0) {
        l->rx_credit = 1.0; /* an idle line does not store credit; below one byte it builds up */
    }
    l->tx_credit += l->bytes_per_period;
    while (l->tx_credit >= 1.0 && hal_sim_uart_depart(&byte)) {
        const unsigned char out = (unsigned char)byte;
        l->tx_credit -= 1.0;
        if (write(l->master, &out, 1) == 1) {
            l->bytes_out++;
        } else {
            l->write_losses++;
        }
    }
    if (hal_sim_bus.uart_tx_count == 0u && l->tx_credit > 1.0) {
        l->tx_credit = 1.0;
    }
}

/* Sleeps until simulated time t is due at the given rate. */
static void serve_pace(double wall0, double t, double rate)
{
    const double ahead = wall0 + t / rate - sim_wall_now();
    if (ahead > 0.0) {
        struct timespec d;
        d.tv_sec = (time_t)ahead;
        d.tv_nsec = (long)((ahead - (double)d.tv_sec) * 1e9);
        (void)nanosleep(&d, NULL);
    }
}

/* The run's configuration as the virtual board needs it: standstill, nothing commanded (a
 * --speed is the initial speed reference, set in sim_serve), the load passive (0 unless given),
 * served until the duration, a signal or the host's shutdown; with --out, the per-period
 * trace.csv of the whole session (no fine.csv). --scenario commission powers the board up as a
 * machine fresh from assembly: rotor anywhere, index not yet seen. */
static void serve_config(const sim_config_t *c, sim_config_t *s)
{
    *s = *c;
    /* commission: the rotor anywhere, the encoder's index not yet seen (a new machine) */
    s->scenario = (c->scenario == SIM_SCEN_COMMISSION) ? SIM_SCEN_COMMISSION : SIM_SCEN_STEADY;
    s->speed_rpm = 0.0;
    s->load_nm = (c->load_nm > -1e9) ? c->load_nm : 0.0;
    s->passive_load = true;
    s->duration_s = (c->duration_s > 0.0) ? c->duration_s : SIM_MAX_DURATION_S;
    s->write_fine = false;
}

/* After the host's shutdown request: until the host has read the reply off the line, so that
 * closing the pseudo-terminal (a hang-up, which discards unread input) does not take it away.
 * The reply shows in the line's input queue within SERVE_ARRIVAL_S (else it was read at
 * once); at most SERVE_LINGER_S in all. */
static void serve_linger(const serve_line_t *l)
{
    const double t0 = sim_wall_now();
    bool seen = false;
    for (;;) {
        const double t = sim_wall_now() - t0;
        const struct timespec d = {0, 1000000L};
        int pending = 0;
        if (ioctl(l->slave, FIONREAD, &pending) != 0) {
            return;
        }
        seen = seen || pending > 0;
        if ((seen && pending == 0) || (!seen && t > SERVE_ARRIVAL_S) || t > SERVE_LINGER_S) {
            return;
        }
        (void)nanosleep(&d, NULL);
    }
}

/* The periods until the duration, a signal, the host's shutdown (the stop's reason in *why) or
 * the output files' size limit; 0, or 1 when the plant diverged or the limit was reached (its
 * one-line message printed). */
static int serve_loop(sim_run_t *rs, serve_line_t *line, const sim_serve_options_t *o,
                      long *periods, const char **why)
{
    sim_result_t r;
    char err[300];
    const double wall0 = sim_wall_now();
    long k;
    memset(&r, 0, sizeof r);
    r.fault_time_s = -1.0;
    r.trip_time_s = -1.0;
    *why = "the duration";
    for (k = 0; k < rs->n_periods; k++) {
        if (serve_stop_requested) {
            *why = "a signal";
            break;
        }
        if (rs->ops->link_shutdown() && hal_sim_bus.uart_tx_count == 0u) {
            *why = "the host (shutdown)"; /* the reply has left the serial port */
            serve_linger(line);
            break;
        }
        if (sim_loop_period(rs, &r, k) != 0) {
            fprintf(stderr, "sixphase-sim: plant state diverged at %.4f s\n", (double)k * rs->ts);
            return 1;
        }
        if (sim_loop_out_limit(rs, k, err, sizeof err) != 0) {
            fprintf(stderr, "sixphase-sim: %s\n", err);
            *periods = k + 1;
            return 1;
        }
        serve_line_period(line);
        rs->ops->link_step();
        if (!o->fast && k % SERVE_PACE_PERIODS == 0) {
            serve_pace(wall0, (double)k * rs->ts, o->rate);
        }
    }
    *periods = k;
    return 0;
}

int sim_serve(const sim_config_t *c, const sim_serve_options_t *o)
{
    sim_config_t cfg;
    sim_run_t rs;
    serve_line_t line;
    char err[256] = "";
    long periods = 0;
    const char *why = "";
    int rc;
    serve_config(c, &cfg);
    if (cfg.out_dir && sim_check_out_dir(cfg.out_dir, err, sizeof err) != 0) {
        fprintf(stderr, "sixphase-sim: %s\n", err);
        return 1;
    }
    hal_sim_use_host_clock(true); /* the board's profile shows host time */
    if (sim_setup(&rs, &cfg, err, sizeof err) != 0) {
        fprintf(stderr, "sixphase-sim: %s\n", err);
        sim_teardown(&rs, false);
        return 1;
    }
    if (serve_line_open(&line, o->baud, rs.ts) != 0) {
        fprintf(stderr, "sixphase-sim: cannot open a pseudo-terminal: %s\n", strerror(errno));
        serve_line_close(&line);
        sim_teardown(&rs, false);
        return 1;
    }
    /* hal_cycles is host time: at a slow pacing a frame takes 1 / rate longer to arrive */
    rs.ops->link_init((!o->fast && o->rate < 1.0) ? 0.02 / o->rate : 0.02);
    if (c->speed_rpm > -1e9) {
        rs.ops->set_speed_rpm(c->speed_rpm); /* the reference a RUN will follow */
    }
    serve_stop_requested = 0;
    (void)signal(SIGINT, serve_on_signal);
    (void)signal(SIGTERM, serve_on_signal);
    printf("%s\n", line.path);
    (void)fflush(stdout);
    rc = serve_loop(&rs, &line, o, &periods, &why);
    if (!o->quiet && rc == 0) {
        fprintf(stderr,
                "sixphase-sim serve: stopped by %s after %.3f s simulated, %lu requests, %lu "
                "bytes in, %lu out, %lu lost in the receive FIFO\n",
                why, (double)periods * rs.ts, rs.ops->link_frames(), line.bytes_in, line.bytes_out,
                (unsigned long)hal_sim_bus.uart_rx_overruns);
    }
    serve_line_close(&line);
    if (sim_recorder_close(&rs.rec, err, sizeof err) != 0) { /* the trace's last rows too */
        fprintf(stderr, "sixphase-sim: %s\n", err);
        rc = 1;
    }
    sim_teardown(&rs, true);
    return rc;
}
