/* field_report.h - writing, reading back and drawing the heatmap error fields of field.h. */
#ifndef BRDF_FIELD_REPORT_H
#define BRDF_FIELD_REPORT_H

#include "field.h"

/* field JSON: schema, context (s: the session that computed it, may be NULL), model,
 * reference, grid, both fields (9 significant digits: every float exactly; null for NaN), peaks, check. Returns 0 or -1 with a message. */
int field_write_json(const char *path, const struct field_result *r, const struct cl_session *s, char *err,
                     size_t errlen);
/* Reads a field JSON back. Returns 0, or 2 when missing or malformed (file:line: problem). */
int field_read_json(const char *path, struct field_result *r, char *err, size_t errlen);

/* "fq:Q=0.64" -> "fq_Q0.64": the model label as used in file names (field_<it>.json,
 * heatmap_<it>.png). */
void field_safe_label(const char *label, char *out, size_t len);

struct draw_panel_layout;
struct draw_heatmap_panel;
/* The heatmap picture of a field: both zones side by side, titled with the model, its
 * parameters and both maxima, each maximum ringed. layout: NULL, or two entries that
 * receive where each panel landed. Returns 0 or -1 with a message. */
int field_draw_heatmap(const char *path, const struct field_result *r, struct draw_panel_layout *layout, char *err,
                       size_t errlen);

/* The same with the colour scales [0, epi_vmax] of the delta panel and [0, att_vmax] of the Delta
 * panel (<= 0: the panel's own maximum), each colour bar saying when its scale is shared. */
int field_draw_heatmap_scaled(const char *path, const struct field_result *r, double epi_vmax, double att_vmax,
                              struct draw_panel_layout *layout, char *err, size_t errlen);

/* The two panels (p[0], p[1]) of r's heatmap (delta, Delta) with those scales; their texts live in t. */
struct field_panel_text {
    char sub[2][160], x_label[2][160], bar[2][160];
};
void field_heatmap_panels(const struct field_result *r, double epi_vmax, double att_vmax,
                          struct draw_heatmap_panel *p, struct field_panel_text *t);

#endif
