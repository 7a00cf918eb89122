/* A sweep's table, see sweep_table.h. */
#include "sweep_table.h"

#include <ctype.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TABLE_MAX_COLUMNS 320
#define TABLE_KEY 80
#define TABLE_VALUE 256

typedef enum { CELL_NUMBER, CELL_TEXT, CELL_BOOL, CELL_NULL } cell_kind_t;

typedef struct {
    char key[TABLE_KEY];
    char value[TABLE_VALUE];
    cell_kind_t kind;
} table_cell_t;

typedef struct {
    int n;
    table_cell_t cell[TABLE_MAX_COLUMNS];
} table_row_t;

typedef struct {
    int n;
    char name[TABLE_MAX_COLUMNS][TABLE_KEY];
} table_columns_t;

/* ---- metrics.json flattened into cells ---- */

typedef struct {
    const char *s;
    table_row_t *row;
} flat_t;

static int flat_value(flat_t *f, const char *key);

static void flat_space(flat_t *f)
{
    while (isspace((unsigned char)*f->s)) {
        f->s++;
    }
}

/* A string at '"' into out (metrics.json writes no escapes; a backslash keeps the next
 * character). */
static int flat_string(flat_t *f, char *out, size_t len)
{
    size_t n = 0;
    f->s++;
    while (*f->s != '\0' && *f->s != '"') {
        char c = *f->s++;
        if (c == '\\' && *f->s != '\0') {
            c = *f->s++;
        }
        if (n + 1 < len) {
            out[n++] = c;
        }
    }
    out[n] = '\0';
    if (*f->s != '"') {
        return -1;
    }
    f->s++;
    return 0;
}

/* Members of an object or elements of an array, at '{' or '['; an element's key is
 * prefix_A, prefix_B, ... (the arrays of metrics.json are per phase). */
static int flat_members(flat_t *f, const char *prefix, int object)
{
    const char close = object ? '}' : ']';
    int k = 0;
    f->s++;
    flat_space(f);
    if (*f->s == close) {
        f->s++;
        return 0;
    }
    for (;; k++) {
        char name[TABLE_KEY], key[2 * TABLE_KEY + 4];
        flat_space(f);
        if (object && (*f->s != '"' || flat_string(f, name, sizeof name) != 0)) {
            return -1;
        }
        if (object) {
            flat_space(f);
            if (*f->s != ':') { /* not *f->s++: a cut text must not step past its end */
                return -1;
            }
            f->s++;
            (void)snprintf(key, sizeof key, "%s%s%s", prefix, prefix[0] ? "_" : "", name);
        } else {
            (void)snprintf(key, sizeof key, "%s_%c", prefix, (char)('A' + k % 26));
        }
        if (strlen(key) >= TABLE_KEY || flat_value(f, key) != 0) {
            return -1;
        }
        flat_space(f);
        if (*f->s == close) {
            f->s++;
            return 0;
        }
        if (*f->s != ',') {
            return -1;
        }
        f->s++;
    }
}

/* A scalar (number, true, false, null) up to the next delimiter. */
static int flat_scalar(flat_t *f, table_cell_t *c)
{
    const size_t n = strcspn(f->s, ",}] \t\r\n");
    char *end = NULL;
    if (n == 0 || n >= sizeof c->value) {
        return -1;
    }
    memcpy(c->value, f->s, n);
    c->value[n] = '\0';
    f->s += n;
    if (strcmp(c->value, "null") == 0) {
        c->kind = CELL_NULL;
    } else if (strcmp(c->value, "true") == 0 || strcmp(c->value, "false") == 0) {
        c->kind = CELL_BOOL;
    } else {
        (void)strtod(c->value, &end);
        if (*end != '\0') {
            return -1;
        }
        c->kind = CELL_NUMBER;
    }
    return 0;
}

static int flat_value(flat_t *f, const char *key)
{
    table_cell_t *c;
    flat_space(f);
    if (*f->s == '{' || *f->s == '[') {
        return flat_members(f, key, *f->s == '{');
    }
    if (f->row->n == TABLE_MAX_COLUMNS) {
        return -1;
    }
    c = &f->row->cell[f->row->n];
    (void)snprintf(c->key, sizeof c->key, "%s", key);
    if (*f->s == '"') {
        c->kind = CELL_TEXT;
        if (flat_string(f, c->value, sizeof c->value) != 0) {
            return -1;
        }
    } else if (flat_scalar(f, c) != 0) {
        return -1;
    }
    f->row->n++;
    return 0;
}

int sweep_table_metrics_whole(const char *json)
{
    static table_row_t scratch;
    flat_t f;
    scratch.n = 0;
    f.s = json;
    f.row = &scratch;
    flat_space(&f);
    if (*f.s != '{' || flat_members(&f, "", 1) != 0) {
        return 0;
    }
    flat_space(&f);
    return *f.s == '\0';
}

/* ---- one point's row ---- */

static void row_add(table_row_t *r, const char *key, const char *value, cell_kind_t kind)
{
    table_cell_t *c;
    if (r->n == TABLE_MAX_COLUMNS) {
        return;
    }
    c = &r->cell[r->n++];
    (void)snprintf(c->key, sizeof c->key, "%s", key);
    (void)snprintf(c->value, sizeof c->value, "%s", value);
    c->kind = kind;
}

/* Whether v is a number as JSON writes one: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)? */
static int json_number(const char *v)
{
    v += (*v == '-');
    if (!isdigit((unsigned char)*v) || (v[0] == '0' && isdigit((unsigned char)v[1]))) {
        return 0;
    }
    v += strspn(v, "0123456789");
    if (*v == '.') {
        const size_t n = strspn(v + 1, "0123456789");
        if (n == 0) {
            return 0;
        }
        v += 1 + n;
    }
    if (*v == 'e' || *v == 'E') {
        size_t n;
        v += 1 + (v[1] == '+' || v[1] == '-');
        n = strspn(v, "0123456789");
        if (n == 0) {
            return 0;
        }
        v += n;
    }
    return *v == '\0';
}

/* An option's value: a number (rewritten as JSON writes numbers when it is not one already:
 * ".5" -> "0.5") or text. */
static void row_add_option(table_row_t *r, const char *option, const char *v)
{
    char *end = NULL;
    const double x = strtod(v, &end);
    char text[64];
    if (end == v || *end != '\0') {
        row_add(r, option, v, CELL_TEXT);
    } else if (json_number(v)) {
        row_add(r, option, v, CELL_NUMBER);
    } else {
        (void)snprintf(text, sizeof text, "%.15g", x);
        row_add(r, option, text, CELL_NUMBER);
    }
}

static const table_cell_t *row_find(const table_row_t *r, const char *key)
{
    int k;
    for (k = 0; k < r->n; k++) {
        if (strcmp(r->cell[k].key, key) == 0) {
            return &r->cell[k];
        }
    }
    return NULL;
}

/* The options of point p as given: the swept ones, then the rest (a flag is true). */
static void row_options(table_row_t *r, const sweep_grid_t *g, long p)
{
    int index[SWEEP_MAX_AXES];
    int k;
    sweep_grid_point(g, p, index);
    for (k = 0; k < g->n_axes; k++) {
        row_add_option(r, g->axis[k].option, g->axis[k].value[index[k]]);
    }
    for (k = 0; k < g->n_fixed; k++) {
        const char *v = g->fixed_value[k];
        if (v) {
            row_add_option(r, g->fixed_option[k], v);
        } else {
            row_add(r, g->fixed_option[k], "true", CELL_BOOL);
        }
    }
}

/* Point p's row: its options, outcome and metrics. */
static void row_build(table_row_t *r, const sweep_grid_t *g, long p, sweep_table_read_fn read)
{
    char num[32], err[TABLE_VALUE] = "";
    char *json = NULL;
    const int ok = read(g, p, &json, err, sizeof err);
    flat_t f;
    r->n = 0;
    (void)snprintf(num, sizeof num, "%ld", p);
    row_add(r, "point", num, CELL_NUMBER);
    row_options(r, g, p);
    row_add(r, "outcome", ok ? "ok" : "failed", CELL_TEXT);
    row_add(r, "error", err, err[0] ? CELL_TEXT : CELL_NULL);
    if (ok) {
        const int before = r->n;
        f.s = json;
        f.row = r;
        if (flat_members(&f, "", 1) != 0) {
            r->n = before;
            (void)snprintf(r->cell[before - 2].value, TABLE_VALUE, "failed");
            (void)snprintf(r->cell[before - 1].value, TABLE_VALUE, "unreadable metrics");
            r->cell[before - 1].kind = CELL_TEXT;
        } else {
            const table_cell_t *fault = row_find(r, "drive_fault");
            if (fault && strtol(fault->value, NULL, 10) != 0) {
                (void)snprintf(r->cell[before - 2].value, TABLE_VALUE, "fault");
            }
        }
    }
    free(json);
}

/* ---- columns: every row's keys, each new one after the key before it in its row ---- */

static int columns_find(const table_columns_t *c, const char *key)
{
    int k;
    for (k = 0; k < c->n; k++) {
        if (strcmp(c->name[k], key) == 0) {
            return k;
        }
    }
    return -1;
}

static void columns_merge(table_columns_t *c, const table_row_t *r)
{
    int k, at = -1;
    for (k = 0; k < r->n; k++) {
        const int found = columns_find(c, r->cell[k].key);
        if (found >= 0) {
            at = found;
        } else if (c->n < TABLE_MAX_COLUMNS) {
            at++;
            memmove(c->name[at + 1], c->name[at], (size_t)(c->n - at) * sizeof c->name[0]);
            (void)snprintf(c->name[at], sizeof c->name[at], "%s", r->cell[k].key);
            c->n++;
        }
    }
}

/* ---- output ---- */

static void csv_cell(FILE *f, const table_cell_t *c)
{
    const char *v;
    if (!c || c->kind == CELL_NULL) {
        return;
    }
    if (c->kind == CELL_BOOL) {
        fputc(c->value[0] == 't' ? '1' : '0', f);
        return;
    }
    if (c->kind == CELL_NUMBER || strpbrk(c->value, ",\"\n") == NULL) {
        fputs(c->value, f);
        return;
    }
    fputc('"', f);
    for (v = c->value; *v != '\0'; v++) {
        if (*v == '"') {
            fputc('"', f); /* a quote inside a quoted field is doubled */
        }
        fputc(*v, f);
    }
    fputc('"', f);
}

static void json_text(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s != '\0'; s++) {
        if (*s == '"' || *s == '\\') {
            fputc('\\', f);
        }
        fputc(*s, f);
    }
    fputc('"', f);
}

static void write_row(FILE *csv, FILE *json, const table_columns_t *cols, const table_row_t *r,
                      int last)
{
    int k;
    fputs("  {", json);
    for (k = 0; k < cols->n; k++) {
        const table_cell_t *c = row_find(r, cols->name[k]);
        if (k > 0) {
            fputc(',', csv);
            fputs(", ", json);
        }
        csv_cell(csv, c);
        json_text(json, cols->name[k]);
        fputs(": ", json);
        if (!c || c->kind == CELL_NULL) {
            fputs("null", json);
        } else if (c->kind == CELL_TEXT) {
            json_text(json, c->value);
        } else {
            fputs(c->value, json);
        }
    }
    fputs("\n", csv);
    fprintf(json, "}%s\n", last ? "" : ",");
}

/* The outcome counts and the faults that stopped points, with their counts. */
static void summary_add(sweep_summary_t *s, const table_row_t *r)
{
    const char *outcome = row_find(r, "outcome")->value;
    const table_cell_t *name = row_find(r, "fault_name");
    char item[TABLE_VALUE + 2], *at;
    if (strcmp(outcome, "ok") == 0) {
        s->ok++;
        return;
    }
    if (strcmp(outcome, "failed") == 0) {
        s->failed++;
        return;
    }
    s->faulted++;
    (void)snprintf(item, sizeof item, "%s ", name ? name->value : "?");
    at = strstr(s->faults, item);
    if (at) { /* "NAME count": count up in place */
        char rest[256];
        char *end = NULL;
        const long n = strtol(at + strlen(item), &end, 10);
        (void)snprintf(rest, sizeof rest, "%s", end);
        (void)snprintf(at, sizeof s->faults - (size_t)(at - s->faults), "%s%ld%s", item, n + 1,
                       rest);
    } else {
        const size_t used = strlen(s->faults);
        (void)snprintf(s->faults + used, sizeof s->faults - used, "%s%s1", used ? ", " : "", item);
    }
}

int sweep_table_write(const sweep_grid_t *g, long points, sweep_table_read_fn read,
                      sweep_summary_t *sum)
{
    static table_row_t row;
    static table_columns_t cols;
    char path[1200];
    FILE *csv, *json;
    long p;
    int k, rc;
    memset(sum, 0, sizeof *sum);
    cols.n = 0;
    for (p = 0; p < points; p++) {
        row_build(&row, g, p, read);
        columns_merge(&cols, &row);
    }
    (void)snprintf(path, sizeof path, "%s/sweep.csv", g->out);
    csv = fopen(path, "w");
    (void)snprintf(path, sizeof path, "%s/sweep.json", g->out);
    json = fopen(path, "w");
    if (!csv || !json) {
        if (csv) {
            (void)fclose(csv);
        }
        if (json) {
            (void)fclose(json);
        }
        return -1;
    }
    for (k = 0; k < cols.n; k++) {
        fprintf(csv, "%s%s", k ? "," : "", cols.name[k]);
    }
    fputs("\n", csv);
    fputs("[\n", json);
    for (p = 0; p < points; p++) {
        row_build(&row, g, p, read);
        summary_add(sum, &row);
        write_row(csv, json, &cols, &row, p + 1 == points);
    }
    fputs("]\n", json);
    rc = (fclose(csv) == 0) ? 0 : -1;
    return (fclose(json) == 0) ? rc : -1;
}
