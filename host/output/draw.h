/* draw.h - every picture brdfbench writes: error heatmaps, line plots, bar charts,
 * image-pass pictures (false-colour error images, contact sheets) and plain RGB PNGs.
 *
 * The implementation (draw.cpp and its siblings, built as the module libbrdfbench-draw.so,
 * draw_module.h) is the only place that uses OpenCV; this interface is plain C, and a new
 * function of it is also listed in draw_module.h and forwarded in draw_load.c. All text is ASCII (OpenCV's built-in Hershey fonts have no Greek), so
 * callers spell "delta"/"Delta" out.
 *
 * Every function that writes a file returns 0 on success and -1 with a one-line message
 * in err (naming the file) on failure. PNGs are encoded in memory and written
 * atomically (temp file in the same folder, fsync, rename): a failed write leaves any
 * previous file of that name intact.
 */
#ifndef BRDF_DRAW_H
#define BRDF_DRAW_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the drawing module ---------------------------------------------------------------- */

/* The pictures are drawn by the module libbrdfbench-draw.so (draw_module.h), opened on the first
 * call below. 0 when it is there (it is opened now), else -1 with the one line why not: a command
 * that draws many pictures asks first, so that a missing module stops it once, before any work,
 * instead of failing picture by picture. Any draw_* that fails for that reason gives that line. */
int draw_module_check(char *err, size_t errlen);

/* ---- image-pass pictures ------------------------------------------------------- */

/* RGB row-major (3 bytes per pixel, width*3 bytes per row), written as a PNG. */
int draw_png_rgb8(const char *path, int width, int height, const unsigned char *rgb,
                  char *err, size_t errlen);

/* False-colour picture of a per-pixel absolute error (row-major, width*height floats;
 * NaN = background, drawn bluish grey RGB 90,90,100) at 1:1 scale, with a title band above and a
 * labelled colour bar (inferno, 0 at the bottom, vmax at the top) on the right.
 * vmax <= 0 or non-finite: the largest finite value of abs_err is used. */
int draw_error_image(const char *path, int width, int height, const float *abs_err,
                     float vmax, const char *title, char *err, size_t errlen);

/* Three panels side by side at 1:1 scale: reference image, model image (both RGB
 * row-major) and the false-colour absolute error (as draw_error_image), each captioned,
 * with a title band and the error's colour bar. */
int draw_contact_sheet(const char *path, int width, int height,
                       const unsigned char *ref_rgb, const unsigned char *model_rgb,
                       const float *abs_err, float vmax, const char *title,
                       char *err, size_t errlen);

/* Signed per-pixel error (model minus reference; NaN = background) at 1:1 scale on the
 * diverging map: blue where the model is under the reference, red where over, white at zero, on
 * the symmetric scale [-vmax, vmax] with a labelled colour bar. vmax <= 0 or non-finite: the
 * largest finite |value|. */
int draw_signed_error_image(const char *path, int width, int height, const float *signed_err,
                            float vmax, const char *title, char *err, size_t errlen);

/* A contact sheet of a grid of small images (the sphere grid: a row per model, a column per
 * shininess), with each row's label left of the reference panel and each column's label above
 * every panel. Rows and columns split the picture evenly (row r holds the pixel rows y with
 * floor(y * rows / height) = r, column c likewise in x). Labels shrink to the band they label. */
struct draw_grid_labels {
    int rows, cols;
    const char *const *row_labels;   /* rows of them */
    const char *const *col_labels;   /* cols of them */
};
int draw_contact_grid(const char *path, int width, int height, const unsigned char *ref_rgb,
                      const unsigned char *model_rgb, const float *abs_err, float vmax, const char *title,
                      const struct draw_grid_labels *labels, char *err, size_t errlen);

/* ---- colour maps ---------------------------------------------------------------- */

/* DRAW_CMAP_DIVERGING: blue (RGB 33, 102, 172) at 0, white at 128, red (RGB 178, 24, 43) at 255,
 * linear between (the ends of ColorBrewer's RdBu), for signed values on a symmetric scale. */
enum draw_cmap { DRAW_CMAP_VIRIDIS = 0, DRAW_CMAP_INFERNO = 1, DRAW_CMAP_DIVERGING = 2 };

/* The colour map's entry 0..255 (0 = bottom, 255 = top) as R, G, B. */
void draw_colormap_rgb(int cmap, int index, unsigned char rgb[3]);

/* How numbers on a value axis or colour bar are labelled. */
enum draw_value_format {
    DRAW_FMT_PLAIN = 0,   /* 0.128 */
    DRAW_FMT_PERCENT = 1  /* values are fractions, labelled times 100 with '%': 1.3% */
};

/* ---- heatmaps ---------------------------------------------------------------------- */

/* One heatmap panel: a grid of values, column index along x (left to right), row index
 * along y (row 0 at the bottom). Column/row centres span [x_min, x_max] / [y_min, y_max]
 * evenly (in log space where *_log is set). */
struct draw_heatmap_panel {
    int cols, rows;
    const float *values;        /* rows*cols, row-major, row 0 first; NaN = no data (grey) */
    double x_min, x_max;
    int x_log;
    const char *x_label;
    double y_min, y_max;
    int y_log;
    const char *y_label;
    double vmin, vmax;          /* colour scale; vmax <= vmin: [0, largest finite value] */
    int cmap;                   /* enum draw_cmap */
    int value_format;           /* enum draw_value_format, for the colour bar */
    const char *bar_label;      /* colour bar caption, e.g. "relative error delta" */
    const char *subtitle;       /* panel heading */
    int mark_max;               /* ring around the cell holding the largest finite value */
};

/* Where a panel landed in the written PNG, in pixels (x right, y down); for captions
 * and for tests that decode the picture. */
struct draw_panel_layout {
    int image_w, image_h;                /* size of the whole written picture */
    int plot_x, plot_y, plot_w, plot_h;  /* the coloured grid */
    int bar_x, bar_y, bar_w, bar_h;      /* colour bar; bar_y is its top (vmax) row */
    int max_col, max_row;                /* cell of the largest finite value, -1 if none */
    int max_px, max_py;                  /* marker centre (centre of that cell), -1 if none marked */
    double max_value;                    /* NaN when the panel holds no finite value */
    double vmin_used, vmax_used;         /* the colour scale actually drawn */
};

/* A figure of npanels (1..4) heatmaps side by side under one title (a second title line
 * may follow a '\n'). layout may be NULL, else it receives npanels entries. */
int draw_heatmap_figure(const char *path, const char *title, int npanels,
                        const struct draw_heatmap_panel *panels,
                        struct draw_panel_layout *layout, char *err, size_t errlen);

/* Small multiples: npanels (1..400) heatmaps of 240 x 170 pixels each, ncols (1..8) to a row,
 * under one title; each panel as in draw_heatmap_figure (its own colour bar, caption and
 * subtitle). */
int draw_heatmap_grid(const char *path, const char *title, int npanels, int ncols,
                      const struct draw_heatmap_panel *panels, char *err, size_t errlen);

/* ---- line plots ---------------------------------------------------------------------- */

#define DRAW_COLOUR_BLACK (-1)   /* series colour: black (the reference, by convention) */
#define DRAW_COLOUR_UNKNOWN (-2)

/* A colour by name (the models' descriptors name theirs: kernels/brdf_model_list.h) as a
 * palette index: "blue", "orange", "green", "red", "purple", "brown", "pink", "grey", "olive",
 * "cyan" (Tableau 10's order), "black" = DRAW_COLOUR_BLACK; DRAW_COLOUR_UNKNOWN for anything else. */
int draw_colour_index(const char *name);

struct draw_series {
    const double *x, *y;
    int count;                  /* a non-finite point (or <= 0 on a log axis) breaks the line */
    const char *label;          /* legend entry; NULL = not in the legend */
    int colour;                 /* palette index 0..9, or DRAW_COLOUR_BLACK */
    int dashed;
    int markers;                /* small circles at the data points */
};

struct draw_line_plot {
    const char *title, *x_label, *y_label;
    int x_log, y_log;
    double x_min, x_max;        /* x_max <= x_min: from the data */
    double y_min, y_max;        /* y_max <= y_min: from the data (linear axes include 0) */
    int y_format;               /* enum draw_value_format */
    int nseries;
    const struct draw_series *series;
    int nvlines;                /* dotted vertical guides (e.g. a zone boundary) */
    const double *vlines;
    const char *const *vline_labels;  /* may be NULL */
    int width, height;          /* 0: 1000 x 620 */
};

int draw_line_plot(const char *path, const struct draw_line_plot *plot, char *err, size_t errlen);

/* ---- bar charts ------------------------------------------------------------------------ */

/* Horizontal bars, one per label, value written at the bar's end. err_lo/err_hi (may be
 * NULL) draw a whisker from err_lo[i] to err_hi[i] (e.g. min..max of repeats). A
 * non-finite value draws no bar and the text "n/a". */
struct draw_bar_chart {
    const char *title, *x_label;
    int nbars;
    const char *const *labels;
    const double *values;
    const double *err_lo, *err_hi;
    const char *const *value_text;  /* may be NULL: the value printed with %.3g */
    int highlight;                  /* index of a bar drawn in black (the reference), -1 none */
    int width;                      /* 0: 1000 */
    int x_log;                      /* value axis logarithmic: from the decade at or below the smallest
                                       positive value (or whisker end) to the decade at or above the
                                       largest, each decade's tick labelled; bars start at the left end */
};

int draw_bar_chart(const char *path, const struct draw_bar_chart *chart, char *err, size_t errlen);

/* ---- scatter plots ------------------------------------------------------------------------ */
/* Points on log-log axes, each labelled beside it; points with front[i] set are joined in
 * order of x and ringed. Marks: a filled square for a reference, a filled triangle for a
 * paper's model, a filled circle otherwise. A point whose x is not > 0 (an exact reference)
 * sits on the left edge of the plot at the axis floor, with its label. */
enum draw_mark { DRAW_MARK_OTHER = 0, DRAW_MARK_PAPER, DRAW_MARK_REFERENCE };
struct draw_scatter {
    const char *title, *x_label, *y_label;
    int x_format;                   /* enum draw_value_format */
    int count;
    const double *x, *y;
    const char *const *labels;
    const int *marks;               /* enum draw_mark */
    const int *front;
};
int draw_scatter_plot(const char *path, const struct draw_scatter *plot, char *err, size_t errlen);
/* The same without the legend of the marks, for points all of one kind. */
int draw_scatter_plot_plain(const char *path, const struct draw_scatter *plot, char *err, size_t errlen);

/* ---- verdict charts (brdfbench compare) --------------------------------------------------- */

/* Small multiples: one panel per kind of row (throughput rates, accuracy errors, ...), every row
 * of it, each run's value as a ratio to the baseline's (a bar per run on a log axis through 1),
 * and per row, for every run after the baseline, its verdict's mark in a column at the right:
 * better (faster, smaller error) a green triangle up, worse a red triangle down, same a grey
 * circle, lost (missing from the run, or failed) a black cross, undecided (noisy, too few
 * repetitions, changed with no better or worse) an amber diamond. Row labels and run names are
 * wrapped (at " | ", then at blanks) and shrunk to fit, never clipped. */
enum draw_verdict {
    DRAW_VERDICT_NONE = 0, DRAW_VERDICT_BETTER, DRAW_VERDICT_WORSE, DRAW_VERDICT_SAME, DRAW_VERDICT_LOST,
    DRAW_VERDICT_UNDECIDED
};
/* The marks' colours, RGB: better 0,140,60; worse 200,0,0; same 150,150,150; lost 0,0,0;
 * undecided 230,160,0 (drawn without anti-aliasing: exactly these). */
void draw_verdict_rgb(int verdict, unsigned char rgb[3]);
struct draw_verdict_panel {
    const char *title;
    int nrows;
    const char *const *labels;   /* nrows */
    const double *ratio;         /* nrows * nseries, [row * nseries + run]; NaN: none */
    const int *verdict;          /* nrows * nseries, enum draw_verdict (the baseline's: NONE) */
};
struct draw_verdict_chart {
    const char *title, *x_label;
    int nseries;                 /* runs, the baseline first */
    const char *const *series;
    int npanels;
    const struct draw_verdict_panel *panels;
    int width;                   /* 0: 1100 */
};
int draw_verdict_chart(const char *path, const struct draw_verdict_chart *c, char *err, size_t errlen);

/* ---- the quick-run stamp ------------------------------------------------------------------ */

/* Adds a band under the picture at path (rewritten atomically, as every picture): pale amber
 * (RGB 255, 240, 200) with text in dark red (RGB 160, 20, 20), centred, the font shrunk to the
 * picture's width; the picture above the band keeps every pixel. */
int draw_stamp_png(const char *path, const char *text, char *err, size_t errlen);

/* ---- reading back ------------------------------------------------------------------------ */

/* Decode a PNG (or any format OpenCV reads) into a malloc'd RGB row-major buffer. */
int draw_read_rgb8(const char *path, int *width, int *height, unsigned char **rgb,
                   char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* BRDF_DRAW_H */
