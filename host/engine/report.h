/* report.h - report.md, the page a person reads first in a run folder: how the run was
 * made, the claims table, the per-model accuracy table, the throughput table, and every
 * picture inline with a one-line caption. A picture is linked only when its file exists in
 * the run folder; a section whose results do not exist says so and why. */
#ifndef BRDF_REPORT_H
#define BRDF_REPORT_H

#include <stddef.h>

#include "accuracy.h"
#include "mdbuf.h"

enum report_section {
    REPORT_HEATMAPS = 0,
    REPORT_PLOTS,
    REPORT_THROUGHPUT,
    REPORT_IMAGES,
    REPORT_SECTION_COUNT
};

struct report_picture {
    char file[160];       /* name inside the run folder */
    char caption[400];    /* one line */
    int section;          /* enum report_section */
    char not_drawn[200];  /* why the picture was left out (nothing to draw); "" when drawn */
};

/* A block of markdown supplied by another part of the run (claims, throughput, image
 * passes), or the reason it is missing. */
struct report_block {
    const char *markdown;  /* NULL: not available */
    const char *missing;   /* why not, shown when markdown is NULL */
};

struct report_input {
    const char *run_dir;
    const char *shown_dir;        /* the folder's name in the text (NULL: run_dir); all writes a staged folder */
    const char *command;          /* the command line that made the run */
    const char *date;             /* ISO 8601 */
    const char *device, *platform_version, *host_cpu, *git_revision;
    double wall_seconds;          /* < 0: not known yet */
    const char *steps_md;         /* optional: the step log as a markdown list */
    /* accuracy */
    const struct accuracy_result *acc;
    int nacc;
    const struct accuracy_grid *acc_grid;
    struct report_block claims, fit, throughput, images;
    const struct report_picture *pictures;
    int npictures;
    const char *notes_md;         /* optional closing notes */
    struct report_block frontier; /* "Which lobe to ship" (frontier_markdown) */
    struct report_block measured; /* "Measured materials" (measured_markdown; all --measured DIR) */
};

/* Builds the markdown text (malloc'd, NUL-terminated) or NULL when out of memory. */
char *report_markdown(const struct report_input *in);
/* Writes run_dir/report.md atomically. Returns 0 or -1 with a message. */
int report_write(const struct report_input *in, char *err, size_t errlen);

/* Summarises run_dir/render.json (written by render_run) for the report: per scene a table of
 * the image metrics and timings into md, and each picture that exists through add(ctx, file,
 * caption) (contact sheets inline; the separate image and error PNGs linked from the table).
 * Returns 0, or 2 with a message naming the file when it is missing or malformed. */
int report_render_summary(const char *run_dir, struct md_buf *md,
                          void (*add)(void *ctx, const char *file, const char *caption), void *ctx, char *err,
                          size_t errlen);

#endif
