/*
 * sixphase-sim sweep and plot, through the executable:
 * - a 2 x 2 grid without --scenario (steady by default): every column of every row, in
 *   sweep.csv and in sweep.json, equals the metrics.json of a single `run` of that point (the
 *   host timings aside); the summary names the workers (default: the online processors);
 * - resume: only a removed point runs again; a rebuilt binary runs every point again;
 * - resume after damage: point files cut at each kind of place (empty, in the header, right
 *   after the "ok" line, in the middle of the JSON) run again, exactly those, and the table
 *   lists each point's own metrics; a points folder that cannot be written is reported as
 *   such before anything runs;
 * - bad grids are refused with exit 2 and one line; --force lifts the point cap;
 * - a point whose run fails fails the sweep and runs again on a rerun;
 * - points the drive stopped in a fault (MPTC-49 trips its over-current protection) are
 *   marked with the fault, counted in the summary and left out of the plots and the Pareto
 *   front; the plots are drawn (PNG sizes);
 * - `run --plot` and `plot DIR` draw a 1000 x 1400 PNG; their refusals are one line.
 */
#define _POSIX_C_SOURCE 200809L

#include <ctype.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <dirent.h>

#include <cmocka.h>

#define EXE SIXPHASE_SIM_EXE
#define GRID "--controller ddc,mptc13 --lambda 20,100 --duration 0.3 --no-plots"
#define MAX_COLUMNS 400
#define VALUE_LEN 320

static char dir[] = "/tmp/sixphase-sweep-XXXXXX";

/* A shell command from a format; its exit status. */
static int shf(const char *fmt, ...)
{
    char cmd[2000];
    va_list ap;
    int rc;
    va_start(ap, fmt);
    (void)vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    rc = system(cmd);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

static char *read_file(const char *path, char *buf, size_t size)
{
    FILE *f = fopen(path, "r");
    size_t n;
    if (!f) {
        print_error("cannot read %s\n", path);
        fail();
    }
    n = fread(buf, 1, size - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static char *read_in_dir(const char *d, const char *name)
{
    static char buf[1 << 20];
    char path[300];
    (void)snprintf(path, sizeof path, "%s/%s", d, name);
    return read_file(path, buf, sizeof buf);
}

/* The message of a refusal: exactly one line, "sixphase-sim: ...". */
static void assert_one_line(const char *text)
{
    const char *nl = strchr(text, '\n');
    if (strncmp(text, "sixphase-sim: ", 14) != 0 || !nl || nl[1] != '\0') {
        print_error("not one 'sixphase-sim:' line: '%s'\n", text);
        fail();
    }
}

/* The point file in DIR/points whose second line (the point's arguments) ends with args. */
static void point_file(const char *d, const char *args, char *path, size_t len)
{
    char folder[300], text[8192];
    struct dirent *e;
    DIR *dh;
    int found = 0;
    (void)snprintf(folder, sizeof folder, "%s/points", d);
    dh = opendir(folder);
    assert_non_null(dh);
    while ((e = readdir(dh)) != NULL) {
        char candidate[600];
        const char *line2, *end;
        FILE *f;
        size_t n;
        if (e->d_name[0] == '.') {
            continue;
        }
        (void)snprintf(candidate, sizeof candidate, "%s/%s", folder, e->d_name);
        f = fopen(candidate, "r");
        if (!f) {
            continue;
        }
        n = fread(text, 1, sizeof text - 1, f);
        text[n] = '\0';
        fclose(f);
        line2 = strchr(text, '\n');
        end = line2 ? strchr(line2 + 1, '\n') : NULL;
        if (end && (size_t)(end - line2 - 1) >= strlen(args) &&
            strncmp(end - strlen(args), args, strlen(args)) == 0) {
            (void)snprintf(path, len, "%s", candidate);
            found++;
        }
    }
    closedir(dh);
    if (found != 1) {
        print_error("%d point files end their arguments with '%s'\n", found, args);
        fail();
    }
}

/* ---- flat key-value views of metrics.json, a sweep.json row and a sweep.csv row ---- */

typedef struct {
    int n;
    char key[MAX_COLUMNS][96];
    char value[MAX_COLUMNS][VALUE_LEN]; /* as the CSV writes it: null "", true "1", false "0" */
} flat_t;

static const char *skip_space(const char *s)
{
    while (isspace((unsigned char)*s)) {
        s++;
    }
    return s;
}

static const char *json_string(const char *s, char *out, size_t len)
{
    size_t n = 0;
    for (s++; *s != '"'; s++) {
        assert_true(*s != '\0');
        if (*s == '\\') {
            s++;
        }
        if (n + 1 < len) {
            out[n++] = *s;
        }
    }
    out[n] = '\0';
    return s + 1;
}

static const char *json_value(const char *s, const char *key, flat_t *o);

/* An object's members (KEY_MEMBER) or an array's elements (KEY_A, KEY_B, ...). */
static const char *json_members(const char *s, const char *prefix, flat_t *o)
{
    const char close = (*s == '{') ? '}' : ']';
    int k = 0;
    s = skip_space(s + 1);
    while (*s != close) {
        char name[96], key[200];
        if (close == '}') {
            s = json_string(skip_space(s), name, sizeof name);
            s = skip_space(s);
            assert_int_equal(*s, ':');
            (void)snprintf(key, sizeof key, "%s%s%s", prefix, *prefix ? "_" : "", name);
            s++;
        } else {
            (void)snprintf(key, sizeof key, "%s_%c", prefix, 'A' + k);
        }
        s = skip_space(json_value(s, key, o));
        k++;
        if (*s == ',') {
            s = skip_space(s + 1);
        }
    }
    return s + 1;
}

static const char *json_value(const char *s, const char *key, flat_t *o)
{
    char *v;
    size_t n;
    s = skip_space(s);
    if (*s == '{' || *s == '[') {
        return json_members(s, key, o);
    }
    assert_true(o->n < MAX_COLUMNS);
    (void)snprintf(o->key[o->n], sizeof o->key[0], "%s", key);
    v = o->value[o->n++];
    if (*s == '"') {
        return json_string(s, v, VALUE_LEN);
    }
    n = strcspn(s, ",}] \n");
    (void)snprintf(v, VALUE_LEN, "%.*s", (int)n, s);
    if (strcmp(v, "null") == 0) {
        v[0] = '\0';
    } else if (strcmp(v, "true") == 0 || strcmp(v, "false") == 0) {
        (void)snprintf(v, VALUE_LEN, "%d", v[0] == 't');
    }
    return s + n;
}

/* One CSV line into fields (quoted fields with doubled quotes). */
static void csv_fields(const char *line, flat_t *o, int keys)
{
    int k = 0;
    for (;; k++) {
        char *v = keys ? o->key[k] : o->value[k];
        const size_t len = keys ? sizeof o->key[0] : VALUE_LEN;
        size_t n = 0;
        assert_true(k < MAX_COLUMNS);
        if (*line == '"') {
            for (line++; !(line[0] == '"' && line[1] != '"'); line++) {
                line += (line[0] == '"'); /* a doubled quote */
                v[n < len - 1 ? n++ : n] = *line;
            }
            line++;
        }
        while (*line != ',' && *line != '\n' && *line != '\0') {
            v[n < len - 1 ? n++ : n] = *line++;
        }
        v[n] = '\0';
        if (*line != ',') {
            break;
        }
        line++;
    }
    o->n = k + 1;
}

/* Row r (0-based) of DIR/sweep.csv as key-value pairs. */
static void csv_row(const char *d, int r, flat_t *row)
{
    const char *line = read_in_dir(d, "sweep.csv");
    int k;
    csv_fields(line, row, 1);
    for (k = 0; k <= r; k++) {
        line = strchr(line, '\n');
        assert_non_null(line);
        line++;
    }
    assert_true(*line != '\0');
    k = row->n;
    csv_fields(line, row, 0);
    assert_int_equal(row->n, k); /* as many fields as the header */
}

static const char *flat_get(const flat_t *f, const char *key)
{
    int k;
    for (k = 0; k < f->n; k++) {
        if (strcmp(f->key[k], key) == 0) {
            return f->value[k];
        }
    }
    return NULL;
}

static void assert_field(const flat_t *f, const char *key, const char *want)
{
    const char *v = flat_get(f, key);
    if (!v || strcmp(v, want) != 0) {
        print_error("%s: '%s', want '%s'\n", key, v ? v : "(no such column)", want);
        fail();
    }
}

/* Every key of a single run's metrics.json but the host timings is in the row, equal. */
static int assert_row_has_run(const flat_t *row, const flat_t *run)
{
    static const char *const host_timings[] = {"realtime_factor", "wall_s", "isr_mean_us"};
    int k, compared = 0;
    for (k = 0; k < run->n; k++) {
        if (strcmp(run->key[k], host_timings[0]) == 0 ||
            strcmp(run->key[k], host_timings[1]) == 0 ||
            strcmp(run->key[k], host_timings[2]) == 0) {
            continue;
        }
        assert_field(row, run->key[k], run->value[k]);
        compared++;
    }
    return compared;
}

static void flat_json_file(const char *d, const char *name, flat_t *o)
{
    o->n = 0;
    (void)json_value(read_in_dir(d, name), "", o);
}

/* Object r (0-based) of DIR/sweep.json. */
static void json_row(const char *d, int r, flat_t *o)
{
    const char *s = skip_space(read_in_dir(d, "sweep.json"));
    int k;
    assert_int_equal(*s, '[');
    s = skip_space(s + 1);
    for (k = 0; k < r; k++) {
        flat_t skip;
        skip.n = 0;
        s = skip_space(json_members(s, "", &skip));
        assert_int_equal(*s, ',');
        s = skip_space(s + 1);
    }
    o->n = 0;
    (void)json_members(s, "", o);
}

static long online_processors(void)
{
    const long n = sysconf(_SC_NPROCESSORS_ONLN);
    return (n < 1) ? 1 : ((n > 64) ? 64 : n);
}

/* ---- the tests ---- */

static void test_table_equals_single_runs(void **state)
{
    static const char *const controllers[2] = {"ddc", "mptc13"};
    static const char *const lambdas[2] = {"20", "100"};
    static flat_t row, jrow, run;
    char want[200];
    int k;
    (void)state;
    assert_non_null(mkdtemp(dir));
    assert_int_equal(shf("%s sweep --out %s " GRID " 2> %s/summary.txt", EXE, dir, dir), 0);
    (void)snprintf(want, sizeof want,
                   "(0 from an earlier run, %ld worker processes): 4 ok, 0 stopped by a drive "
                   "fault, 0 failed",
                   online_processors());
    assert_non_null(strstr(read_in_dir(dir, "summary.txt"), want));
    for (k = 0; k < 4; k++) {
        int n;
        csv_row(dir, k, &row);
        json_row(dir, k, &jrow);
        assert_field(&row, "--controller", controllers[k / 2]);
        assert_field(&row, "--lambda", lambdas[k % 2]);
        assert_field(&row, "--duration", "0.3");
        assert_field(&row, "--scenario", "steady");
        assert_field(&row, "outcome", "ok");
        assert_field(&jrow, "outcome", "ok");
        assert_int_equal(shf("%s run --controller %s --scenario steady --lambda %s --duration 0.3 "
                             "> %s/single.json",
                             EXE, controllers[k / 2], lambdas[k % 2], dir),
                         0);
        flat_json_file(dir, "single.json", &run);
        n = assert_row_has_run(&row, &run);
        assert_int_equal(assert_row_has_run(&jrow, &run), n);
        print_message("row %d: %d values equal a single run's\n", k, n);
        assert_true(n >= 80); /* 85 keys today */
    }
}

static void test_resume_runs_only_the_missing_point(void **state)
{
    static char before[1 << 20];
    char path[200];
    struct stat kept, again;
    (void)state;
    (void)snprintf(before, sizeof before, "%s", read_in_dir(dir, "sweep.csv"));
    point_file(dir, "--controller ddc --lambda 20", path, sizeof path);
    assert_int_equal(stat(path, &kept), 0);
    point_file(dir, "--controller mptc13 --lambda 20", path, sizeof path);
    assert_int_equal(remove(path), 0);
    sleep(1); /* a rewritten point file would show a later time */
    assert_int_equal(shf("%s sweep --out %s " GRID " 2> %s/summary.txt", EXE, dir, dir), 0);
    assert_non_null(strstr(read_in_dir(dir, "summary.txt"), "(3 from an earlier run"));
    assert_int_equal(access(path, R_OK), 0); /* run again */
    point_file(dir, "--controller ddc --lambda 20", path, sizeof path);
    assert_int_equal(stat(path, &again), 0);
    assert_true(again.st_mtime == kept.st_mtime); /* p0000 was not run again */
    assert_string_equal(read_in_dir(dir, "sweep.csv"), before);
}

/* The same sweep by a rebuilt executable (here: a copy whose file differs by a byte) runs
 * every point again; its rerun takes them all from the first. */
static void test_rebuilt_binary_reruns_every_point(void **state)
{
    char copy[200];
    (void)state;
    (void)snprintf(copy, sizeof copy, "%s/sixphase-sim-rebuilt", dir);
    assert_int_equal(shf("cp %s %s && printf x >> %s", EXE, copy, copy), 0);
    assert_int_equal(shf("%s sweep --out %s " GRID " 2> %s/summary.txt", copy, dir, dir), 0);
    assert_non_null(strstr(read_in_dir(dir, "summary.txt"), "(0 from an earlier run"));
    assert_int_equal(shf("%s sweep --out %s " GRID " 2> %s/summary.txt", copy, dir, dir), 0);
    assert_non_null(strstr(read_in_dir(dir, "summary.txt"), "(4 from an earlier run"));
    assert_int_equal(remove(copy), 0);
}

#define DAMAGE_GRID "--controller ddc --lambda 20,40,60,80,100 --duration 0.1 --no-plots --jobs 2"

/* Point file path cut to keep bytes: -1 keeps them all; else the file's first keep bytes. */
static long cut_point(const char *path, const char *where)
{
    static char text[1 << 16];
    const char *ok;
    long keep;
    (void)read_file(path, text, sizeof text);
    ok = strstr(text, "\nok\n");
    assert_non_null(ok);
    if (strcmp(where, "empty") == 0) {
        keep = 0;
    } else if (strcmp(where, "header") == 0) {
        keep = (long)(strchr(text, '\n') - text) + 5; /* inside the arguments' line */
    } else if (strcmp(where, "after ok") == 0) {
        keep = (long)(ok - text) + 4;
    } else {
        keep = (long)(ok - text) + 4 + (long)(strlen(ok + 4) / 2); /* the JSON in half */
    }
    assert_int_equal(truncate(path, keep), 0);
    return keep;
}

/* A point file cut at any place is run again on the resume, exactly those, and the table lists
 * each point's own metrics (before: a file cut after its "ok" line showed another point's
 * metrics; one cut in its JSON was never run again and every resume exited 1). */
static void test_resume_reruns_exactly_the_damaged_points(void **state)
{
    static const char *const where[5] = {"intact", "empty", "header", "after ok", "json"};
    static const char *const lambda[5] = {"20", "40", "60", "80", "100"};
    static char before[1 << 20];
    char d5[] = "/tmp/sixphase-sweep5-XXXXXX", path[5][600], args[64];
    struct stat st[5], again;
    int k;
    (void)state;
    assert_non_null(mkdtemp(d5));
    assert_int_equal(shf("%s sweep --out %s " DAMAGE_GRID " 2> %s/summary.txt", EXE, d5, d5), 0);
    (void)snprintf(before, sizeof before, "%s", read_in_dir(d5, "sweep.csv"));
    for (k = 0; k < 5; k++) {
        (void)snprintf(args, sizeof args, "--lambda %s", lambda[k]);
        point_file(d5, args, path[k], sizeof path[k]);
        if (k > 0) {
            print_message("cut %s at %ld bytes (%s)\n", path[k], cut_point(path[k], where[k]),
                          where[k]);
        }
        assert_int_equal(stat(path[k], &st[k]), 0);
    }
    sleep(1); /* a rewritten point file shows a later time */
    assert_int_equal(shf("%s sweep --out %s " DAMAGE_GRID " 2> %s/summary.txt", EXE, d5, d5), 0);
    assert_non_null(strstr(read_in_dir(d5, "summary.txt"), "(1 from an earlier run"));
    assert_non_null(strstr(read_in_dir(d5, "summary.txt"), "5 ok, 0 stopped by a drive fault, 0 "
                                                           "failed"));
    for (k = 0; k < 5; k++) {
        assert_int_equal(stat(path[k], &again), 0);
        if (k == 0) {
            assert_true(again.st_mtime == st[0].st_mtime); /* the intact point: not run again */
        } else {
            assert_true(again.st_mtime > st[k].st_mtime); /* each damaged one: run again */
        }
    }
    assert_string_equal(read_in_dir(d5, "sweep.csv"), before); /* each point's own metrics */
    /* and once more: nothing left to run */
    assert_int_equal(shf("%s sweep --out %s " DAMAGE_GRID " 2> %s/summary.txt", EXE, d5, d5), 0);
    assert_non_null(strstr(read_in_dir(d5, "summary.txt"), "(5 from an earlier run"));
    assert_int_equal(shf("rm -rf %s", d5), 0);
}

/* A points folder the sweep cannot write is reported as such, in one line, before any point
 * runs: a file where the folder should be (fails for root too, as CI runs) and, when not root,
 * a read-only folder. */
static void test_unwritable_points_folder_reported(void **state)
{
    char d6[] = "/tmp/sixphase-sweep6-XXXXXX";
    const char *msg;
    (void)state;
    assert_non_null(mkdtemp(d6));
    assert_int_equal(shf("echo not-a-folder > %s/points", d6), 0);
    assert_int_equal(shf("%s sweep --out %s " DAMAGE_GRID " 2> %s/err.txt", EXE, d6, d6), 1);
    msg = read_in_dir(d6, "err.txt");
    assert_one_line(msg);
    assert_non_null(strstr(msg, "cannot write"));
    assert_non_null(strstr(msg, "/points/: Not a directory"));
    assert_int_not_equal(shf("test -e %s/sweep.csv", d6), 0); /* nothing ran */
    if (geteuid() != 0) {
        assert_int_equal(shf("rm %s/points && mkdir -m 555 %s/points", d6, d6), 0);
        assert_int_equal(shf("%s sweep --out %s " DAMAGE_GRID " 2> %s/err.txt", EXE, d6, d6), 1);
        msg = read_in_dir(d6, "err.txt");
        assert_one_line(msg);
        assert_non_null(strstr(msg, "/points/: Permission denied"));
    } else {
        print_message("running as root: the read-only folder case is skipped\n");
    }
    assert_int_equal(shf("chmod -R u+w %s && rm -rf %s", d6, d6), 0);
}

static void test_bad_grids_refused(void **state)
{
    static const char *const bad[] = {
        "--lambda 10:5:1", "--lambda 10:20:0", "--lambda ,", "--bogus 1,2", "--lambda 20,abc",
        "--lambda 1:250:1 --fs 5000,10000", "--lambda 20,30 --plot", "--lambda 20,30 --jobs 0",
        /* plain decimals, as every other number (strtol took these) */
        "--lambda 20,30 --jobs 010", "--lambda 20,30 --jobs 2x"};
    size_t k;
    (void)state;
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        assert_int_equal(
            shf("%s sweep --out %s --controller ddc %s 2> %s/err.txt", EXE, dir, bad[k], dir), 2);
        assert_one_line(read_in_dir(dir, "err.txt"));
    }
}

/* 402 points need --force; with it they run (0.01 s each). */
static void test_force_lifts_the_cap(void **state)
{
    char d4[] = "/tmp/sixphase-sweep4-XXXXXX";
    const char *t;
    int lines = 0;
    (void)state;
    assert_non_null(mkdtemp(d4));
    assert_int_equal(shf("%s sweep --out %s --controller ddc --duration 0.01 --lambda 1:201:1 --fs "
                         "9000,10000 --no-plots --quiet 2> %s/err.txt",
                         EXE, d4, d4),
                     2);
    assert_one_line(read_in_dir(d4, "err.txt"));
    assert_int_equal(shf("%s sweep --out %s --controller ddc --duration 0.01 --lambda 1:201:1 --fs "
                         "9000,10000 --no-plots --quiet --force",
                         EXE, d4),
                     0);
    for (t = read_in_dir(d4, "sweep.csv"); (t = strchr(t, '\n')) != NULL; t++) {
        lines++;
    }
    assert_int_equal(lines, 403);
    assert_int_equal(shf("rm -rf %s", d4), 0);
}

/* A point whose run fails (the drive stops in its calibration at 800 V) fails the sweep, and
 * a rerun runs it again rather than taking the failure as done; list values in the JSON are
 * numbers. */
static void test_failed_points_rerun_and_json_numbers(void **state)
{
    char d2[] = "/tmp/sixphase-sweep2-XXXXXX";
    static flat_t row;
    (void)state;
    assert_non_null(mkdtemp(d2));
    assert_int_equal(shf("%s sweep --out %s --controller ddc --vdc 800 --duration 0.3,0.5 "
                         "--no-plots 2> %s/summary.txt",
                         EXE, d2, d2),
                     1);
    assert_int_equal(shf("%s sweep --out %s --controller ddc --vdc 800 --duration 0.3,0.5 "
                         "--no-plots 2> %s/summary.txt",
                         EXE, d2, d2),
                     1);
    assert_non_null(strstr(read_in_dir(d2, "summary.txt"), "(0 from an earlier run"));
    assert_non_null(strstr(read_in_dir(d2, "summary.txt"), "0 ok, 0 stopped by a drive fault, 2 "
                                                           "failed"));
    csv_row(d2, 1, &row);
    assert_field(&row, "outcome", "failed");
    assert_non_null(strstr(flat_get(&row, "error"), "during its ADC calibration"));
    assert_int_equal(shf("%s sweep --out %s --controller ddc --lambda .5,1 --duration 0.1 "
                         "--no-plots --quiet",
                         EXE, d2),
                     0);
    assert_non_null(strstr(read_in_dir(d2, "sweep.json"), "\"--lambda\": 0.5,"));
    assert_non_null(strstr(read_in_dir(d2, "sweep.json"), "\"lambda\": 0.5,"));
    assert_int_equal(shf("rm -rf %s", d2), 0);
}

static unsigned png_size(const char *d, const char *name, unsigned *height)
{
    char path[300];
    unsigned char h[24];
    struct stat st;
    FILE *f;
    (void)snprintf(path, sizeof path, "%s/%s", d, name);
    f = fopen(path, "rb");
    assert_non_null(f);
    assert_int_equal(fread(h, 1, 24, f), 24);
    fclose(f);
    assert_int_equal(stat(path, &st), 0);
    assert_true(st.st_size > 10000); /* something drawn */
    *height = (unsigned)((h[20] << 24) | (h[21] << 16) | (h[22] << 8) | h[23]);
    return (unsigned)((h[16] << 24) | (h[17] << 16) | (h[18] << 8) | h[19]);
}

/* The example in small: MPTC-49 trips at every point. */
static void test_faulted_points_marked_and_left_out_of_the_plots(void **state)
{
    char d3[] = "/tmp/sixphase-sweep3-XXXXXX";
    static flat_t row;
    const char *line;
    unsigned w, h;
    int k, front = 0;
    (void)state;
    assert_non_null(mkdtemp(d3));
    assert_int_equal(shf("%s sweep --out %s --lambda 20,100 --controller ddc,mptc49 --duration "
                         "0.3 2> %s/summary.txt",
                         EXE, d3, d3),
                     0);
    assert_non_null(strstr(read_in_dir(d3, "summary.txt"),
                           "2 ok, 2 stopped by a drive fault (OVERCURRENT 2), 0 failed"));
    for (k = 0; k < 4; k++) {
        csv_row(d3, k, &row);
        assert_field(&row, "outcome", (k % 2 == 0) ? "ok" : "fault");
        assert_field(&row, "fault_name", (k % 2 == 0) ? "NONE" : "OVERCURRENT");
    }
    w = png_size(d3, "plots/thd_percent.png", &h);
    assert_true(w == 630 && h == 360);
    w = png_size(d3, "plots/tradeoff.png", &h);
    assert_true(w == 900 && h == 360);
    line = strchr(read_in_dir(d3, "plots/pareto.csv"), '\n');
    for (; line && line[1] != '\0'; line = strchr(line + 1, '\n')) {
        char metric[40];
        int point;
        double fsw, value;
        assert_int_equal(sscanf(line + 1, "%39[^,],%d,%lf,%lf", metric, &point, &fsw, &value), 4);
        assert_true(point == 0 || point == 2); /* the DDC points */
        assert_true(fsw > 1000.0 && value > 0.0);
        front++;
    }
    assert_true(front >= 2); /* one per trade-off at least */
    assert_int_equal(shf("rm -rf %s", d3), 0);
}

static void test_run_plot(void **state)
{
    char path[200], none[200];
    unsigned w, h;
    (void)state;
    assert_int_equal(shf("%s run --controller ddc --scenario steady --duration 0.2 --out %s "
                         "--plot --quiet",
                         EXE, dir),
                     0);
    w = png_size(dir, "run.png", &h);
    assert_true(w == 1000 && h == 1400);
    (void)snprintf(path, sizeof path, "%s/run.png", dir);
    assert_int_equal(remove(path), 0);
    assert_int_equal(shf("%s plot %s", EXE, dir), 0);
    assert_int_equal(access(path, R_OK), 0);
    assert_int_equal(
        shf("%s run --controller ddc --scenario steady --plot 2> %s/err.txt", EXE, dir), 2);
    assert_one_line(read_in_dir(dir, "err.txt"));
    /* refused before anything runs: the directory is not even made */
    (void)snprintf(none, sizeof none, "%s/never", dir);
    assert_int_equal(shf("%s run --controller ddc --scenario steady --no-trace --out %s --plot "
                         "2> %s/err.txt",
                         EXE, none, dir),
                     2);
    assert_one_line(read_in_dir(dir, "err.txt"));
    assert_int_not_equal(access(none, F_OK), 0);
    assert_int_not_equal(shf("%s plot %s 2> %s/err.txt", EXE, none, dir), 0);
    assert_one_line(read_in_dir(dir, "err.txt"));
    assert_int_equal(shf("rm -rf %s", dir), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table_equals_single_runs),
        cmocka_unit_test(test_resume_runs_only_the_missing_point),
        cmocka_unit_test(test_rebuilt_binary_reruns_every_point),
        cmocka_unit_test(test_resume_reruns_exactly_the_damaged_points),
        cmocka_unit_test(test_unwritable_points_folder_reported),
        cmocka_unit_test(test_bad_grids_refused),
        cmocka_unit_test(test_force_lifts_the_cap),
        cmocka_unit_test(test_failed_points_rerun_and_json_numbers),
        cmocka_unit_test(test_faulted_points_marked_and_left_out_of_the_plots),
        cmocka_unit_test(test_run_plot),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
