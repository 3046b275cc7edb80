/* compare.c - reads the runs that `brdfbench compare` is given, matches their rows by key and
 * decides each cell's verdict against the baseline (see compare.h); compare_report.c writes. */
#define _POSIX_C_SOURCE 200809L
#include "compare.h"
#include "outdir.h"
#include "ranktest.h"
#include "rdoc_read.h"
#include "room.h"
#include "schemas.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

const char *cmp_kind_name(int k) { return rd_kind_name(k); }

const char *cmp_verdict_name(int v)
{
    switch (v) {
    case CMP_V_NONE: return "";
    case CMP_V_MISSING: return "missing";
    case CMP_V_FAILED: return "failed";
    case CMP_V_SAME: return "same";
    case CMP_V_FASTER: return "faster";
    case CMP_V_SLOWER: return "slower";
    case CMP_V_UNDECIDED: return "undecided";
    case CMP_V_UNCHANGED: return "unchanged";
    case CMP_V_BETTER: return "changed, better";
    case CMP_V_WORSE: return "changed, worse";
    case CMP_V_CHANGED: return "changed";
    case CMP_V_NOISY: return "noisy";
    }
    return "?";
}

static void fail(char *err, size_t errlen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void fail(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}

/* ---- rows ------------------------------------------------------------------------------ */

/* Where a file's figures go while it is read. */
struct cmp_reader {
    struct compare_set *set;
    int run;
    int kind;
    int oom;
    char dup[CMP_TEXT + 80];   /* the first key given twice in the file, or "" */
};

/* The hash of a row's identity. */
static unsigned row_hash(int kind, const char *device, const char *key, const char *metric)
{
    unsigned h = 2166136261u ^ (unsigned)kind;
    const char *parts[3] = { device, key, metric };
    for (int p = 0; p < 3; ++p) {
        for (const unsigned char *s = (const unsigned char *)parts[p]; *s; ++s)
            h = (h ^ *s) * 16777619u;
        h = (h ^ 0xffu) * 16777619u;   /* a separator: ("ab", "c") is not ("a", "bc") */
    }
    return h;
}

/* Puts row i into the index (which has room). */
static void index_put(struct compare_set *set, int i)
{
    const struct cmp_row *r = &set->rows[i];
    unsigned mask = (unsigned)set->index_cap - 1;
    unsigned at = row_hash(r->kind, r->device, r->key, r->metric) & mask;
    while (set->index[at])
        at = (at + 1) & mask;
    set->index[at] = i + 1;
}

/* The index of every row, at most half full; 0, or -1 when out of memory. */
static int index_rebuild(struct compare_set *set, int want)
{
    int cap = 64;
    while (cap < 2 * want)
        cap *= 2;
    int *t = calloc((size_t)cap, sizeof *t);
    if (!t)
        return -1;
    free(set->index);
    set->index = t;
    set->index_cap = cap;
    for (int i = 0; i < set->nrows; ++i)
        index_put(set, i);
    set->index_n = set->nrows;
    return 0;
}

/* A row's cell for the run being read, the row made when new. Rows are found through a hash
   index: a linear search per figure made compare quadratic in rows (20,000 rows took more than
   a minute). */
static struct cmp_cell *cell_for(struct cmp_reader *rd, const char *device, const char *key, const char *model,
                                 const char *metric, int sense)
{
    struct compare_set *set = rd->set;
    if ((set->index_n != set->nrows || 2 * (set->nrows + 1) > set->index_cap) &&
        index_rebuild(set, set->nrows + 1) != 0) {
        rd->oom = 1;
        return NULL;
    }
    unsigned mask = (unsigned)set->index_cap - 1;
    for (unsigned at = row_hash(rd->kind, device, key, metric) & mask; set->index[at]; at = (at + 1) & mask) {
        struct cmp_row *r = &set->rows[set->index[at] - 1];
        if (r->kind == rd->kind && strcmp(r->device, device) == 0 && strcmp(r->key, key) == 0 &&
            strcmp(r->metric, metric) == 0)
            return &r->cell[rd->run];
    }
    struct cmp_row *rows = room_for_one(set->rows, set->nrows, &set->cap, sizeof *rows, 64);
    if (!rows) {
        rd->oom = 1;
        return NULL;
    }
    set->rows = rows;
    struct cmp_row *r = &set->rows[set->nrows++];
    memset(r, 0, sizeof *r);
    r->kind = rd->kind;
    r->sense = sense;
    snprintf(r->device, sizeof r->device, "%s", device);
    snprintf(r->key, sizeof r->key, "%s", key);
    snprintf(r->model, sizeof r->model, "%s", model);
    snprintf(r->metric, sizeof r->metric, "%s", metric);
    index_put(set, set->nrows - 1);
    set->index_n = set->nrows;
    return &r->cell[rd->run];
}

static struct cmp_cell *put_value(struct cmp_reader *rd, const char *device, const char *key, const char *model,
                                  const char *metric, int sense, double v, const char *reason)
{
    struct cmp_cell *c = cell_for(rd, device, key, model, metric, sense);
    if (c && c->present && !rd->dup[0])
        snprintf(rd->dup, sizeof rd->dup, "%s%s%.200s (%s)", device, *device ? " | " : "", key, metric);
    if (!c || c->present)
        return NULL;
    c->present = 1;
    c->ok = isfinite(v) && !(reason && *reason);
    c->value = v;
    c->lo = c->hi = NAN;
    if (!c->ok)
        snprintf(c->reason, sizeof c->reason, "%s", reason && *reason ? reason : "not a finite number");
    return c;
}

static void ctx_put(struct cmp_run *run, const char *key, const char *value)
{
    for (int i = 0; i < run->nctx; ++i)
        if (strcmp(run->ctx_key[i], key) == 0)
            return;   /* the first file that names it wins */
    if (run->nctx == CMP_MAX_CTX || !value)
        return;
    snprintf(run->ctx_key[run->nctx], sizeof run->ctx_key[0], "%s", key);
    snprintf(run->ctx_value[run->nctx], sizeof run->ctx_value[0], "%s", value);
    run->nctx++;
}

static void ctx_put_all(struct cmp_run *run, const struct rd_context *c)
{
    for (int i = 0; i < c->count; ++i)
        ctx_put(run, c->key[i], c->value[i]);
}

/* What a metric means for a verdict: a timed rate is decided by its repetitions, any other
   figure at the 4th significant digit, in its direction. */
static int sense_of(const struct rd_metric *m)
{
    if (m->timed)
        return CMP_SPEED;
    return m->direction == RD_LOWER ? CMP_ERROR : m->direction == RD_HIGHER ? CMP_SCORE : CMP_VALUE;
}

/* A row's metrics as cells of run rd->run; the repetitions move from the document into the cells. */
static void put_row(struct cmp_reader *rd, struct rd_row *row, int tagged)
{
    for (int k = 0; k < row->nmetrics; ++k) {
        struct rd_metric *m = &row->metrics[k];
        struct cmp_cell *c = put_value(rd, tagged ? row->device : "", row->label, row->model, m->name, sense_of(m),
                                       m->value, row->ok ? NULL : row->reason);
        if (!c)
            continue;
        c->lo = m->lo;
        c->hi = m->hi;
        c->reps = m->reps;
        c->nreps = m->nreps;
        c->norm = m->norm;
        c->nnorm = m->nnorm;
        c->norm_cpu = m->norm_cpu;
        m->reps = m->norm = NULL;
        c->retries = row->retries;
        c->disturbed = row->disturbed;
    }
}

/* The rows and context of one result document into run `run` of set. */
static int add_doc(struct compare_set *set, int run, struct rdoc *doc, const char *path, char *err, size_t errlen)
{
    int kind = rd_kind_of_name(doc->kind);
    if (kind < 0) {
        fail(err, errlen, "%s: rows of kind \"%.40s\", compare reads %s, %s, %s, %s and %s", path, doc->kind,
             rd_kind_name(0), rd_kind_name(1), rd_kind_name(2), rd_kind_name(3), rd_kind_name(4));
        return 2;
    }
    if (strcmp(doc->schema, THROUGHPUT_SCHEMA_V1) == 0) {   /* rates alone: nothing to decide a verdict on */
        fail(err, errlen, "%s: schema \"%s\", compare reads \"%s\" (run the command again with this version)", path,
             doc->schema, THROUGHPUT_SCHEMA);
        return 2;
    }
    struct cmp_run *r = &set->run[run];
    ctx_put_all(r, &doc->ctx);
    for (int i = 0; i < doc->ndevices; ++i) {
        int j = 0;
        while (j < set->ndevices && strcmp(set->devices[j].name, doc->devices[i].name) != 0)
            ++j;
        if (j == set->ndevices) {
            if (set->ndevices == CMP_MAX_RUNS)
                continue;
            snprintf(set->devices[set->ndevices++].name, sizeof set->devices[0].name, "%s", doc->devices[i].name);
        }
        ctx_put_all(&set->devices[j], &doc->devices[i].ctx);
    }
    if (doc->disturbed > 0)
        r->disturbed = doc->disturbed;
    snprintf(r->files + strlen(r->files), sizeof r->files - strlen(r->files), "%s%s", r->files[0] ? ", " : "",
             doc->file);
    struct cmp_reader rd = { .set = set, .run = run, .kind = kind };
    int tagged = rdoc_distinct_devices(doc) > 1;
    for (int i = 0; i < doc->nrows; ++i)
        put_row(&rd, &doc->rows[i], tagged);
    if (rd.oom) {
        fail(err, errlen, "out of memory reading %s", path);
        return 2;
    }
    if (rd.dup[0]) {
        fail(err, errlen, "%s: the row %s appears twice (accepted: one row per key, as brdfbench writes it)", path,
             rd.dup);
        return 2;
    }
    return 0;
}

static int read_file(struct compare_set *set, int run, const char *path, char *err, size_t errlen)
{
    struct rdoc doc;
    if (rdoc_read_file(path, &doc, err, errlen))
        return 2;
    int rc = add_doc(set, run, &doc, path, err, errlen);
    rdoc_free(&doc);
    return rc;
}

static int read_run(struct compare_set *set, int run, const char *path, char *err, size_t errlen)
{
    struct cmp_run *r = &set->run[run];
    snprintf(r->path, sizeof r->path, "%s", path);
    /* the heading: the last path component (a file: its folder's name too) */
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", path);
    size_t n = strlen(buf);
    while (n > 1 && buf[n - 1] == '/')
        buf[--n] = '\0';
    struct stat st;
    if (stat(path, &st) != 0) {
        fail(err, errlen, "%s: %s", path, strerror(errno));
        return 2;
    }
    const char *base = strrchr(buf, '/');
    snprintf(r->name, sizeof r->name, "%s", base ? base + 1 : buf);
    if (!S_ISDIR(st.st_mode))
        return read_file(set, run, path, err, errlen);
    /* the folder's result files, each read once by the one reader of a run folder */
    struct rdoc *docs = calloc(RD_KIND_COUNT, sizeof *docs);
    int found = 0, rc = 0;
    if (!docs) {
        fail(err, errlen, "out of memory reading %s", path);
        return 2;
    }
    if (rdoc_read_folder(path, -1, docs, &found, err, errlen))
        rc = 2;
    for (int i = 0; i < found; ++i) {
        if (!rc) {
            char file[4200];
            if (path_join(file, sizeof file, path, docs[i].file) == 0)
                rc = add_doc(set, run, &docs[i], file, err, errlen);
        }
        rdoc_free(&docs[i]);
    }
    free(docs);
    if (rc)
        return rc;
    if (!found) {
        char files[512];
        rd_kind_files(files, sizeof files);
        fail(err, errlen, "%s: no result file (any of %s)", path, files);
        return 2;
    }
    return 0;
}

/* One run whose rows name several devices becomes one column per device. */
static void split_devices(struct compare_set *set)
{
    char devs[CMP_MAX_RUNS][CMP_TEXT];
    int ndev = 0;
    for (int i = 0; i < set->nrows; ++i) {
        const char *d = set->rows[i].device;
        if (!*d)
            continue;
        int k = 0;
        while (k < ndev && strcmp(devs[k], d) != 0)
            ++k;
        if (k == ndev && ndev < CMP_MAX_RUNS)
            snprintf(devs[ndev++], sizeof devs[0], "%s", d);
    }
    if (ndev < 2)
        return;
    set->by_device = 1;
    for (int k = ndev - 1; k >= 0; --k) {
        set->run[k] = set->run[0];
        snprintf(set->run[k].name, sizeof set->run[k].name, "%s", devs[k]);
    }
    set->nruns = ndev;
    /* each column's device context from the file's list of devices */
    for (int k = 0; k < ndev; ++k)
        for (int c = 0; c < set->run[k].nctx; ++c) {
            const char *v = NULL;
            for (int j = 0; j < set->ndevices && !v; ++j)
                if (strcmp(set->devices[j].name, devs[k]) == 0)
                    for (int m = 0; m < set->devices[j].nctx && !v; ++m)
                        if (strcmp(set->devices[j].ctx_key[m], set->run[k].ctx_key[c]) == 0)
                            v = set->devices[j].ctx_value[m];
            if (strcmp(set->run[k].ctx_key[c], "device") == 0)
                v = devs[k];
            if (v)
                snprintf(set->run[k].ctx_value[c], sizeof set->run[k].ctx_value[c], "%.250s", v);
        }
    /* rows of device k move to column k of the row with the same key and no device */
    int n = set->nrows;
    for (int i = 0; i < n; ++i) {
        struct cmp_row *r = &set->rows[i];
        if (!*r->device)
            continue;
        int k = 0;
        while (k < ndev && strcmp(devs[k], r->device) != 0)
            ++k;
        if (k == ndev)
            continue;
        struct cmp_reader rd = { .set = set, .run = k, .kind = r->kind };
        struct cmp_cell moved = r->cell[0];
        memset(&r->cell[0], 0, sizeof r->cell[0]);
        char key[CMP_TEXT], model[CMP_TEXT], metric[64];
        int sense = r->sense;
        snprintf(key, sizeof key, "%s", r->key);
        snprintf(model, sizeof model, "%s", r->model);
        snprintf(metric, sizeof metric, "%s", r->metric);
        struct cmp_cell *c = cell_for(&rd, "", key, model, metric, sense);   /* may move set->rows */
        if (c) {
            *c = moved;
        } else {
            free(moved.reps);
            free(moved.norm);
        }
    }
    /* drop the emptied device rows */
    int w = 0;
    for (int i = 0; i < set->nrows; ++i)
        if (!*set->rows[i].device)
            set->rows[w++] = set->rows[i];
    set->nrows = w;
}

int compare_load(struct compare_set *set, const char *const *paths, int npaths, char *err, size_t errlen)
{
    memset(set, 0, sizeof *set);
    set->alpha = CMP_DEFAULT_ALPHA;
    set->threshold = CMP_DEFAULT_THRESHOLD;
    set->min_reps = CMP_WARN_REPS;
    if (npaths < 1 || npaths > CMP_MAX_RUNS) {
        fail(err, errlen, "expected 1 to %d runs (the first is the baseline), got %d", CMP_MAX_RUNS, npaths);
        return 2;
    }
    set->nruns = npaths;
    for (int i = 0; i < npaths; ++i) {
        int rc = read_run(set, i, paths[i], err, errlen);
        if (rc)
            return rc;
    }
    if (npaths == 1) {
        split_devices(set);
        if (!set->by_device) {
            fail(err, errlen, "%s: one run holds one device; give a second run to compare with (or a run of "
                              "--device all)", paths[0]);
            return 2;
        }
    }
    /* something in common: a row of the baseline in at least one other run */
    int common = 0;
    for (int i = 0; i < set->nrows && !common; ++i)
        for (int k = 1; k < set->nruns; ++k)
            common |= set->rows[i].cell[0].present && set->rows[i].cell[k].present;
    if (!common) {
        fail(err, errlen, "%s and %s have no row in common (files: %s / %s)", set->run[0].name,
             set->nruns > 1 ? set->run[1].name : "?", set->run[0].files, set->nruns > 1 ? set->run[1].files : "");
        return 2;
    }
    return 0;
}

const char *compare_context(const struct compare_set *set, int r, const char *key)
{
    for (int i = 0; i < set->run[r].nctx; ++i)
        if (strcmp(set->run[r].ctx_key[i], key) == 0)
            return set->run[r].ctx_value[i];
    return NULL;
}

