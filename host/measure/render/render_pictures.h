/* render_pictures.h - the pictures of the image passes (render.c): per model its image, its
 * absolute and signed error images and its contact sheet; the sphere grid's labelled contact
 * sheet; the same for He's comparison. Each error picture is stamped when the run is quick. */
#ifndef BRDF_RENDER_PICTURES_H
#define BRDF_RENDER_PICTURES_H

#include "render.h"
#include "render_report.h"

#include <stddef.h>

/* One picture set of an image w x h in scene_dir: <prefix><base>.png (when rgb is not NULL),
 * _error.png, _signed_error.png and (when ref_rgb is not NULL) _contact.png; the paths relative
 * to the run folder ("render/<scene>/...") go into image, error, signed_error and contact.
 * abs_err and signed_err: w*h floats (NaN = background). 0, or EXIT_RUNTIME with a message. */
struct render_picture_set {
    const char *scene_dir, *scene, *prefix, *base;
    int w, h;
    const unsigned char *rgb, *ref_rgb;
    const float *abs_err, *signed_err;
    double max_abs;
    const char *error_title, *signed_title, *contact_title;
    char *image, *error, *signed_error, *contact;   /* 256 bytes each; image/contact may be NULL */
};
int render_write_pictures(const struct render_picture_set *p, char *err, size_t errlen);

/* The signed error image's title: "<scene>: <model> - <reference> specular radiance; blue: under,
 * red: over, scale +-<max>". */
void render_signed_title(char *out, size_t len, const char *scene, const char *model, const char *reference,
                         double max_abs);

/* The sphere grid's contact sheet (scene_dir/contact.png): a row per model of o, labelled with
 * its name, a column per shininess, labelled "n = ...". caption (may be NULL) receives the
 * caption drawn: the error scale vmax is relative to each row's reference peak. */
int render_write_grid(const char *scene_dir, const struct render_options *o, int w, int h,
                      const unsigned char *grid_r, const unsigned char *grid_m, const float *grid_err, double vmax,
                      char *caption, size_t caption_len,
                      char *err, size_t errlen);

#endif
