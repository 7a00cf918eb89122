/* Streaming CSV output, see recorder.h. */
#define _POSIX_C_SOURCE 200809L

#include "recorder.h"

#include <errno.h>
#include <string.h>

#include "csv_format.h"

static const char trace_header[] =
    "t,speed_rpm,theta_e,i_A,i_B,i_C,i_D,i_E,i_F,i_d,i_q,i_x,i_y,Te,Te_avg,psi_s,Tref,psi_ref,legs,"
    "duty,vector\n";
static const char fine_header[] = "t,i_A,theta_e_unwrapped,i_x,i_y,Te,speed_rpm\n";

static int csv_file_open(sim_csv_file_t *cf, const char *dir, const char *name, const char *header)
{
    (void)snprintf(cf->path, sizeof cf->path, "%s/%s", dir, name);
    cf->used = 0;
    cf->failed = false;
    cf->f = fopen(cf->path, "w");
    if (!cf->f) {
        return -1;
    }
    memcpy(cf->buf, header, strlen(header));
    cf->used = strlen(header);
    return 0;
}

static void csv_file_flush(sim_csv_file_t *cf)
{
    if (cf->used > 0 && fwrite(cf->buf, 1, cf->used, cf->f) != cf->used) {
        cf->failed = true;
    }
    cf->used = 0;
}

/* Room for one more row, the buffer flushed when it could not take the longest row. */
static char *csv_file_room(sim_csv_file_t *cf)
{
    if (cf->used + SIM_ROW_MAX_CHARS > sizeof cf->buf) {
        csv_file_flush(cf);
    }
    return cf->buf + cf->used;
}

static int csv_file_close(sim_csv_file_t *cf)
{
    int rc;
    if (!cf->f) {
        return 0;
    }
    csv_file_flush(cf);
    rc = (fclose(cf->f) == 0 && !cf->failed) ? 0 : -1;
    cf->f = NULL;
    return rc;
}

int sim_recorder_open(sim_recorder_t *r, const char *dir, bool trace, bool fine, double limit_mb,
                      char *err, size_t err_len)
{
    r->trace.f = r->fine.f = NULL;
    r->trace_on = dir != NULL && trace;
    r->fine_on = dir != NULL && fine;
    r->limit_bytes = limit_mb * 1e6;
    r->bytes = (double)((r->trace_on ? sizeof trace_header - 1u : 0u) +
                        (r->fine_on ? sizeof fine_header - 1u : 0u));
    r->limit_reached = false;
    if (r->trace_on && csv_file_open(&r->trace, dir, "trace.csv", trace_header) != 0) {
        (void)snprintf(err, err_len, "cannot write %s: %s", r->trace.path, strerror(errno));
        return -1;
    }
    if (r->fine_on && csv_file_open(&r->fine, dir, "fine.csv", fine_header) != 0) {
        (void)snprintf(err, err_len, "cannot write %s: %s", r->fine.path, strerror(errno));
        sim_recorder_discard(r);
        return -1;
    }
    return 0;
}

/* fprintf(f, "%.6f,%.3f,%.5f x 16,%s,%.4f,%d\n", ...) of the earlier writer */
char *sim_trace_row_text(char *out, const sim_trace_row_t *row)
{
    const double five[16] = {row->theta_e,    row->i_phase[0], row->i_phase[1], row->i_phase[2],
                             row->i_phase[3], row->i_phase[4], row->i_phase[5], row->i_d,
                             row->i_q,        row->i_x,        row->i_y,        row->te,
                             row->te_avg,     row->psi_s,      row->tref,       row->psi_ref};
    int k;
    out = csv_put_fixed(out, row->t, 6);
    *out++ = ',';
    out = csv_put_fixed(out, row->speed_rpm, 3);
    for (k = 0; k < 16; k++) {
        *out++ = ',';
        out = csv_put_fixed(out, five[k], 5);
    }
    *out++ = ',';
    for (k = 0; k < 6; k++) {
        *out++ = (char)('0' + ((row->vector >> (5 - k)) & 1));
    }
    *out++ = ',';
    out = csv_put_fixed(out, row->duty, 4);
    *out++ = ',';
    out = csv_put_int(out, row->vector);
    *out++ = '\n';
    return out;
}

/* fprintf(f, "%.7f,%.5f,%.5f,%.5f,%.5f,%.5f,%.3f\n", ...) of the earlier writer */
char *sim_fine_row_text(char *out, const sim_fine_row_t *row)
{
    out = csv_put_fixed(out, row->t, 7);
    *out++ = ',';
    out = csv_put_fixed(out, row->i_a, 5);
    *out++ = ',';
    out = csv_put_fixed(out, row->theta_e_unwrapped, 5);
    *out++ = ',';
    out = csv_put_fixed(out, row->i_x, 5);
    *out++ = ',';
    out = csv_put_fixed(out, row->i_y, 5);
    *out++ = ',';
    out = csv_put_fixed(out, row->te, 5);
    *out++ = ',';
    out = csv_put_fixed(out, row->speed_rpm, 3);
    *out++ = '\n';
    return out;
}

/* Takes the row written at start into cf's buffer when it fits under the limit. */
static void recorder_take(sim_recorder_t *r, sim_csv_file_t *cf, const char *start, const char *end)
{
    const double n = (double)(end - start);
    if (r->limit_reached || r->bytes + n > r->limit_bytes) {
        r->limit_reached = true; /* the files end at the last whole row before the limit */
        return;
    }
    r->bytes += n;
    cf->used += (size_t)(end - start);
}

void sim_recorder_trace(sim_recorder_t *r, const sim_trace_row_t *row)
{
    if (r->trace_on && !r->limit_reached) {
        char *start = csv_file_room(&r->trace);
        recorder_take(r, &r->trace, start, sim_trace_row_text(start, row));
    }
}

void sim_recorder_fine(sim_recorder_t *r, const sim_fine_row_t *row)
{
    if (r->fine_on && !r->limit_reached) {
        char *start = csv_file_room(&r->fine);
        recorder_take(r, &r->fine, start, sim_fine_row_text(start, row));
    }
}

int sim_recorder_close(sim_recorder_t *r, char *err, size_t err_len)
{
    if (csv_file_close(&r->trace) != 0) {
        (void)snprintf(err, err_len, "cannot write %s", r->trace.path);
        return -1;
    }
    if (csv_file_close(&r->fine) != 0) {
        (void)snprintf(err, err_len, "cannot write %s", r->fine.path);
        return -1;
    }
    return 0;
}

void sim_recorder_discard(sim_recorder_t *r)
{
    if (r->trace.f) {
        (void)fclose(r->trace.f);
        r->trace.f = NULL;
        (void)remove(r->trace.path);
    }
    if (r->fine.f) {
        (void)fclose(r->fine.f);
        r->fine.f = NULL;
        (void)remove(r->fine.path);
    }
}
