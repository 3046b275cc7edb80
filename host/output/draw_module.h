/* draw_module.h - the boundary between brdfbench and its drawing module, libbrdfbench-draw.so
 * (draw*.cpp and OpenCV): the main binary does not link OpenCV, so that a command that draws
 * nothing does not load its ~140 shared libraries at start-up. The first draw_* call opens the
 * module (draw_load.c) and takes this table of its functions; every draw_* of the main binary
 * forwards to the table.
 *
 * The module exports one symbol, DRAW_MODULE_ENTRY, a function that takes the host's functions
 * the pictures need (the atomic write and the input check of host/output, whose state, such as
 * the run folder that writes are confined to, lives in the main binary) and returns the table.
 * The table's abi must equal DRAW_MODULE_ABI: a module of another version is refused, not used.
 *
 * A new function of draw.h: one X(...) line below (the module's table is filled from the list)
 * and its forwarder in draw_load.c.
 */
#ifndef BRDF_DRAW_MODULE_H
#define BRDF_DRAW_MODULE_H

#include <stddef.h>
#include <sys/stat.h>

#include "draw.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Raised whenever the list or a signature of draw.h changes. */
#define DRAW_MODULE_ABI 1
#define DRAW_MODULE_FILE "libbrdfbench-draw.so"
#define DRAW_MODULE_ENTRY "brdfbench_draw_module"

/* draw.h's functions, by name without the draw_ prefix. */
#define DRAW_MODULE_FUNCTIONS(X)                                                               \
    X(png_rgb8) X(error_image) X(contact_sheet) X(signed_error_image) X(contact_grid)          \
    X(colormap_rgb) X(heatmap_figure) X(heatmap_grid) X(colour_index) X(line_plot)             \
    X(bar_chart) X(scatter_plot) X(scatter_plot_plain) X(verdict_rgb) X(verdict_chart)         \
    X(stamp_png) X(read_rgb8)

/* What the module calls back: write_file_atomic (outdir.h) and infile_open (infile.h). */
struct draw_host_api {
    int (*write_file_atomic)(const char *path, const void *data, size_t len, char *err, size_t errlen);
    int (*infile_open)(const char *path, int flags, struct stat *st, char *why, size_t whylen);
};

#define DRAW_MODULE_MEMBER(name) __typeof__(draw_##name) *name;
struct draw_module_api {
    int abi; /* DRAW_MODULE_ABI of the module's build */
    DRAW_MODULE_FUNCTIONS(DRAW_MODULE_MEMBER)
};
#undef DRAW_MODULE_MEMBER

typedef const struct draw_module_api *(*draw_module_entry_fn)(const struct draw_host_api *host);

#ifdef __cplusplus
}
#endif

#endif /* BRDF_DRAW_MODULE_H */
