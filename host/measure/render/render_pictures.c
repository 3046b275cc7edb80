/* render_pictures.c - the image passes' pictures (render_pictures.h), through draw.h. */
#include "render_pictures.h"

#include "draw.h"
#include "exitcodes.h"
#include "outdir.h"
#include "plots.h"

#include <stdio.h>
#include <string.h>

/* A picture of the run in scene_dir (run/<stage>/<scene>): stamped when the run is quick. */
static int stamp(const char *path, char *err, size_t errlen)
{
    return plots_stamp_if_quick(path, 2, err, errlen) ? EXIT_RUNTIME : 0;
}

/* scene_dir/<prefix><base><suffix>.png, and its name relative to the run folder into rel. */
static void picture_path(const struct render_picture_set *p, const char *suffix, char *path, size_t len, char *rel)
{
    char name[400];
    snprintf(name, sizeof name, "%s%s%s.png", p->prefix, p->base, suffix);
    path_join(path, len, p->scene_dir, name);
    if (rel) snprintf(rel, 256, "render/%s/%s", p->scene, name);
}

void render_signed_title(char *out, size_t len, const char *scene, const char *model, const char *reference,
                         double max_abs)
{
    snprintf(out, len, "%s: %s - %s specular radiance\nblue: model under the reference, red: over, white: equal; "
             "scale +-%.3g radiance (absolute)", scene, model, reference, max_abs);
}

int render_write_pictures(const struct render_picture_set *p, char *err, size_t errlen)
{
    char path[4600];
    if (p->rgb) {
        picture_path(p, "", path, sizeof path, p->image);
        if (draw_png_rgb8(path, p->w, p->h, p->rgb, err, errlen) != 0) return EXIT_RUNTIME;
    }
    picture_path(p, "_error", path, sizeof path, p->error);
    if (draw_error_image(path, p->w, p->h, p->abs_err, (float)p->max_abs, p->error_title, err, errlen) != 0 ||
        stamp(path, err, errlen))
        return EXIT_RUNTIME;
    picture_path(p, "_signed_error", path, sizeof path, p->signed_error);
    if (draw_signed_error_image(path, p->w, p->h, p->signed_err, (float)p->max_abs, p->signed_title, err, errlen) != 0 ||
        stamp(path, err, errlen))
        return EXIT_RUNTIME;
    if (!p->ref_rgb) return 0;
    picture_path(p, "_contact", path, sizeof path, p->contact);
    if (draw_contact_sheet(path, p->w, p->h, p->ref_rgb, p->rgb, p->abs_err, (float)p->max_abs, p->contact_title,
                           err, errlen) != 0 ||
        stamp(path, err, errlen))
        return EXIT_RUNTIME;
    return 0;
}

int render_write_grid(const char *scene_dir, const struct render_options *o, int w, int h,
                      const unsigned char *grid_r, const unsigned char *grid_m, const float *grid_err, double vmax,
                      char *caption, size_t caption_len, char *err, size_t errlen)
{
    const char *rows[RENDER_MAX_MODELS], *cols[RENDER_MAX_COLS];
    char col_text[RENDER_MAX_COLS][32];
    for (int mi = 0; mi < o->nmodels; mi++) rows[mi] = o->models[mi].label;
    for (int c = 0; c < o->ncols; c++) {
        snprintf(col_text[c], sizeof col_text[c], "n = %g", o->sphere_n[c]);
        cols[c] = col_text[c];
    }
    struct draw_grid_labels labels = {o->nmodels, o->ncols, rows, cols};
    char path[4600], title[300];   /* render_report.h: grid_caption[300] */
    path_join(path, sizeof path, scene_dir, "contact.png");
    snprintf(title, sizeof title,
             "spheres: a row per model (named at the left), a column per shininess n; references | "
             "models | error relative to the row's reference peak, scale 0..%.3g of the peak (the largest "
             "over the grid; not radiance)", vmax);
    if (caption)
        snprintf(caption, caption_len, "%s", title);
    if (draw_contact_grid(path, w, h, grid_r, grid_m, grid_err, (float)vmax, title, &labels, err, errlen) != 0)
        return EXIT_RUNTIME;
    return stamp(path, err, errlen);
}
