/* heatmaps_shared.h - the run's heatmaps on one colour scale: heatmaps_shared_scale.png (every
 * model's delta and Delta fields side by side, small multiples labelled by model, on the largest
 * delta and the largest Delta over the models) and, with --shared-scale, each model's
 * heatmap_<model>.png redrawn on those scales. Drawn from the run folder's field_<model>.json. */
#ifndef BRDF_HEATMAPS_SHARED_H
#define BRDF_HEATMAPS_SHARED_H

#include <stddef.h>

#define HEATMAPS_SHARED_FILE "heatmaps_shared_scale.png"

/* The field_*.json names of dir in name order (malloc'd, each and the array; NULL with count 0
 * when the folder cannot be read or holds none). */
char **field_file_names(const char *dir, size_t *count);

/* Writes run_dir/heatmaps_shared_scale.png from every field_*.json of run_dir (none: nothing
 * written, 0); with shared, also redraws heatmap_<model>.png of each model (only_label: only that
 * model's; NULL: all) on the shared scales, counting them in *drawn (may be NULL). Returns 0, 2
 * (a field file malformed: err names it) or 3 (a picture not written: err names it). */
int plots_heatmaps_shared(const char *run_dir, int shared, const char *only_label, int *drawn, char *err,
                          size_t errlen);

/* The same for a command's run (every model), the message on stderr as "brdfbench CMD: ...". */
int plots_heatmaps_shared_step(const char *cmd, const char *run_dir, int shared);

#endif
