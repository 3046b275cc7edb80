/* render_internal.h - inside render: what its files share (render.c, render_scene.c,
 * render_metrics.c, render_shade.c, render_images.c, render_fit.c, render_timing.c).
 * Not an interface for other modules: render.h is. */
#ifndef BRDFBENCH_RENDER_INTERNAL_H
#define BRDFBENCH_RENDER_INTERNAL_H

#include <stddef.h>

#include "geometry.h"
#include "raster.h"
#include "render.h"
#include "render_report.h"

/* ---- scenes (render_scene.c) ---- */

struct scene_data {
    int kind;
    struct mesh mesh;          /* teapot and bunny */
    size_t patches;            /* teapot: Bezier patches read */
    char source[600];          /* the file read, or "analytic" */
};

/* Reads and checks a scene's file (the spheres are analytic). Returns 0 or an exit code. */
int scene_load(int kind, const struct render_options *o, struct scene_data *sd, char *err, size_t errlen);
/* The scene's G-buffer at w x h and its light. */
int scene_gbuffer(const struct scene_data *sd, const struct render_options *o, int w, int h,
                  struct gbuffer *g, struct render_light *lt, char *err, size_t errlen);
/* The rows [y0, y1) of the image that model `row` owns (the whole image on a mesh). */
void model_region(const struct scene_data *sd, const struct render_options *o, int h,
                  int row, int *y0, int *y1);

/* ---- metrics (render_metrics.c) ---- */

/* The worst pixel of m (metrics' max_x, max_y) with its light, eye and normal (render_report.h). */
void render_worst_pixel(const struct gbuffer *g, const struct render_light *lt, const struct image_metrics *mt,
                        const float *spec_m, const float *spec_r, struct render_worst_pixel *wp);
void compute_metrics(const struct gbuffer *g, int y0, int y1, const unsigned *rgba_m,
                     const float *spec_m, const unsigned *rgba_r, const float *spec_r,
                     double threshold, float *errimg, float *signed_img, struct image_metrics *mt);
void check_reference(const struct gbuffer *g, int y0, int y1, const struct model_spec *m,
                     int mode, const struct render_light *lt, const struct render_options *o,
                     const unsigned *rgba, const float *spec, struct reference_check *rc);

/* ---- the device (render_shade.c) ---- */

/* One launch of the copy kernel (the G-buffer read, the image written, no shading). */
int device_copy(struct render_device *d, cl_mem gbuf, size_t stride, size_t npix,
                cl_mem out_rgba, cl_mem out_spec, double *seconds);

/* ---- the passes (render_images.c, render_fit.c, render_timing.c) ---- */

/* A model label as a file name: "fq:Q=0.64" -> "fq_Q=0.64". */
void label_to_file(const char *label, char *out, size_t len);
/* A pass's host images of npix pixels each, named by element type (packed RGBA, float and double
 * planes, 8-bit RGB of 3 bytes a pixel) so that one call allocates them and one frees them; an
 * entry left NULL is skipped. */
#define PIXEL_BUFFERS_MAX 6
struct pixel_buffers {
    unsigned **rgba[PIXEL_BUFFERS_MAX];
    float **floats[PIXEL_BUFFERS_MAX];
    double **doubles[PIXEL_BUFFERS_MAX];
    unsigned char **rgb[PIXEL_BUFFERS_MAX];
};
/* -1 when out of memory (what was allocated is left for pixel_buffers_free). */
int pixel_buffers_alloc(const struct pixel_buffers *b, size_t npix);
void pixel_buffers_free(const struct pixel_buffers *b);
/* A pass's device buffers, and their release (see render_images.c). */
void pass_release(cl_mem out_spec, cl_mem out_rgba, cl_mem gbuf, struct gbuffer *g);
int pass_buffers(struct cl_session *s, const struct gbuffer *g, cl_mem_flags gbuf_flags, const char *which,
                 cl_mem *gbuf, cl_mem *out_rgba, cl_mem *out_spec);
int image_pass(struct render_device *dev, const struct scene_data *sd,
               const struct render_options *o, const char *stage_dir,
               struct scene_result *res, char *err, size_t errlen);
int measured_scene(struct render_device *dev, const struct scene_data *sd, const struct render_options *o,
                   const char *stage_dir, struct scene_result *res, char *err, size_t errlen);
int he_pass(struct render_device *dev, const struct scene_data *sd, const struct render_options *o,
            const char *stage_dir, struct scene_result *res, char *err, size_t errlen);
int time_pass(struct render_device *dev, const struct scene_data *sd,
              const struct render_options *o, int w, int h, struct size_timing *st,
              char *err, size_t errlen);

#endif
