/* rdoc.c - the result document's rows, their writers, and the reader of brdfbench.rows/1. */
#include "rdoc.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "jsonr.h"
#include "jsonw.h"
#include "room.h"
#include "schemas.h"

static const char *const direction_names[] = { "higher", "lower", "neither" };

const char *rd_direction_name(int d) { return d >= RD_HIGHER && d <= RD_NEITHER ? direction_names[d] : "?"; }

int rd_direction_of(const char *name)
{
    for (int d = RD_HIGHER; d <= RD_NEITHER; ++d)
        if (name && strcmp(name, direction_names[d]) == 0)
            return d;
    return -1;
}

void rdoc_init(struct rdoc *d, const char *schema, const char *kind, const char *file)
{
    memset(d, 0, sizeof *d);
    snprintf(d->schema, sizeof d->schema, "%s", schema ? schema : "");
    snprintf(d->kind, sizeof d->kind, "%s", kind ? kind : "");
    snprintf(d->file, sizeof d->file, "%s", file ? file : "");
}

static void free_texts(struct rd_text *t, int n)
{
    for (int i = 0; i < n; ++i)
        free(t[i].value);
    free(t);
}

void rdoc_free(struct rdoc *d)
{
    for (int i = 0; i < d->nrows; ++i) {
        for (int m = 0; m < d->rows[i].nmetrics; ++m) {
            free(d->rows[i].metrics[m].reps);
            free(d->rows[i].metrics[m].norm);
        }
        free(d->rows[i].metrics);
        free_texts(d->rows[i].texts, d->rows[i].ntexts);
    }
    free(d->rows);
    d->rows = NULL;
    d->nrows = d->cap = 0;
    free_texts(d->texts, d->ntexts);
    d->texts = NULL;
    d->ntexts = d->tcap = 0;
}

void rd_ctx_put(struct rd_context *c, const char *key, const char *value)
{
    if (!value || rd_ctx_get(c, key) || c->count == RD_MAX_CTX)
        return;
    snprintf(c->key[c->count], sizeof c->key[0], "%s", key);
    snprintf(c->value[c->count], sizeof c->value[0], "%s", value);
    c->count++;
}

const char *rd_ctx_get(const struct rd_context *c, const char *key)
{
    for (int i = 0; i < c->count; ++i)
        if (strcmp(c->key[i], key) == 0)
            return c->value[i];
    return NULL;
}

struct rd_device *rdoc_device(struct rdoc *d, const char *name)
{
    for (int i = 0; i < d->ndevices; ++i)
        if (strcmp(d->devices[i].name, name) == 0)
            return &d->devices[i];
    if (d->ndevices == RD_MAX_DEVICES)
        return NULL;
    struct rd_device *dv = &d->devices[d->ndevices++];
    memset(dv, 0, sizeof *dv);
    snprintf(dv->name, sizeof dv->name, "%s", name);
    return dv;
}

/* Out of memory: the document is incomplete, and no row or metric is given. */
static void *out_of_memory(struct rdoc *d)
{
    d->oom = 1;
    return NULL;
}

struct rd_row *rdoc_row(struct rdoc *d, const char *device, const char *model)
{
    struct rd_row *rows = room_for_one(d->rows, d->nrows, &d->cap, sizeof *rows, 32);
    if (!rows)
        return out_of_memory(d);
    d->rows = rows;
    struct rd_row *r = &d->rows[d->nrows++];
    memset(r, 0, sizeof *r);
    r->ok = 1;
    snprintf(r->status, sizeof r->status, "ok");
    snprintf(r->device, sizeof r->device, "%s", device ? device : "");
    snprintf(r->model, sizeof r->model, "%s", model ? model : "");
    return r;
}

static struct rd_key *add_key(struct rd_row *r, const char *name, const char *value)
{
    if (r->nkeys == RD_MAX_KEYS) {
        r->truncated = 1;
        return NULL;
    }
    struct rd_key *k = &r->keys[r->nkeys++];
    if ((size_t)snprintf(k->name, sizeof k->name, "%s", name) >= sizeof k->name ||
        (size_t)snprintf(k->value, sizeof k->value, "%s", value ? value : "") >= sizeof k->value)
        r->truncated = 1;
    return k;
}

void rd_row_attr(struct rd_row *r, const char *name, const char *value) { add_key(r, name, value); }

void rd_row_key(struct rd_row *r, const char *name, const char *prefix, const char *value)
{
    struct rd_key *k = add_key(r, name, value);
    if (!k)
        return;
    k->in_label = 1;
    size_t n = strlen(r->label);
    if ((size_t)snprintf(r->label + n, sizeof r->label - n, "%s%s%s", n ? " | " : "", prefix ? prefix : "",
                         k->value) >= sizeof r->label - n)
        r->truncated = 1;
}

void rd_row_fail(struct rd_row *r, const char *status, const char *reason)
{
    r->ok = 0;
    snprintf(r->status, sizeof r->status, "%s", status && *status ? status : "failed");
    snprintf(r->reason, sizeof r->reason, "%s", reason && *reason ? reason : "failed");
}

struct rd_metric *rd_row_metric(struct rdoc *d, struct rd_row *r, const char *name, const char *unit, int direction,
                                int timed, double v)
{
    struct rd_metric *metrics = room_for_one(r->metrics, r->nmetrics, &r->cap, sizeof *metrics, 4);
    if (!metrics)
        return out_of_memory(d);
    r->metrics = metrics;
    struct rd_metric *m = &r->metrics[r->nmetrics++];
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "%s", name);
    snprintf(m->unit, sizeof m->unit, "%s", unit ? unit : "1");
    m->direction = direction;
    m->timed = timed;
    m->value = v;
    m->lo = m->hi = NAN;
    return m;
}

static double *copy_of(struct rdoc *d, const double *v, int n)
{
    double *c = n > 0 ? malloc((size_t)n * sizeof *c) : NULL;
    if (n > 0 && !c)
        return out_of_memory(d);
    if (c)
        memcpy(c, v, (size_t)n * sizeof *c);
    return c;
}

int rd_metric_reps(struct rdoc *d, struct rd_metric *m, const double *v, int n)
{
    free(m->reps);
    m->reps = copy_of(d, v, n);
    m->nreps = m->reps ? n : 0;
    return n > 0 && !m->reps ? -1 : 0;
}

int rd_metric_normalised(struct rdoc *d, struct rd_metric *m, const double *v, int n, int per_cpu_second)
{
    free(m->norm);
    m->norm = copy_of(d, v, n);
    m->nnorm = m->norm ? n : 0;
    m->norm_cpu = m->norm && per_cpu_second;
    return n > 0 && !m->norm ? -1 : 0;
}

/* The text named name in (*t, *n), replaced or added. */
static int put_text(struct rdoc *d, struct rd_text **t, int *n, int *cap, const char *name, const char *value)
{
    char *copy = strdup(value ? value : "");
    if (!copy) {
        d->oom = 1;
        return -1;
    }
    for (int i = 0; i < *n; ++i)
        if (strcmp((*t)[i].name, name) == 0) {
            free((*t)[i].value);
            (*t)[i].value = copy;
            return 0;
        }
    struct rd_text *grown = room_for_one(*t, *n, cap, sizeof **t, 4);
    if (!grown) {
        free(copy);
        d->oom = 1;
        return -1;
    }
    *t = grown;
    struct rd_text *x = &(*t)[(*n)++];
    snprintf(x->name, sizeof x->name, "%s", name);
    x->value = copy;
    return 0;
}

static const char *get_text(const struct rd_text *t, int n, const char *name)
{
    for (int i = 0; i < n; ++i)
        if (strcmp(t[i].name, name) == 0)
            return t[i].value;
    return NULL;
}

int rd_row_text(struct rdoc *d, struct rd_row *r, const char *name, const char *value)
{
    return put_text(d, &r->texts, &r->ntexts, &r->tcap, name, value);
}

int rdoc_text(struct rdoc *d, const char *name, const char *value)
{
    return put_text(d, &d->texts, &d->ntexts, &d->tcap, name, value);
}

/* vsnprintf into a malloc'd string (NULL out of memory). */
static char *vformat(const char *fmt, va_list ap)
{
    va_list again;
    va_copy(again, ap);
    int n = vsnprintf(NULL, 0, fmt, ap);
    char *s = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (s)
        vsnprintf(s, (size_t)n + 1, fmt, again);
    va_end(again);
    return s;
}

int rd_row_textf(struct rdoc *d, struct rd_row *r, const char *name, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *s = vformat(fmt, ap);
    va_end(ap);
    int rc = s ? rd_row_text(d, r, name, s) : (d->oom = 1, -1);
    free(s);
    return rc;
}

int rdoc_textf(struct rdoc *d, const char *name, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *s = vformat(fmt, ap);
    va_end(ap);
    int rc = s ? rdoc_text(d, name, s) : (d->oom = 1, -1);
    free(s);
    return rc;
}

const char *rd_row_text_get(const struct rd_row *r, const char *name) { return get_text(r->texts, r->ntexts, name); }
const char *rdoc_text_get(const struct rdoc *d, const char *name) { return get_text(d->texts, d->ntexts, name); }

const char *rd_row_text_or(const struct rd_row *r, const char *name, const char *fallback)
{
    const char *t = rd_row_text_get(r, name);
    return t ? t : fallback;
}

const char *rdoc_text_or(const struct rdoc *d, const char *name, const char *fallback)
{
    const char *t = rdoc_text_get(d, name);
    return t ? t : fallback;
}

double rd_row_value(const struct rd_row *r, const char *name)
{
    const struct rd_metric *m = rd_row_find(r, name);
    return m ? m->value : NAN;
}

const struct rd_row *rdoc_find_row(const struct rdoc *d, const char *key, const char *value)
{
    for (int i = 0; i < d->nrows; ++i) {
        const char *v = rd_row_key_value(&d->rows[i], key);
        if (v && strcmp(v, value) == 0)
            return &d->rows[i];
    }
    return NULL;
}

struct rd_metric *rd_row_find(const struct rd_row *r, const char *name)
{
    for (int m = 0; m < r->nmetrics; ++m)
        if (strcmp(r->metrics[m].name, name) == 0)
            return &r->metrics[m];
    return NULL;
}

const char *rd_row_key_value(const struct rd_row *r, const char *name)
{
    for (int k = 0; k < r->nkeys; ++k)
        if (strcmp(r->keys[k].name, name) == 0)
            return r->keys[k].value;
    return NULL;
}

int rdoc_distinct_devices(const struct rdoc *d)
{
    const char *first = NULL;
    for (int i = 0; i < d->nrows; ++i) {
        const char *dv = d->rows[i].device;
        if (!*dv)
            continue;
        if (!first)
            first = dv;
        else if (strcmp(first, dv) != 0)
            return 2;
    }
    return first ? 1 : 0;
}

/* ---- writers ----------------------------------------------------------------------------- */

static void json_context(struct jw *w, const char *key, const struct rd_context *c)
{
    jw_kv_obj(w, key);
    for (int i = 0; i < c->count; ++i)
        jw_kv_str(w, c->key[i], c->value[i]);
    jw_obj_end(w);
}

/* A "texts" object, written only when there are texts (files without any stay as they were). */
static void json_texts(struct jw *w, const struct rd_text *t, int n)
{
    if (n <= 0)
        return;
    jw_kv_obj(w, "texts");
    for (int i = 0; i < n; ++i)
        jw_kv_str(w, t[i].name, t[i].value);
    jw_obj_end(w);
}

static void json_metric(struct jw *w, const struct rd_metric *m)
{
    jw_obj_begin(w);
    jw_kv_str(w, "name", m->name);
    jw_kv_str(w, "unit", m->unit);
    jw_kv_str(w, "direction", rd_direction_name(m->direction));
    jw_kv_bool(w, "timed", m->timed);
    jw_kv_num(w, "value", m->value);
    if (isfinite(m->lo) || isfinite(m->hi)) {
        jw_kv_num(w, "min", m->lo);
        jw_kv_num(w, "max", m->hi);
    }
    if (m->reps)
        jw_kv_nums(w, "reps", m->reps, (size_t)m->nreps);
    if (m->norm) {
        jw_kv_nums(w, "normalised_reps", m->norm, (size_t)m->nnorm);
        jw_kv_bool(w, "normalised_per_cpu_second", m->norm_cpu);
    }
    jw_obj_end(w);
}

/* The context, the devices and the rows: what a brdfbench.rows/1 document and a result file's
   "rows" member hold alike. */
static void json_rows_body(struct jw *w, const struct rdoc *d)
{
    json_context(w, "context", &d->ctx);
    jw_kv_int(w, "disturbed_reps", d->disturbed);
    jw_kv_arr(w, "devices");
    for (int i = 0; i < d->ndevices; ++i) {
        jw_obj_begin(w);
        jw_kv_str(w, "name", d->devices[i].name);
        json_context(w, "context", &d->devices[i].ctx);
        jw_obj_end(w);
    }
    jw_arr_end(w);
    json_texts(w, d->texts, d->ntexts);
    jw_kv_arr(w, "rows");
    for (int i = 0; i < d->nrows; ++i) {
        const struct rd_row *r = &d->rows[i];
        jw_obj_begin(w);
        jw_kv_str(w, "device", r->device);
        jw_kv_str(w, "model", r->model);
        for (int in_label = 1; in_label >= 0; --in_label) {
            jw_kv_obj(w, in_label ? "keys" : "attributes");
            for (int k = 0; k < r->nkeys; ++k)
                if (r->keys[k].in_label == in_label)
                    jw_kv_str(w, r->keys[k].name, r->keys[k].value);
            jw_obj_end(w);
        }
        jw_kv_str(w, "row", r->label);   /* not "label": that member is one key of a file, never " | " */
        jw_kv_str(w, "status", r->status);
        if (!r->ok)
            jw_kv_str(w, "reason", r->reason);
        jw_kv_int(w, "preemption_retries", r->retries);
        jw_kv_int(w, "disturbed_reps", r->disturbed);
        jw_kv_arr(w, "metrics");
        for (int m = 0; m < r->nmetrics; ++m)
            json_metric(w, &r->metrics[m]);
        jw_arr_end(w);
        json_texts(w, r->texts, r->ntexts);
        jw_obj_end(w);
    }
    jw_arr_end(w);
}

void rdoc_json(const struct rdoc *d, struct md_buf *out)
{
    struct jw w;
    jw_init(&w);
    jw_obj_begin(&w);
    jw_kv_str(&w, "schema", ROWS_SCHEMA);
    jw_kv_obj(&w, "source");
    jw_kv_str(&w, "schema", d->schema);
    jw_kv_str(&w, "kind", d->kind);
    jw_kv_str(&w, "file", d->file);
    jw_obj_end(&w);
    json_rows_body(&w, d);
    jw_obj_end(&w);
    md_append(out, w.out.s ? w.out.s : "", w.out.len);
    md_append(out, "\n", 1);
    if (w.out.failed)
        out->failed = 1;
    jw_free(&w);
}

void rdoc_json_rows_member(struct jw *w, const struct rdoc *d)
{
    jw_kv_obj(w, "rows");
    json_rows_body(w, d);
    jw_obj_end(w);
}

/* The names of the keys the rows carry, in the order they first appear. */
static int key_names(const struct rdoc *d, const char *names[], int max)
{
    int n = 0;
    for (int i = 0; i < d->nrows; ++i)
        for (int k = 0; k < d->rows[i].nkeys; ++k) {
            int j = 0;
            while (j < n && strcmp(names[j], d->rows[i].keys[k].name) != 0)
                ++j;
            if (j == n && n < max)
                names[n++] = d->rows[i].keys[k].name;
        }
    return n;
}

static void csv_num(struct md_buf *b, double v)
{
    if (isfinite(v))
        md_printf(b, ",%.17g", v);
    else
        md_append(b, ",", 1);
}

void rdoc_csv(const struct rdoc *d, struct md_buf *out)
{
    const char *names[RD_MAX_KEYS * 4];
    int nk = key_names(d, names, (int)(sizeof names / sizeof names[0]));
    md_printf(out, "device");
    for (int k = 0; k < nk; ++k) {
        md_append(out, ",", 1);
        md_csv_text(out, names[k]);
    }
    md_printf(out, ",status,reason,metric,unit,direction,value,min,max,reps\r\n");
    for (int i = 0; i < d->nrows; ++i) {
        const struct rd_row *r = &d->rows[i];
        for (int m = 0; m < r->nmetrics; ++m) {
            const struct rd_metric *mt = &r->metrics[m];
            md_csv_text(out, r->device);
            for (int k = 0; k < nk; ++k) {
                md_append(out, ",", 1);
                md_csv_text(out, rd_row_key_value(r, names[k]));
            }
            md_printf(out, ",");
            md_csv_text(out, r->status);
            md_append(out, ",", 1);
            md_csv_text(out, r->ok ? "" : r->reason);
            md_append(out, ",", 1);
            md_csv_text(out, mt->name);
            md_append(out, ",", 1);
            md_csv_text(out, mt->unit);
            md_printf(out, ",%s", rd_direction_name(mt->direction));
            csv_num(out, mt->value);
            csv_num(out, mt->lo);
            csv_num(out, mt->hi);
            md_printf(out, ",%d\r\n", mt->nreps);
        }
    }
}

void rdoc_markdown(const struct rdoc *d, struct md_buf *out)
{
    int several = rdoc_distinct_devices(d) > 1;
    md_printf(out, "### %s (%s, %s)\n\n", d->kind, d->file, d->schema);
    for (int i = 0; i < d->ctx.count; ++i) {
        md_printf(out, "- %s: ", d->ctx.key[i]);
        md_cell_text(out, d->ctx.value[i]);
        md_printf(out, "\n");
    }
    md_printf(out, "\n|%s row | metric | value | unit | better | range | reps |\n", several ? " device |" : "");
    md_printf(out, "|%s---|---|---:|---|---|---|---:|\n", several ? "---|" : "");
    for (int i = 0; i < d->nrows; ++i) {
        const struct rd_row *r = &d->rows[i];
        for (int m = 0; m < r->nmetrics; ++m) {
            const struct rd_metric *mt = &r->metrics[m];
            md_printf(out, "|");
            if (several) {
                md_printf(out, " ");
                md_cell_text(out, r->device);
                md_printf(out, " |");
            }
            md_printf(out, " ");
            md_cell_text(out, r->label);
            md_printf(out, " | %s | ", mt->name);
            if (!r->ok) {
                md_printf(out, "not measured: ");
                md_cell_text(out, r->reason);
            } else if (isfinite(mt->value)) {
                md_printf(out, "%.4g", mt->value);
            } else {
                md_printf(out, "-");
            }
            md_printf(out, " | %s | %s | ", mt->unit, rd_direction_name(mt->direction));
            if (isfinite(mt->lo) && isfinite(mt->hi))
                md_printf(out, "%.4g..%.4g", mt->lo, mt->hi);
            md_printf(out, " | %d |\n", mt->nreps);
        }
    }
    md_printf(out, "\n");
}

/* ---- reading brdfbench.rows/1 back --------------------------------------------------------- */

static void read_ctx(const struct jr_value *o, struct rd_context *c)
{
    for (size_t i = 0; o && o->type == JR_OBJ && i < o->count; ++i)
        if (o->items[i].type == JR_STR)
            rd_ctx_put(c, o->keys[i], o->items[i].str);
}

/* A number of a metric: a timed rate in [0, RD_MAX_RATE], any other figure within
   +-RD_MAX_VALUE; null (not measured) or absent reads as NAN. */
static int figure_ok(const struct jr_doc *j, const struct jr_value *v, const char *key, int timed, char *err,
                     size_t errlen)
{
    if (!v || v->type == JR_NULL)
        return 0;
    if (v->type != JR_NUM)
        return jr_fail(j, v, err, errlen, "\"%s\" is not a number (accepted: a number, or null when not measured)", key);
    if (timed ? v->num >= 0 && v->num <= RD_MAX_RATE : fabs(v->num) <= RD_MAX_VALUE)
        return 0;
    return jr_fail(j, v, err, errlen, "\"%s\" is %.6g (accepted: %s, or null when not measured)", key, v->num,
                   timed ? "a rate in [0, 1e+18]" : "a number in [-1e+100, 1e+100]");
}

/* A text of the document that reaches the terminal or a table: one line, no control
   character (an escape sequence would drive the terminal). */
static int text_ok(const struct jr_doc *j, const struct jr_value *v, const char *key, char *err, size_t errlen)
{
    if (!v || v->type != JR_STR)
        return 0;
    for (const char *p = v->str; *p; ++p)
        if ((unsigned char)*p < 0x20 || *p == 0x7f)
            return jr_fail(j, v, err, errlen, "\"%.40s\" holds %s (accepted: one line of text without control "
                           "characters, as brdfbench writes it)", key,
                           *p == '\n' ? "a newline" : *p == 0x1b ? "an escape character" : "a control character");
    return 0;
}

/* A "texts" object: strings of any length, lines allowed but no other control character. */
static int read_texts(const struct jr_doc *j, const struct jr_value *o, struct rdoc *d, struct rd_row *r, char *err,
                      size_t errlen)
{
    if (!o)
        return 0;
    if (o->type != JR_OBJ)
        return jr_fail(j, o, err, errlen, "\"texts\" is not an object (accepted: an object of strings)");
    for (size_t k = 0; k < o->count; ++k) {
        const struct jr_value *v = &o->items[k];
        if (v->type != JR_STR)
            return jr_fail(j, v, err, errlen, "text \"%.40s\" must be a string", o->keys[k]);
        for (const char *p = v->str; *p; ++p)
            if (((unsigned char)*p < 0x20 && *p != '\n') || *p == 0x7f)
                return jr_fail(j, v, err, errlen, "text \"%.40s\" holds %s (accepted: text without control "
                               "characters other than newlines, as brdfbench writes it)", o->keys[k],
                               *p == 0x1b ? "an escape character" : "a control character");
        if (r ? rd_row_text(d, r, o->keys[k], v->str) : rdoc_text(d, o->keys[k], v->str))
            return 0;
    }
    return 0;
}

/* The metric's numbers, and its unit as one line of table-safe text. */
static int metric_ok(const struct jr_doc *j, const struct jr_value *mo, int timed, int direction, char *err,
                     size_t errlen)
{
    static const char *const figures[] = { "value", "min", "max" };
    const char *name = jr_str_or(mo, "name", "");
    if (text_ok(j, jr_get(mo, "name"), "name", err, errlen))
        return 2;
    for (size_t k = 0; k < sizeof figures / sizeof figures[0]; ++k) {
        const struct jr_value *v = jr_get(mo, figures[k]);
        if (figure_ok(j, v, figures[k], timed, err, errlen))
            return 2;
        /* a figure where lower is better (an error, a count, a cost) is a magnitude, as the row
           declares it: -1 would read as "better" */
        if (v && v->type == JR_NUM && !timed && direction == RD_LOWER && !(v->num >= 0))
            return jr_fail(j, v, err, errlen, "\"%s\" of %.60s is %.6g (accepted: a figure where lower is better is "
                           "in [0, 1e+100], or null when not measured)", figures[k], name, v->num);
    }
    static const char *const arrays[] = { "reps", "normalised_reps" };
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; ++k) {
        const struct jr_value *a = jr_get(mo, arrays[k]);
        for (size_t i = 0; a && a->type == JR_ARR && i < a->count; ++i)
            if (figure_ok(j, &a->items[i], arrays[k], 1, err, errlen))
                return 2;
    }
    const char *unit = jr_str_or(mo, "unit", "");
    for (const char *p = unit; *p; ++p)
        if ((unsigned char)*p < 0x20 || *p == '|' || *p == 0x7f)
            return jr_fail(j, jr_get(mo, "unit"), err, errlen,
                           "\"unit\" holds '%s' (accepted: one line of text without '|')", *p == '|' ? "|" : "a control character");
    return 0;
}

static int read_metric(const struct jr_doc *j, const struct jr_value *mo, struct rdoc *d, struct rd_row *r, char *err,
                       size_t errlen)
{
    const char *name, *dir;
    if (jr_need_str(j, mo, "name", &name, err, errlen) || jr_need_str(j, mo, "direction", &dir, err, errlen))
        return 2;
    int direction = rd_direction_of(dir);
    if (direction < 0)
        return jr_fail(j, jr_get(mo, "direction"), err, errlen,
                       "\"direction\" is \"%.40s\" (accepted: higher, lower, neither)", dir);
    const struct jr_value *tv = jr_get(mo, "timed");
    const int timed = tv && tv->type == JR_BOOL && tv->num != 0;
    if (metric_ok(j, mo, timed, direction, err, errlen))
        return 2;
    struct rd_metric *m = rd_row_metric(d, r, name, jr_str_or(mo, "unit", "1"), direction, timed,
                                        jr_num_or_nan(mo, "value"));
    if (!m)
        return 0;
    m->lo = jr_num_or_nan(mo, "min");
    m->hi = jr_num_or_nan(mo, "max");
    size_t n = 0;
    if (jr_get(mo, "reps")) {
        if (jr_need_num_array(j, mo, "reps", &m->reps, &n, err, errlen))
            return 2;
        m->nreps = (int)n;
    }
    if (jr_get(mo, "normalised_reps")) {
        if (jr_need_num_array(j, mo, "normalised_reps", &m->norm, &n, err, errlen))
            return 2;
        m->nnorm = (int)n;
        const struct jr_value *cpu = jr_get(mo, "normalised_per_cpu_second");
        m->norm_cpu = cpu && cpu->type == JR_BOOL && cpu->num != 0;
    }
    return 0;
}

static int read_row(const struct jr_doc *j, const struct jr_value *ro, struct rdoc *d, char *err, size_t errlen)
{
    const struct jr_value *keys, *metrics;
    if (jr_need(j, ro, "keys", JR_OBJ, &keys, err, errlen) || jr_need(j, ro, "metrics", JR_ARR, &metrics, err, errlen))
        return 2;
    struct rd_row *r = rdoc_row(d, jr_str_or(ro, "device", ""), jr_str_or(ro, "model", ""));
    if (!r)
        return 0;
    const struct jr_value *attrs = jr_get(ro, "attributes");
    for (int in_label = 1; in_label >= 0; --in_label) {
        const struct jr_value *o = in_label ? keys : attrs;
        for (size_t k = 0; o && o->type == JR_OBJ && k < o->count; ++k) {
            if (o->items[k].type != JR_STR)
                return jr_fail(j, &o->items[k], err, errlen, "key \"%.40s\" must be a string", o->keys[k]);
            if (in_label)
                rd_row_key(r, o->keys[k], NULL, o->items[k].str);
            else
                rd_row_attr(r, o->keys[k], o->items[k].str);
        }
    }
    static const char *const texts[] = { "row", "status", "reason", "model", "device" };
    for (size_t t = 0; t < sizeof texts / sizeof texts[0]; ++t)
        if (text_ok(j, jr_get(ro, texts[t]), texts[t], err, errlen))
            return 2;
    for (int in_label = 1; in_label >= 0; --in_label) {
        const struct jr_value *o = in_label ? keys : attrs;
        for (size_t k = 0; o && o->type == JR_OBJ && k < o->count; ++k) {
            if (text_ok(j, &o->items[k], o->keys[k], err, errlen))
                return 2;
            /* the label joins the keys with " | ": a key holding '|' would make two rows one */
            if (in_label && strchr(o->items[k].str, '|'))
                return jr_fail(j, &o->items[k], err, errlen, "\"%.40s\" holds '|', which would break the table "
                               "(accepted: one line of text without '|', as brdfbench writes it)", o->keys[k]);
        }
    }
    /* the label as written (it may carry prefixes the keys do not) */
    snprintf(r->label, sizeof r->label, "%s", jr_str_or(ro, "row", r->label));
    const char *status = jr_str_or(ro, "status", "ok");
    if (strcmp(status, "ok") != 0)
        rd_row_fail(r, status, jr_str_or(ro, "reason", status));
    r->line = ro->line;
    r->retries = (int)fmax(0, jr_num_or_nan(ro, "preemption_retries"));
    r->disturbed = (int)fmax(0, jr_num_or_nan(ro, "disturbed_reps"));
    if (r->truncated || strlen(jr_str_or(ro, "row", "")) >= sizeof r->label)
        return jr_fail(j, ro, err, errlen, "a row whose keys do not fit (at most %d keys, a label and each key of at "
                       "most %d bytes): two distinct rows could read as one", RD_MAX_KEYS, RD_TEXT - 1);
    for (size_t m = 0; m < metrics->count; ++m)
        if (read_metric(j, &metrics->items[m], d, r, err, errlen))
            return 2;
    return read_texts(j, jr_get(ro, "texts"), d, r, err, errlen);
}

/* The context, devices and rows of obj (a rows document's root, or a result file's "rows"
   member) added to d. */
static int read_rows_body(const struct jr_doc *j, const struct jr_value *obj, struct rdoc *d, char *err, size_t errlen)
{
    const struct jr_value *rows;
    if (jr_need(j, obj, "rows", JR_ARR, &rows, err, errlen))
        return 2;
    read_ctx(jr_get(obj, "context"), &d->ctx);
    if (!d->disturbed)
        d->disturbed = (int)fmax(0, jr_num_or_nan(obj, "disturbed_reps"));
    const struct jr_value *devs = jr_get(obj, "devices");
    for (size_t i = 0; devs && devs->type == JR_ARR && i < devs->count; ++i) {
        struct rd_device *dv = rdoc_device(d, jr_str_or(&devs->items[i], "name", "?"));
        if (dv)
            read_ctx(jr_get(&devs->items[i], "context"), &dv->ctx);
    }
    if (read_texts(j, jr_get(obj, "texts"), d, NULL, err, errlen))
        return 2;
    for (size_t i = 0; i < rows->count; ++i)
        if (read_row(j, &rows->items[i], d, err, errlen))
            return 2;
    return 0;
}

int rdoc_from_rows_json(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    const struct jr_value *src;
    if (jr_need(j, &j->root, "source", JR_OBJ, &src, err, errlen))
        return 2;
    rdoc_init(d, jr_str_or(src, "schema", ""), jr_str_or(src, "kind", ""), jr_str_or(src, "file", ""));
    if (read_rows_body(j, &j->root, d, err, errlen)) {
        rdoc_free(d);
        return 2;
    }
    return 0;
}

int rdoc_from_rows_member(const struct jr_doc *j, const struct jr_value *member, struct rdoc *d, char *err,
                          size_t errlen)
{
    if (!member || member->type != JR_OBJ)
        return jr_fail(j, member ? member : &j->root, err, errlen, "\"rows\" is not an object (accepted: the "
                       "context, devices and rows of a brdfbench.rows/1 document)");
    return read_rows_body(j, member, d, err, errlen);
}

struct rdoc *rdoc_new(const char *schema, const char *kind, const char *file, char *err, size_t errlen)
{
    struct rdoc *d = malloc(sizeof *d);
    if (!d) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    rdoc_init(d, schema, kind, file);
    return d;
}

int rdoc_built(struct rdoc *d, char *err, size_t errlen)
{
    if (!d->oom)
        return 0;
    rdoc_delete(d);
    snprintf(err, errlen, "out of memory");
    return -1;
}

void rdoc_delete(struct rdoc *d)
{
    if (!d)
        return;
    rdoc_free(d);
    free(d);
}
