/* render.h - the full-image shading passes (`brdfbench render`) as a library call: the
 * sphere grid, the Utah teapot and the Stanford bunny shaded with every model on the
 * device, error images against each model's reference, image metrics, the double host
 * reference on a sample of pixels, and Mpixel/s against a copy kernel moving the same
 * bytes, all written under one output folder (render.json plus render/<scene>/ PNGs). */
#ifndef BRDFBENCH_RENDER_H
#define BRDFBENCH_RENDER_H

#include <stddef.h>

#include "clsession.h"
#include "engine.h"
#include "merl.h"
#include "models.h"

#define RENDER_MAX_MODELS 32
#define RENDER_MAX_COLS 16
#define RENDER_MAX_TIME_SIZES 4
#define RENDER_MIN_SIDE 16
#define RENDER_MAX_SIDE 16384
/* Device bytes per pixel: seven G-buffer floats in, RGBA8 and one float out. */
#define RENDER_DEVICE_BYTES_PER_PIXEL 36
/* Host bytes per pixel, at least: the G-buffer (28), the pass's RGBA8 and three float images
 * (16), the contact sheet's error float and two RGB8 images (10), a model's cached RGBA8 and
 * specular float (8). */
#define RENDER_HOST_BYTES_PER_PIXEL 62

enum render_scene { RENDER_SPHERES = 0, RENDER_TEAPOT, RENDER_BUNNY, RENDER_SCENE_COUNT };

/* Debian's files the mesh scenes read (and the packages that ship them). */
#define RENDER_TEAPOT_PATH "/usr/share/doc/povray/examples/advanced/teapot/teapot.inc"
#define RENDER_TEAPOT_PACKAGE "povray-examples"
#define RENDER_BUNNY_PATH "/usr/share/glmark2/models/bunny.obj"
#define RENDER_BUNNY_PACKAGE "glmark2-data"

struct render_options {
    struct engine_io io;               /* the run folder and --quiet: progress and the table (engine.h) */
    int scene_on[RENDER_SCENE_COUNT];  /* which scenes to render */
    int width, height;                 /* image pass size */
    int ntime_sizes;                   /* timing sizes (0: no timing) */
    int time_w[RENDER_MAX_TIME_SIZES], time_h[RENDER_MAX_TIME_SIZES];
    int reps, warmup;                  /* timed launches after warm-up launches */
    int nmodels;
    struct model_spec models[RENDER_MAX_MODELS];
    int ncols;                         /* sphere grid columns: one shininess each */
    double sphere_n[RENDER_MAX_COLS];
    double mesh_n;                     /* shininess of the teapot and the bunny */
    int tess;                          /* teapot: quads per patch side */
    int point_light;                   /* 0: directional light */
    double exposure, kd, ks, ambient, f0;
    double tint[3];                    /* material colour (linear RGB) */
    double threshold;                  /* error above this counts as a visible error */
    int ref_samples;                   /* pixels per model checked against the double reference */
    const char *teapot_path, *bunny_path;
    int he_material;                   /* He comparison on the meshes: a preset of the model he, -1: none */
    int write_images;                  /* PNGs (image, error image, contact sheet) */
    int nmeasured;                     /* measured materials on the meshes (--measured) */
    const struct merl_material *measured[4];
};

/* Defaults: all three scenes at 1920x1080, timing at 1920x1080 and 3840x2160 (7 reps after
 * 2 warm-ups), every model of the default set and the physically based models, sphere columns
 * 4 16 64 256 1000, n = 64 on the meshes, teapot at 16 quads per patch side, a directional
 * light; the teapot and the bunny also shaded by He's model (rough aluminium) beside
 * Blinn-Phong at its best-matching n and the cheap lobes at that n. */
void render_options_default(struct render_options *o);

/* Checks a size against the accepted range and the device's memory (global memory and
 * largest single buffer). Returns 0, or 2 with a message naming `what` and the range. */
int render_check_size(const struct cl_session *s, const char *what, long width, long height,
                      int nmodels_rows, char *err, size_t errlen);

/* What a run gives back: the message of a failure (report.md's image passes are drawn from
 * render.json's rows: host/results/report/report_render.c). Unlike the other
 * engines, render leaves its message to the caller (r->err), because it also runs inside them
 * (the frontier's teapot pass, all's image passes), which name the pass. */
struct render_result {
    char err[1024];
};
void render_result_free(struct render_result *r);

/* Runs every selected scene: images and metrics at width x height, timings at each timing
 * size; writes o->io.out_dir/render.json and render/<scene>/ *.png, progress and the table
 * on stdout unless o->io.quiet. The files of a run are staged and moved into place at the
 * end, so a failed run leaves the previous results as they were.
 * Returns 0, 2 (bad input: size, malformed scene file), 3 (runtime, or a scene's Debian
 * file missing), with a one-line message in r->err. */
int render_run(struct cl_session *s, const struct render_options *o, struct render_result *r);

/* --- pieces exposed for the tests ------------------------------------------------------ */

/* Shading mode of the kernel for a model: the cosine it takes and Cook-Torrance or not. */
int render_shading_mode(const struct model_spec *m);
/* The mode a model's reference ref is shaded in beside a model shaded in `mode`: the same, but a
 * user full BRDF's reference (a built-in model) in its own. */
int render_reference_mode(int mode, const struct model_spec *ref);

/* Shading parameters (the kernel's float16 `params`) for a camera eye and the options. */
struct render_light {
    double eye[3];
    double light[3];     /* unit direction towards the light, or its position */
    int point;
    double intensity;
};

/* The double-precision host reference of one pixel: specular radiance and total radiance
 * from a position, unit normal and shininess (the same formulas as kernels/shade.cl). */
/* The unit directions to the eye and the light at a position, and the irradiance e at normal
 * incidence (the geometry render_shade_ref and kernels/shade.cl use). */
void render_pixel_geometry(const struct render_light *lt, const double pos[3], double v[3], double l[3], double *e);
/* The RGB bytes of packed RGBA8 pixels. */
void render_rgba_to_rgb(const unsigned *rgba, size_t n, unsigned char *rgb);
void render_shade_ref(const struct model_spec *m, int mode, const struct render_light *lt,
                      const struct render_options *o, const double pos[3], const double nrm[3],
                      double n, double *spec, double *radiance);
/* The least-squares fit of Blinn-Phong to He's image: minimises sum (k a_i c_i^n - h_i)^2 over
 * k (closed form for each n) and n in [1, 20000] (Brent's method in log n). */
void render_he_fit(const double *a, const double *c, const double *h, size_t count, double *n, double *k,
                   double *rel_rms);
/* The exact 8-bit display colour of a radiance (the curve the display table samples). */
void render_display_exact(const struct render_options *o, double radiance, unsigned char rgb[3]);

/* One shading pass on the device: G-buffer planes (7 x stride floats) already in `gbuf`.
 * Used by render_run and the tests. */
struct render_device {
    struct cl_session *s;
    cl_program program;
    cl_kernel shade, copy;
    cl_mem display_table;
    cl_mem merl_table;        /* the measured material of SHADE_MEASURED (NULL: none) */
    cl_mem no_table;          /* what the kernel reads as the table otherwise */
    int display_code_error;   /* largest table entry's distance to the exact curve, codes */
    size_t global_size;
};
int render_device_open(struct render_device *d, struct cl_session *s,
                       const struct render_options *o, char *err, size_t errlen);
void render_device_close(struct render_device *d);
/* Shades npix pixels of a G-buffer already on the device; reads back rgba and spec when
 * they are non-NULL; *seconds receives the kernel's profiled time. */
int render_device_shade(struct render_device *d, cl_mem gbuf, size_t stride, size_t npix,
                        cl_mem out_rgba, cl_mem out_spec, const struct model_spec *m, int mode,
                        const struct render_light *lt, const struct render_options *o,
                        unsigned *rgba, float *spec, double *seconds);

#endif
