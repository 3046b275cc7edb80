/* rdoc.h - the result document: the figures of one result file as rows under one context.
 *
 * A row is one thing measured: its keys (the model with its parameters, the build-option
 * variant, the scene, ...; the device where the file holds several), its status (ok, or not
 * measured with the reason) and its metrics. A metric is a named value with its unit and its
 * direction (higher is better, lower is better, or neither), and, where it was timed, its
 * min..max range and its repetitions. Every reader of results works on these rows: compare
 * matches them across runs, `gate --baseline` takes a bound from them, `plot` draws the
 * throughput bars from them, and `brdfbench rows` writes them as JSON (brdfbench.rows/1),
 * CSV or markdown.
 *
 * The rows are the primary record: each engine builds them from what it measured (the keys,
 * each metric's unit, direction and repetitions declared there, where the figure is made) and
 * writes them into its result file as its "rows" member (rdoc_json_rows_member), beside the
 * kind's own detail. Every reader (rdoc_read.h) takes them from there, or from a
 * brdfbench.rows/1 document; only a file of a kind's previous version, written before the
 * files carried rows, is read by its layout (the upgrade functions of rdoc_read.c). */
#ifndef BRDF_RDOC_H
#define BRDF_RDOC_H

#include <stddef.h>

#include "mdbuf.h"

#define RD_TEXT 256
#define RD_NAME 64
#define RD_MAX_KEYS 8
#define RD_MAX_CTX 32
#define RD_MAX_DEVICES 16
#define RD_MAX_RATE 1e18     /* evaluations, pixels or FLOPs per second: above an exa per second is no measurement */
#define RD_MAX_VALUE 1e100   /* any other figure: beyond this no float model computed it */

enum rd_direction {
    RD_HIGHER = 0,   /* a speed, a PSNR */
    RD_LOWER,        /* an error, a cost */
    RD_NEITHER       /* a fitted coefficient */
};
const char *rd_direction_name(int d);    /* "higher", "lower", "neither" */
int rd_direction_of(const char *name);   /* the inverse; -1 for another word */

struct rd_metric {
    char name[RD_NAME];    /* "evals_per_s", "epicentre.max_rel", ... */
    char unit[24];         /* "1/s", "dB", "1" (a ratio or a plain number) */
    int direction;         /* enum rd_direction */
    int timed;             /* a rate measured by repeated launches: its verdict is the rank test's */
    double value;          /* a rate: the median; NAN when not measured */
    double lo, hi;         /* a rate's min and max; NAN when unknown */
    double *reps;          /* the repetitions (malloc'd), or NULL */
    int nreps;
    double *norm;          /* the repetitions normalised by the run's reference kernel (malloc'd), or NULL */
    int nnorm;
    int norm_cpu;          /* norm is per CPU second (a CPU device) */
};

/* A text of a row or of the document: what a page shows in words (a claim as the paper states
 * it, a verdict's sentence, why a model is where it is), of any length, on one line or several.
 * compare, gate and the exports ignore texts; report.md and the pages read them. */
struct rd_text {
    char name[RD_NAME];
    char *value;           /* malloc'd */
};

struct rd_key {
    char name[32];
    char value[RD_TEXT];
    int in_label;          /* part of the row's label (an attribute such as n_min is not) */
};

struct rd_row {
    char device[RD_TEXT];          /* the row's own device ("" when the file names none per row) */
    char label[RD_TEXT];           /* the keys as one line, e.g. "cq2 | default | n uniform" */
    char model[RD_TEXT];           /* the model (with parameters), for grouping */
    struct rd_key keys[RD_MAX_KEYS];
    int nkeys;
    int ok;                        /* measured */
    char status[32];               /* "ok", or the file's word for why not ("failed", "device_disagrees") */
    char reason[RD_TEXT];          /* why not, when !ok */
    int line;                      /* the line of the row in its file (0: unknown) */
    struct rd_metric *metrics;
    int nmetrics, cap;
    struct rd_text *texts;
    int ntexts, tcap;
    int retries, disturbed;        /* preemption retries and disturbed repetitions behind the row */
    int truncated;                 /* a key past RD_MAX_KEYS was dropped, or the label or a key was cut
                                      (two distinct rows could then read as one: the readers refuse it) */
};

struct rd_context {
    int count;
    char key[RD_MAX_CTX][48];
    char value[RD_MAX_CTX][RD_TEXT];
};

struct rd_device {
    char name[RD_TEXT];            /* the tag rows carry in their device key */
    struct rd_context ctx;
};

struct rdoc {
    char schema[RD_NAME];          /* the schema of the file the rows come from */
    char kind[32];                 /* "throughput", "accuracy", "render", "fit", "frontier" */
    char file[RD_NAME];            /* its usual file name, e.g. "throughput.json" */
    struct rd_context ctx;         /* the run's context, as text */
    struct rd_device devices[RD_MAX_DEVICES];   /* a --device all file's devices */
    int ndevices;
    int disturbed;                 /* repetitions the runner kept although preempted */
    struct rd_row *rows;
    int nrows, cap;
    struct rd_text *texts;         /* the document's texts (a verdict paragraph, a note under a table) */
    int ntexts, tcap;
    int oom;                       /* an allocation failed: the document is incomplete */
};

void rdoc_init(struct rdoc *d, const char *schema, const char *kind, const char *file);
void rdoc_free(struct rdoc *d);
/* A result file's writer's rows: rdoc_new allocates and initialises the document (NULL with
 * "out of memory" in err); rdoc_built checks it after the rows are added (0, or -1 with the
 * document deleted and "out of memory" in err); rdoc_delete frees it. */
struct rdoc *rdoc_new(const char *schema, const char *kind, const char *file, char *err, size_t errlen);
int rdoc_built(struct rdoc *d, char *err, size_t errlen);
void rdoc_delete(struct rdoc *d);

/* A context entry; the first value given for a key is kept. */
void rd_ctx_put(struct rd_context *c, const char *key, const char *value);
const char *rd_ctx_get(const struct rd_context *c, const char *key);
/* The device named name (added when new; NULL when RD_MAX_DEVICES are there). */
struct rd_device *rdoc_device(struct rdoc *d, const char *name);

/* A new row (NULL when out of memory, with d->oom set): ok with no keys and no metrics. */
struct rd_row *rdoc_row(struct rdoc *d, const char *device, const char *model);
/* A key of the row; the label is the keys' values joined by " | ", each after its prefix
 * ("n " for an n mode: "n uniform"). */
void rd_row_key(struct rd_row *r, const char *name, const char *prefix, const char *value);
/* A key that identifies the row for a reader looking it up (gate --baseline's n range) but is
 * not part of its label. */
void rd_row_attr(struct rd_row *r, const char *name, const char *value);
/* Marks the row not measured, with its status word ("failed" when NULL) and the reason. */
void rd_row_fail(struct rd_row *r, const char *status, const char *reason);
/* A metric of the row (NULL when out of memory, with d->oom set): value v, no range, no
 * repetitions. */
struct rd_metric *rd_row_metric(struct rdoc *d, struct rd_row *r, const char *name, const char *unit, int direction,
                                int timed, double v);
/* The metric's repetitions, in the order they ran (copied; none kept when n <= 0): each one's
 * rate for a timed metric. Returns 0, or -1 out of memory (d->oom set). */
int rd_metric_reps(struct rdoc *d, struct rd_metric *m, const double *v, int n);
/* The same repetitions normalised by the run's reference kernel in the same round (per CPU
 * second on a CPU device: per_cpu_second). */
int rd_metric_normalised(struct rdoc *d, struct rd_metric *m, const double *v, int n, int per_cpu_second);
/* A text of the row (rd_row_text) or of the document (rdoc_text), copied; a text given again
 * under the same name replaces the first. Returns 0, or -1 out of memory (d->oom set). */
int rd_row_text(struct rdoc *d, struct rd_row *r, const char *name, const char *value);
int rdoc_text(struct rdoc *d, const char *name, const char *value);
/* A formatted text of the row or the document (printf's format). */
int rd_row_textf(struct rdoc *d, struct rd_row *r, const char *name, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
int rdoc_textf(struct rdoc *d, const char *name, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* The text named name of the row or of the document, or NULL (the _or forms: fallback instead). */
const char *rd_row_text_get(const struct rd_row *r, const char *name);
const char *rdoc_text_get(const struct rdoc *d, const char *name);
const char *rd_row_text_or(const struct rd_row *r, const char *name, const char *fallback);
const char *rdoc_text_or(const struct rdoc *d, const char *name, const char *fallback);
/* The value of the row's metric named name, or NAN when the row has none. */
double rd_row_value(const struct rd_row *r, const char *name);
/* The first row whose key (or attribute) key has the value value, or NULL. */
const struct rd_row *rdoc_find_row(const struct rdoc *d, const char *key, const char *value);

/* The metric named name of the row, or NULL. */
struct rd_metric *rd_row_find(const struct rd_row *r, const char *name);
/* The key named name of the row, or NULL. */
const char *rd_row_key_value(const struct rd_row *r, const char *name);
/* How many distinct devices the rows name (0: none does). */
int rdoc_distinct_devices(const struct rdoc *d);

/* The writers. Each writes every row and metric: JSON as brdfbench.rows/1 (the context, the
 * devices and the rows, each metric with its unit, direction, range and repetitions), CSV with
 * one line per metric of a row (device, the keys, status, reason, metric, unit, direction,
 * value, min, max, reps), markdown as one table per document. */
void rdoc_json(const struct rdoc *d, struct md_buf *out);
void rdoc_csv(const struct rdoc *d, struct md_buf *out);
void rdoc_markdown(const struct rdoc *d, struct md_buf *out);

struct jw;
/* A result file's "rows" member: {"context", "disturbed_reps", "devices", "rows"} as in a
 * brdfbench.rows/1 document (the source is the file itself; its context block keeps the
 * run's device and build, this context only the kind's own lines). */
void rdoc_json_rows_member(struct jw *w, const struct rdoc *d);

struct jr_doc;
struct jr_value;
/* Reads a parsed brdfbench.rows/1 document back. Returns 0, or 2 with "FILE:LINE:COL: ...". */
int rdoc_from_rows_json(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen);
/* Adds a result file's "rows" member (its context lines, devices and rows) to d, which the
 * caller has initialised (rdoc_init) with the file's schema and kind. Returns 0, or 2 with
 * "FILE:LINE:COL: ..." (the caller frees d). */
int rdoc_from_rows_member(const struct jr_doc *j, const struct jr_value *member, struct rdoc *d, char *err,
                          size_t errlen);

#endif
