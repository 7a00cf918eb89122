/*
 * `sixphase-link identify` end to end: the virtual board (`sixphase-sim serve --scenario
 * commission --fast`) with a machine unlike the reference one (R +30 %, L_q +13 %, psi_f -11 %,
 * the encoder's index 77 degrees from the d axis), the host tool running the drive's
 * commissioning over the serial link, applying it and writing the motor parameter file; the
 * file read back by `sixphase-sim run --ctl-params` on the same machine: the drive then holds
 * its speed, which it cannot with the reference parameters and offset 0. The tool's refusals:
 * the DC link below the under-voltage limit (exit 1, the reason in one line), bad arguments
 * (exit 2).
 */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "motor_params_file.h"

#define PLANT                                                                                      \
    "--motor-r", "2.6", "--motor-lq", "0.062", "--motor-psi-f", "0.2", "--encoder-offset-deg", "77"

/* Run argv (NULL-terminated) to completion; its exit status, stdout and stderr captured. */
static int run_cmd(char *const argv[], char *out, size_t out_len, char *err, size_t err_len)
{
    int po[2], pe[2], status = 0;
    size_t no = 0, ne = 0;
    pid_t pid;
    assert_int_equal(pipe(po), 0);
    assert_int_equal(pipe(pe), 0);
    pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        (void)dup2(po[1], 1);
        (void)dup2(pe[1], 2);
        execv(argv[0], argv);
        _exit(127);
    }
    (void)close(po[1]);
    (void)close(pe[1]);
    for (;;) {
        ssize_t r = (no + 1 < out_len) ? read(po[0], out + no, out_len - 1 - no) : 0;
        ssize_t s = (ne + 1 < err_len) ? read(pe[0], err + ne, err_len - 1 - ne) : 0;
        if (r <= 0 && s <= 0) {
            break;
        }
        no += (r > 0) ? (size_t)r : 0u;
        ne += (s > 0) ? (size_t)s : 0u;
    }
    out[no] = '\0';
    err[ne] = '\0';
    (void)close(po[0]);
    (void)close(pe[0]);
    (void)waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* A virtual board with the given options; its pseudo-terminal's path into pty. */
static pid_t serve(char *const extra[], char *pty, size_t len)
{
    char *argv[32];
    int out[2], n = 0, k;
    ssize_t got = 0;
    pid_t pid;
    argv[n++] = (char *)SIXPHASE_SIM_EXE;
    argv[n++] = (char *)"serve";
    argv[n++] = (char *)"--scenario";
    argv[n++] = (char *)"commission";
    argv[n++] = (char *)"--fast";
    argv[n++] = (char *)"--quiet";
    argv[n++] = (char *)"--duration";
    argv[n++] = (char *)"600";
    for (k = 0; extra[k]; k++) {
        argv[n++] = extra[k];
    }
    argv[n] = NULL;
    assert_int_equal(pipe(out), 0);
    pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        (void)dup2(out[1], 1);
        execv(argv[0], argv);
        _exit(127);
    }
    (void)close(out[1]);
    while (got < (ssize_t)len - 1 && read(out[0], &pty[got], 1) == 1 && pty[got] != '\n') {
        got++;
    }
    pty[got] = '\0';
    (void)close(out[0]);
    assert_true(got > 0);
    return pid;
}

static void stop(pid_t pid)
{
    (void)kill(pid, SIGTERM);
    (void)waitpid(pid, NULL, 0);
}

static double speed_of(const char *metrics)
{
    const char *s = strstr(metrics, "\"speed_mean_rpm\": ");
    return s ? atof(s + strlen("\"speed_mean_rpm\": ")) : -1e9;
}

/* The file identify wrote: every entry, the plant's machine and the inertia (0.01 kg m^2) with
 * the speed gains designed for it. */
static void check_identified_file(const char *path)
{
    motor_params_t m;
    char err[2048];
    assert_int_equal(motor_params_read(path, &m, err, sizeof err), 0);
    assert_true(m.have == (1u << MOTOR_PARAM_COUNT) - 1u);
    assert_true(m.value[MOTOR_PARAM_R] > 2.6 * 0.97 && m.value[MOTOR_PARAM_R] < 2.6 * 1.03);
    assert_true(m.value[MOTOR_PARAM_LQ] > 0.062 * 0.95 && m.value[MOTOR_PARAM_LQ] < 0.062 * 1.05);
    assert_true(m.value[MOTOR_PARAM_PSI_F] > 0.2 * 0.97 && m.value[MOTOR_PARAM_PSI_F] < 0.2 * 1.03);
    {
        const double deg = m.value[MOTOR_PARAM_ENCODER_OFFSET] * 360.0 / 4294967296.0;
        assert_true(deg > 75.0 && deg < 79.0);
    }
    assert_true(m.value[MOTOR_PARAM_INERTIA] > 0.01 * 0.95 &&
                m.value[MOTOR_PARAM_INERTIA] < 0.01 * 1.05);
    assert_true(m.value[MOTOR_PARAM_SPEED_KP] > 1.5 * 0.95 &&
                m.value[MOTOR_PARAM_SPEED_KP] < 1.5 * 1.05);
}

/* The file on the same machine: the drive holds 1500 r/min at rated load, the reference
 * machine's parameters do not. */
/* One identify on the board: argv after "identify"; the exit status, stdout and stderr. */
static int identify(char *pty, char *const *args, char *out, size_t out_n, char *err, size_t err_n)
{
    char *argv[16] = {(char *)SIXPHASE_LINK_EXE, (char *)"-d", pty, (char *)"-t", (char *)"2000",
                      (char *)"identify"};
    int rc, k = 6;
    while (*args != NULL && k < 15) {
        argv[k++] = *args++;
    }
    argv[k] = NULL;
    rc = run_cmd(argv, out, out_n, err, err_n);
    print_message("%s%s", out, err);
    return rc;
}

static void check_file_holds_the_speed(char *path)
{
    char *const with[] = {(char *)SIXPHASE_SIM_EXE,
                          (char *)"run",
                          (char *)"--controller",
                          (char *)"ddc",
                          (char *)"--scenario",
                          (char *)"steady",
                          (char *)"--duration",
                          (char *)"0.4",
                          PLANT,
                          (char *)"--ctl-params",
                          path,
                          NULL};
    char *const without[] = {(char *)SIXPHASE_SIM_EXE,
                             (char *)"run",
                             (char *)"--controller",
                             (char *)"ddc",
                             (char *)"--scenario",
                             (char *)"steady",
                             (char *)"--duration",
                             (char *)"0.4",
                             PLANT,
                             NULL};
    char out[8192], err[2048];
    double good, bad;
    assert_int_equal(run_cmd(with, out, sizeof out, err, sizeof err), 0);
    good = speed_of(out);
    (void)run_cmd(without, out, sizeof out, err, sizeof err);
    bad = speed_of(out);
    print_message("speed with the file %.1f r/min, with the reference machine %.1f r/min\n", good,
                  bad);
    assert_true(good > 1485.0 && good < 1515.0);
    assert_true(bad < 1485.0 || bad > 1515.0);
}

static void test_identify_apply_and_file(void **state)
{
    char *plant[] = {PLANT, NULL};
    char pty[160], out[8192], err[2048], path[] = "/tmp/sixphase-identify-XXXXXX";
    pid_t board;
    int fd;
    (void)state;
    fd = mkstemp(path);
    assert_true(fd >= 0);
    (void)close(fd);
    board = serve(plant, pty, sizeof pty);
    sleep(1); /* the board calibrates its offsets first (0.1 s simulated) */
    {
        char *args[] = {(char *)"--apply", (char *)"--out", path, NULL};
        assert_int_equal(identify(pty, args, out, sizeof out, err, sizeof err), 0);
    }
    stop(board);
    assert_non_null(strstr(out, "commissioning done"));
    assert_non_null(strstr(out, "applied: quantities 0x01FC")); /* the machine and the inertia */
    check_identified_file(path);
    check_file_holds_the_speed(path);
    (void)remove(path);
}

static void test_identify_refused_with_the_dc_link_low(void **state)
{
    char *low[] = {(char *)"--vdc", (char *)"300", NULL};
    char pty[160], out[4096], err[1024];
    pid_t board;
    int rc;
    (void)state;
    board = serve(low, pty, sizeof pty);
    {
        char *args[] = {NULL};
        sleep(1);
        rc = identify(pty, args, out, sizeof out, err, sizeof err);
    }
    stop(board);
    print_message("exit %d: %s", rc, err);
    assert_int_equal(rc, 1);
    assert_non_null(strstr(err, "commissioning refused: DC link below the under-voltage limit"));
    assert_non_null(strchr(err, '\n'));
    assert_true(strchr(err, '\n')[1] == '\0'); /* one line */
}

/* A sequence that fails (A and B swapped) leaves an earlier parameter file as it was: before,
 * the tool wrote a file of nothing over it, which the firmware build took as the reference
 * machine. */
static void test_identify_failure_keeps_the_file(void **state)
{
    static const char earlier[] = "/* an earlier, good identification */\n"
                                  "#define SIXPHASE_MOTOR_R_OHM 2.5f\n";
    char *reversed[] = {(char *)"--encoder-reversed", NULL};
    char path[] = "/tmp/sixphase-identify-keep-XXXXXX";
    char pty[160], out[4096], err[1024], back[256];
    size_t n;
    FILE *f;
    pid_t board;
    int rc, fd;
    (void)state;
    fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, earlier, sizeof earlier - 1u), (ssize_t)(sizeof earlier - 1u));
    (void)close(fd);
    board = serve(reversed, pty, sizeof pty);
    {
        char *args[] = {(char *)"--out", path, NULL};
        sleep(1);
        rc = identify(pty, args, out, sizeof out, err, sizeof err);
    }
    stop(board);
    print_message("exit %d: %s", rc, err);
    assert_int_equal(rc, 1);
    assert_non_null(strstr(err, "commissioning failed: "));
    assert_non_null(strstr(err, "not written"));
    assert_true(strchr(err, '\n')[1] == '\0'); /* one line */
    f = fopen(path, "r");
    assert_non_null(f);
    n = fread(back, 1, sizeof back - 1u, f);
    (void)fclose(f);
    back[n] = '\0';
    assert_string_equal(back, earlier);
    (void)remove(path);
}

/* Issue 25's reproducer: a weak magnet (psi_f 0.0675 Wb, 0.3 x the reference). Before,
 * psi_f ended poor (no_speed), L_d and L_q poor (rotor_moved), identify --apply --out exited 0,
 * the file left out psi_f and L_d and the drive kept 0.225 Wb: at rated load the speed
 * collapsed, no fault. Now every quantity is measured ok at the default test current (the flux
 * step waits for its speed; the inductances judge the rotor's motion by what it can bias):
 * applied and written. At a tenth of rated current (the steps up to psi_f) the flux step cannot
 * hold its speed steady and R's scatter passes its limit: identify refuses (exit 1, one line
 * naming them, no file), and asked for a partial apply the drive refuses the mix, a poor psi_f
 * (0.068 Wb) that contradicts the 0.225 Wb it would keep. */
#define STEPS_TO_PSI "phases,encoder,r,ldq,lxy,psi_f"

static void test_identify_weak_magnet(void **state)
{
    char *plant[] = {(char *)"--motor-psi-f", (char *)"0.0675", (char *)"--seed", (char *)"7",
                     NULL};
    char pty[160], out[8192], err[2048], path[] = "/tmp/sixphase-identify-weak-XXXXXX";
    pid_t board;
    int fd;
    (void)state;
    fd = mkstemp(path);
    assert_true(fd >= 0);
    (void)close(fd);
    (void)remove(path);
    board = serve(plant, pty, sizeof pty);
    sleep(1);
    {
        char *args[] = {(char *)"--steps",
                        (char *)STEPS_TO_PSI,
                        (char *)"--current",
                        (char *)"0.1",
                        (char *)"--apply",
                        (char *)"--out",
                        path,
                        NULL};
        assert_int_equal(identify(pty, args, out, sizeof out, err, sizeof err), 1);
        assert_non_null(strstr(err, "psi_f poor (no_speed)"));
        assert_non_null(strstr(err, "nothing applied or written"));
        assert_true(strchr(err, '\n')[1] == '\0'); /* one line */
        assert_int_not_equal(access(path, F_OK), 0);
    }
    {
        char *args[] = {(char *)"--steps",
                        (char *)STEPS_TO_PSI,
                        (char *)"--current",
                        (char *)"0.1",
                        (char *)"--partial",
                        (char *)"--apply",
                        NULL};
        assert_int_equal(identify(pty, args, out, sizeof out, err, sizeof err), 1);
        assert_non_null(strstr(err, "apply refused"));
    }
    {
        char *args[] = {(char *)"--apply", (char *)"--out", path, NULL};
        assert_int_equal(identify(pty, args, out, sizeof out, err, sizeof err), 0);
        assert_null(strstr(out, " poor "));
        assert_non_null(strstr(out, "applied:"));
        assert_int_equal(access(path, F_OK), 0);
    }
    (void)remove(path);
    stop(board);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_identify_apply_and_file),
        cmocka_unit_test(test_identify_refused_with_the_dc_link_low),
        cmocka_unit_test(test_identify_failure_keeps_the_file),
        cmocka_unit_test(test_identify_weak_magnet),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
