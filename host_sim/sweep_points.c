/* A sweep's point files, see sweep_points.h. */
#include "sweep_points.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define POINT_LINE 4096

void sweep_binary_id(char out[SWEEP_BINARY_ID_LEN])
{
    uint64_t h = 14695981039346656037ull; /* FNV-1a 64 */
    unsigned char buf[65536];
    size_t n, i;
    FILE *f = fopen("/proc/self/exe", "rb");
    out[0] = '\0';
    if (!f) {
        return;
    }
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) {
        for (i = 0; i < n; i++) {
            h = (h ^ buf[i]) * 1099511628211ull;
        }
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

static void point_path(const sweep_grid_t *g, long p, char *out, size_t len)
{
    (void)snprintf(out, len, "%s/points/p%04ld.txt", g->out, p);
}

void sweep_point_save(const sweep_grid_t *g, const char *binary_id, long p, const sim_case_t *c)
{
    char path[1200], args[POINT_LINE];
    FILE *f;
    point_path(g, p, path, sizeof path);
    sweep_point_args_text(g, p, args, sizeof args);
    f = fopen(path, "w");
    if (!f) {
        return; /* the table reports the point as failed: its file is missing */
    }
    fprintf(f, "sixphase-sim %s\n%s\n", binary_id, args);
    if (c->ok) {
        fprintf(f, "ok\n");
        sim_print_metrics_json_no_timings(f, &c->cfg, &c->res);
    } else {
        fprintf(f, "failed %s\n", c->err[0] ? c->err : "(no message)");
    }
    (void)fclose(f);
}

/* The file's first three lines without their newlines; NULL when it is missing or short. */
static FILE *point_open(const sweep_grid_t *g, long p, char lines[3][POINT_LINE])
{
    char path[1200];
    int k;
    FILE *f;
    point_path(g, p, path, sizeof path);
    f = fopen(path, "r");
    for (k = 0; f && k < 3; k++) {
        if (!fgets(lines[k], POINT_LINE, f)) {
            (void)fclose(f);
            return NULL;
        }
        lines[k][strcspn(lines[k], "\n")] = '\0';
    }
    return f;
}

int sweep_point_done(const sweep_grid_t *g, const char *binary_id, long p)
{
    static char lines[3][POINT_LINE];
    char key[64], args[POINT_LINE];
    FILE *f;
    int done;
    if (binary_id[0] == '\0') {
        return 0;
    }
    f = point_open(g, p, lines);
    if (!f) {
        return 0;
    }
    (void)fclose(f);
    (void)snprintf(key, sizeof key, "sixphase-sim %s", binary_id);
    sweep_point_args_text(g, p, args, sizeof args);
    done = strcmp(lines[0], key) == 0 && strcmp(lines[1], args) == 0 && strcmp(lines[2], "ok") == 0;
    return done;
}

/* The rest of an open file, malloc'd; NULL when out of memory. */
static char *point_rest(FILE *f)
{
    size_t len = 0, cap = 8192;
    char *text = (char *)malloc(cap);
    size_t n;
    while (text && (n = fread(text + len, 1, cap - len - 1, f)) > 0) {
        len += n;
        if (len + 1 == cap) {
            char *grown = (char *)realloc(text, cap * 2);
            if (!grown) {
                free(text);
                return NULL;
            }
            text = grown;
            cap *= 2;
        }
    }
    if (text) {
        text[len] = '\0';
    }
    return text;
}

int sweep_point_read(const sweep_grid_t *g, long p, char **json, char *err, size_t len)
{
    static char lines[3][POINT_LINE];
    FILE *f = point_open(g, p, lines);
    *json = NULL;
    if (!f) {
        (void)snprintf(err, len, "no result: its point file is missing or cut short");
        return 0;
    }
    if (strcmp(lines[2], "ok") != 0) {
        (void)snprintf(err, len, "%s",
                       strncmp(lines[2], "failed ", 7) == 0 ? lines[2] + 7 : lines[2]);
        (void)fclose(f);
        return 0;
    }
    *json = point_rest(f);
    (void)fclose(f);
    if (!*json) {
        (void)snprintf(err, len, "out of memory");
        return 0;
    }
    return 1;
}
