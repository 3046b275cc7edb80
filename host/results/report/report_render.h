/* report_render.h - report.md's image passes drawn from render.json's rows alone (rdoc.h):
 * what scene_rows builds where the images are measured (host/measure/render/render_report.c),
 * or the upgrade of a previous file (rdoc_read.c). */
#ifndef BRDF_REPORT_RENDER_H
#define BRDF_REPORT_RENDER_H

#include <stddef.h>

#include "mdbuf.h"
#include "rdoc.h"

/* Per scene a table of the models' image figures and timings into md, He's comparison where
 * the scene has one, and each picture through add(ctx, file, caption) (the scene's contact
 * sheet, each model's against its reference, He's; the separate image and error PNGs are linked
 * from the table when they exist in run_dir). */
void report_render_summary(const struct rdoc *render, const char *run_dir, struct md_buf *md,
                           void (*add)(void *ctx, const char *file, const char *caption), void *ctx);

#endif
