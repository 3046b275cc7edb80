/* report.h - report.md, the page a person reads first in a run folder: how the run was
 * made, the claims table, the per-model accuracy table, the throughput table, and every
 * picture inline with a one-line caption. A picture is linked only when its file exists in
 * the run folder; a section whose results do not exist says so and why. The page is made from
 * the run folder's files alone (report_build): `all` writes run.json and then the page the same
 * way `brdfbench report RUN` rebuilds it. */
#ifndef BRDF_REPORT_H
#define BRDF_REPORT_H

#include <stddef.h>

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

/* The parts of a run that other commands make, each a section of report.md with the file it
 * comes from: claims (claims.json's rows, with q_sweep.json's and physical.json's, drawn as
 * reproduce draws claims.md: report_claims.h), fit (fit.json), throughput
 * (throughput.json's rows; its page throughput.md is drawn from them), images (render.json),
 * frontier (frontier.md), measured (measured.md). */
enum report_part {
    REPORT_PART_CLAIMS = 0,
    REPORT_PART_FIT,
    REPORT_PART_THROUGHPUT,
    REPORT_PART_IMAGES,
    REPORT_PART_FRONTIER,
    REPORT_PART_MEASURED,
    REPORT_PART_COUNT
};

/* The page of a part, written beside its JSON by `all` (claims.md by reproduce) from the JSON's rows, or
 * NULL for the parts whose section is drawn from their file's rows (fit, images). */
const char *report_part_page(int part);

struct report_part_state {
    int ran;               /* 0: the part was not run (frontier and measured then have no section) */
    char missing[200];     /* why its section is not available; "" when it is */
};

/* One line of the step list. */
struct report_step {
    char name[32];
    char message[1024];
    double seconds;
    int exit_code;         /* 0: done; else the part failed with this exit code */
};

/* What `all` records of its run in run.json: with the run folder's other files it is all
 * that report.md is made of. */
struct report_run {
    const char *command;          /* the command line that made the run */
    const char *folder;           /* the run folder's name in the text (all writes a staged folder) */
    double wall_seconds;
    const struct report_step *steps;
    int nsteps;
    struct report_part_state parts[REPORT_PART_COUNT];
    const char *images_note;      /* scenes left out, "" when none */
    const struct report_picture *pictures; /* those of the accuracy sweep, heatmaps and plots */
    int npictures;
};

/* Writes run_dir/run.json (schema RUN_SCHEMA) with the session's context. Returns 0, or -1
 * with a message. */
struct cl_session;
int report_run_write(const char *run_dir, const struct report_run *run, const struct cl_session *s, char *err,
                     size_t errlen);

/* report.md's text, made from the run folder alone: run.json, the rows of accuracy.json,
 * fit.json and render.json (report_docs.h), and the parts' pages. *text is malloc'd. Returns 0, or 2 with a message naming
 * the file that is missing or malformed, or 3 when out of memory. */
int report_build(const char *run_dir, char **text, char *err, size_t errlen);
/* Builds report.md and writes it atomically to out (NULL: run_dir/report.md; "-": standard
 * output). Returns 0, 2 (as report_build) or 3 when it cannot be written. */
int report_rebuild(const char *run_dir, const char *out, char *err, size_t errlen);
/* The same, with the rows of docs (report_docs.h: report_docs_init(docs, run_dir), then
 * report_docs_put for the rows the run holds in memory): a file put there is not read back, any
 * other is read from run_dir as report_build reads it. docs stays the caller's (it holds the
 * files read too; report_docs_free frees it). */
struct report_docs;
int report_build_docs(const char *run_dir, struct report_docs *docs, char **text, char *err, size_t errlen);
int report_rebuild_docs(const char *run_dir, struct report_docs *docs, const char *out, char *err, size_t errlen);

/* A file the run names (a picture) is in run_dir and not empty: a section links it only then. */
int report_file_exists(const char *dir, const char *name);

#endif
