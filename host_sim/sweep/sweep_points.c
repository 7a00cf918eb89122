/* A sweep's point files, see sweep_points.h. */
#define _POSIX_C_SOURCE 200809L /* fileno, fsync */

#include "sweep_points.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sweep_table.h"

#define POINT_LINE 4096
#define POINT_PATH 1200
#define POINT_FILE_MAX (4L << 20) /* a point's file is about 10 kB; larger is not one */

static uint64_t fnv1a(uint64_t h, const unsigned char *s, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) {
        h = (h ^ s[i]) * 1099511628211ull;
    }
    return h;
}

#define FNV1A_START 14695981039346656037ull

void sweep_binary_id(char out[SWEEP_BINARY_ID_LEN])
{
    uint64_t h = FNV1A_START;
    unsigned char buf[65536];
    size_t n;
    FILE *f = fopen("/proc/self/exe", "rb");
    out[0] = '\0';
    if (!f) {
        return;
    }
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) {
        h = fnv1a(h, buf, n);
    }
    if (!ferror(f)) {
        (void)snprintf(out, SWEEP_BINARY_ID_LEN, "%016llx", (unsigned long long)h);
    }
    (void)fclose(f);
}

void sweep_point_args_text(const sweep_grid_t *g, long p, char *out, size_t len)
{
    char *args[SWEEP_MAX_ARGS + 2 * SWEEP_MAX_AXES];
    const int n = sweep_grid_args(g, p, args);
    size_t used = 0;
    int k;
    out[0] = '\0';
    for (k = 0; k < n && used < len; k++) {
        used += (size_t)snprintf(out + used, len - used, "%s%s", k ? " " : "", args[k]);
    }
}

/* DIR/points/KEY followed by suffix; the point's arguments into args. */
static void point_path(const sweep_grid_t *g, long p, const char *suffix, char *out, size_t len,
                       char args[POINT_LINE])
{
    sweep_point_args_text(g, p, args, POINT_LINE);
    (void)snprintf(
        out, len, "%s/points/%016llx%s", g->out,
        (unsigned long long)fnv1a(FNV1A_START, (const unsigned char *)args, strlen(args)), suffix);
}

int sweep_points_prepare(const sweep_grid_t *g, char *err, size_t len)
{
    char dir[POINT_PATH], probe[POINT_PATH + 32];
    FILE *f;
    (void)snprintf(dir, sizeof dir, "%s/points", g->out);
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        (void)snprintf(err, len, "cannot write %s/: %s", dir, strerror(errno));
        return -1;
    }
    /* a read-only folder, or a file where the folder should be: found before any point runs */
    (void)snprintf(probe, sizeof probe, "%s/.probe-%ld.tmp", dir, (long)getpid());
    f = fopen(probe, "w");
    if (!f) {
        (void)snprintf(err, len, "cannot write %s/: %s", dir, strerror(errno));
        return -1;
    }
    (void)fclose(f);
    (void)remove(probe);
    return 0;
}

/* The file's text: ferror, fsync and fclose checked, so a full disk is reported, not left as
 * a short file to be renamed into place. */
static int point_write_text(FILE *f, const char *binary_id, const char *args, const sim_case_t *c)
{
    int rc;
    fprintf(f, "sixphase-sim %s\n%s\n", binary_id, args);
    if (c->ok) {
        fprintf(f, "ok\n");
        sim_print_metrics_json_no_timings(f, &c->cfg, &c->res);
    } else {
        fprintf(f, "failed %s\n", c->err[0] ? c->err : "(no message)");
    }
    rc = (fflush(f) == 0 && !ferror(f) && fsync(fileno(f)) == 0) ? 0 : -1;
    return (fclose(f) == 0) ? rc : -1;
}

int sweep_point_save(const sweep_grid_t *g, const char *binary_id, long p, const sim_case_t *c,
                     char *err, size_t len)
{
    char path[POINT_PATH], tmp[POINT_PATH], args[POINT_LINE];
    FILE *f;
    point_path(g, p, ".txt", path, sizeof path, args);
    point_path(g, p, ".tmp", tmp, sizeof tmp, args);
    errno = 0;
    f = fopen(tmp, "w");
    if (!f || point_write_text(f, binary_id, args, c) != 0 || rename(tmp, path) != 0) {
        (void)snprintf(err, len, "cannot write %s: %s", path,
                       errno ? strerror(errno) : "write error");
        (void)remove(tmp);
        return -1;
    }
    return 0;
}

/* The whole file, malloc'd and NUL-terminated; NULL with the reason in err. */
static char *point_slurp(const char *path, char *err, size_t len)
{
    FILE *f = fopen(path, "rb");
    char *text;
    size_t n;
    if (!f) {
        (void)snprintf(err, len, "no result: %s: %s", path, strerror(errno));
        return NULL;
    }
    text = (char *)malloc((size_t)POINT_FILE_MAX + 1u);
    n = text ? fread(text, 1, (size_t)POINT_FILE_MAX + 1u, f) : 0u;
    if (!text || ferror(f) || n > (size_t)POINT_FILE_MAX) {
        (void)snprintf(err, len, "no result: cannot read %s", path);
        free(text);
        text = NULL;
    } else {
        text[n] = '\0';
    }
    (void)fclose(f);
    return text;
}

/* Splits off the next line (it must end in a newline); NULL when the text ends first. */
static char *point_line(char **at)
{
    char *line = *at;
    char *nl = strchr(line, '\n');
    if (!nl) {
        return NULL;
    }
    *nl = '\0';
    *at = nl + 1;
    return line;
}

/* Point p's file checked against the point: 1 a whole ok run (*json points into *text), 0 with
 * the reason in err. *text is malloc'd (free it) unless NULL. */
static int point_check(const sweep_grid_t *g, long p, const char *binary_id, char **text,
                       const char **json, char *err, size_t len)
{
    char path[POINT_PATH], args[POINT_LINE];
    char *at, *id, *argl, *outcome;
    point_path(g, p, ".txt", path, sizeof path, args);
    *text = point_slurp(path, err, len);
    if (!*text) {
        return 0;
    }
    at = *text;
    id = point_line(&at);
    argl = id ? point_line(&at) : NULL;
    outcome = argl ? point_line(&at) : NULL;
    if (!outcome || strncmp(id, "sixphase-sim ", 13) != 0 || strcmp(argl, args) != 0) {
        (void)snprintf(err, len, "no result: %s is cut short or another point's", path);
        return 0;
    }
    if (binary_id && strcmp(id + 13, binary_id) != 0) {
        (void)snprintf(err, len, "run by another build");
        return 0;
    }
    if (strcmp(outcome, "ok") != 0) {
        (void)snprintf(err, len, "%s", strncmp(outcome, "failed ", 7) == 0 ? outcome + 7 : outcome);
        return 0;
    }
    if (!sweep_table_metrics_whole(at)) {
        (void)snprintf(err, len, "no result: the metrics in %s are cut short or unreadable", path);
        return 0;
    }
    *json = at;
    return 1;
}

int sweep_point_done(const sweep_grid_t *g, const char *binary_id, long p)
{
    char err[POINT_PATH + 100];
    char *text = NULL;
    const char *json = NULL;
    int done;
    if (binary_id[0] == '\0') {
        return 0;
    }
    done = point_check(g, p, binary_id, &text, &json, err, sizeof err);
    free(text);
    return done;
}

int sweep_point_read(const sweep_grid_t *g, long p, char **json, char *err, size_t len)
{
    char *text = NULL;
    const char *metrics = NULL;
    *json = NULL;
    if (!point_check(g, p, NULL, &text, &metrics, err, len)) {
        free(text);
        return 0;
    }
    memmove(text, metrics, strlen(metrics) + 1u);
    *json = text;
    return 1;
}
