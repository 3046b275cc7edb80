/* report_run.h - run.json read back (report_run.c), for report.c: internal to the report. */
#ifndef BRDF_REPORT_RUN_H
#define BRDF_REPORT_RUN_H

#include <stddef.h>

#include "jsonr.h"
#include "report.h"

/* run.json, checked: every string and array below points into doc. */
struct report_run_doc {
    struct jr_doc doc;
    const char *command, *folder, *images_note;
    const char *date, *git_revision, *host_cpu;
    const char *device, *platform_version; /* device NULL: the run had none */
    double wall_seconds;
    const struct jr_value *steps;    /* [{name, status, message | exit_code, seconds}] */
    const struct jr_value *pictures; /* [{file, section, caption, not_drawn?}] */
    int part_ran[REPORT_PART_COUNT];
    const char *part_missing[REPORT_PART_COUNT]; /* NULL: available */
};

/* Reads run_dir/run.json. Returns 0, or 2 with a message naming the file, line and member. */
int report_run_read(const char *run_dir, struct report_run_doc *r, char *err, size_t errlen);
void report_run_free(struct report_run_doc *r);
/* enum report_section of a section's name in run.json, or -1. */
int report_section_of(const char *name);

#endif
