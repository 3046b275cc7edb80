/* plots.h - the line plots and bar charts of a run, as data: each figure (its series, axes,
 * labels, file name and report caption) is built from results, written to plots.json,
 * drawn to PNG, and can be read back from plots.json and redrawn without recomputing.
 *
 * Builders for the papers' figures:
 *   f against x at one n for several models and their reference (paper 1 fig. 2, paper 2 fig. 5)
 *   max delta / max Delta against n for several models (paper 1 figs. 3, 5; paper 2 fig. 6)
 *   max delta / max Delta of f_Q against Q (paper 2 figs. 2-3)
 *   bars (throughput per model). */
#ifndef BRDF_PLOTS_H
#define BRDF_PLOTS_H

#include "schemas.h"
#include <stdbool.h>
#include <stddef.h>

#include "accuracy.h"
#include "models.h"

#define PLOT_MAX_SERIES 24
#define PLOT_MAX_BARS 64
#define PLOT_MAX_VLINES 4

enum plot_kind { PLOT_LINES = 0, PLOT_BARS = 1 };

struct plot_series {
    char label[96];
    int colour;            /* palette index 0..9, or -1 (black: a reference) */
    int dashed, markers;
    size_t count;
    double *x, *y;         /* owned */
};

struct plot_figure {
    char file[128];        /* PNG name inside the run folder */
    char caption[256];     /* one line under the picture in the report */
    int kind;              /* enum plot_kind */
    char title[256], x_label[128], y_label[128];
    int x_log, y_log, y_format;          /* y_format: enum draw_value_format */
    double x_min, x_max, y_min, y_max;   /* max <= min: from the data */
    int nseries;
    struct plot_series series[PLOT_MAX_SERIES];
    int nvlines;
    double vlines[PLOT_MAX_VLINES];
    char vline_labels[PLOT_MAX_VLINES][48];
    /* PLOT_BARS: one bar per label; series[0].y holds the values, series[1].y / series[2].y
       (optional) the low and high ends of a whisker. */
    int nbars;
    char bar_labels[PLOT_MAX_BARS][64];
    int highlight;         /* bar drawn dark (the reference), -1 none */
};

struct plot_set {
    int count, cap;
    struct plot_figure *figs;
};

void plots_init(struct plot_set *set);
void plots_free(struct plot_set *set);
/* A new empty figure (NULL when out of memory). */
struct plot_figure *plots_add(struct plot_set *set, int kind, const char *file, const char *caption);
/* Copies count points into a new series of fig. Returns 0 or -1 (full or out of memory). */
int plot_series_add(struct plot_figure *fig, const char *label, int colour, int dashed, const double *x,
                    const double *y, size_t count);
/* A stable colour per model: its descriptor's (references are black). */
int plot_model_colour(const struct model_spec *m);
/* 1 when name is a colour of the palette ("black" included): every descriptor's must be. */
int plot_colour_known(const char *name);

/* f(x) for x in [0, min(pi/2, 4 x_e(n))] at shininess n: the reference of models[0] in black, then each
 * model; a dotted line at x_e(n). Evaluated in double on the host. */
int plots_add_curves(struct plot_set *set, const char *file, const char *caption, const char *title, double n,
                     const struct model_spec *models, int count);
/* Per-n maxima from accuracy results: relative = 1 plots the epicentre's max delta,
 * relative = 0 the max Delta over the whole range [0, pi/2]. Results of a model against
 * itself are skipped, and so are models whose registry family is not one of `families`
 * (nfamilies = 0: any). Long n grids are binned (the maximum of each bin) to at most 1000 points.
 * Returns 0, -1 (out of memory), or 1 when no model of the families ran: then no figure is
 * added (an empty plot is never drawn). */
int plots_add_max_vs_n(struct plot_set *set, const char *file, const char *caption, const char *title,
                       const struct accuracy_result *res, int count, int relative, const enum model_family *families,
                       int nfamilies);
/* max delta or max Delta against Q: q[count], fq[count]; baseline (e.g. f2's value, which
 * does not depend on Q) drawn as a dashed line; NAN for none. Returns 0, -1 (out of memory), or
 * 1 when no (q, fq) pair is finite: then no figure is added. */
int plots_add_against_q(struct plot_set *set, const char *file, const char *caption, const char *title,
                        const char *y_label, int y_format, const double *q, const double *fq, int count,
                        const char *fq_label, double baseline, const char *baseline_label, double mark_q);
/* Horizontal bars; lo/hi may be NULL. */
int plots_add_bars(struct plot_set *set, const char *file, const char *caption, const char *title,
                   const char *x_label, const char *const *labels, const double *values, const double *lo,
                   const double *hi, int count, int highlight);

/* Throughput bars from a throughput.json (schema brdfbench.throughput/2 or /1): the rows of the
 * default build options in one n mode ("uniform" or "varying"), median evaluations per
 * second with a min..max whisker, the pow() built-in drawn dark. Returns 0, 1 when the
 * file holds no such row, or 2 with a message naming the file when it is malformed. */
int plots_add_throughput(struct plot_set *set, const char *json_path, const char *n_mode, const char *file,
                         const char *caption, char *err, size_t errlen);

/* Draws every figure into dir. Keeps going after a failure; returns the number of
 * pictures that could not be written (0 = all written), the first message in err. */
int plots_draw(const struct plot_set *set, const char *dir, char *err, size_t errlen);
int plot_figure_draw(const struct plot_figure *fig, const char *path, char *err, size_t errlen);

/* plots.json (with the context block of session s, which may be NULL). write: 0 or -1;
 * read: 0, or 2 naming file, line and problem. */
struct cl_session;
int plots_write_json(const struct plot_set *set, const char *path, const struct cl_session *s, char *err,
                     size_t errlen);
int plots_read_json(const char *path, struct plot_set *set, char *err, size_t errlen);

/* ---- the quick-run stamp ------------------------------------------------------------------ */

#define PLOTS_QUICK_STAMP "coarse grid (--quick), not for figures"

/* true when the run folder's accuracy.json was measured on a grid as coarse as `all --quick`'s
 * in either dimension (an n step of 10 or more, or 256 samples per zone or fewer); false when
 * it has none or cannot be read. The answer for a folder is kept until its accuracy.json
 * changes. */
bool plots_run_is_quick(const char *run_dir);
/* Stamps PLOTS_QUICK_STAMP under the picture png (draw_stamp_png) when the run folder `up`
 * levels above png's own folder (0: that folder) is quick. 0, or -1 with a message. */
int plots_stamp_if_quick(const char *png, int up, char *err, size_t errlen);

/* 1 when name is a picture name plots.json may give: NAME.png, letters, digits and ._-+=,
 * not starting with '.', at most 200 characters (so never a data file of the run). */
int plot_file_name_ok(const char *name);

#endif
