/* render_report.h - the results of the image passes (render.c measures them) and their
 * writers (render_report.c: render.json, the markdown summary, the printed timings). */
#ifndef BRDFBENCH_RENDER_REPORT_H
#define BRDFBENCH_RENDER_REPORT_H

#include <stddef.h>

#include "clsession.h"
#include "render.h"

/* kernels/shade.cl's constants (shading modes, display table, the parameters' positions),
   the same header as the kernel's */
#include "shade_shared.h"

/* Work-items of one launch: each walks a contiguous run of pixels, so a few per core
   balance the load without barriers; the same count for every size keeps one launch
   shape (PoCL compiles per shape). */
#define RENDER_WORK_ITEMS 256
/* The work-items of a render launch on device s: RENDER_WORK_ITEMS on a CPU device; on a GPU, 512
   per compute unit (256 work-items would fill two of a GPU's multiprocessors and leave the rest
   idle). Pixels are independent: the images do not depend on it. */
struct cl_session;
long render_work_items(const struct cl_session *s);

struct image_metrics {
    size_t pixels;             /* foreground pixels in the region */
    double max_abs;
    int max_x, max_y;          /* frame coordinates of the largest error */
    double mean_abs, rmse;
    double psnr_db;            /* 8-bit RGB; NAN when the images are identical */
    double share_above;        /* share of pixels with error above the threshold */
    double peak_reference;     /* largest reference specular radiance in the region */
    size_t nonfinite;          /* foreground pixels whose error is NaN or Inf (left out of the figures
                                  above; any makes the model's figures not figures: written as null) */
};

/* The largest |model - reference| relative to the reference's peak radiance in the same
   region (what the sphere grid's error scale shows); NAN without a peak. max_abs itself is
   absolute: specular radiance in units of the light's irradiance E = 1. */
double render_max_of_peak(const struct image_metrics *mt);

struct reference_check {
    int samples;
    double max_abs;            /* |device - double| of the specular radiance */
    double value_at_max;       /* the double value there */
    double peak;               /* largest double specular radiance among the samples */
    double relative_to_peak;   /* max_abs / max(peak, 1e-30) */
    int max_code;              /* largest 8-bit difference to the exact display colour */
    double bound;              /* stated bound on max_abs */
    int within;
};

struct model_result {
    int mode;
    int y0, y1;                /* frame rows its figures cover */
    struct model_spec ref;
    struct image_metrics metrics;
    struct reference_check check;
    char image[256], error[256], contact[256];  /* paths relative to out_dir */
    char signed_error[256];    /* the signed error image, beside error */
    char contact_caption[400]; /* the contact sheet's caption, as drawn (render.json has it) */
    /* The pixel of the largest |model - reference| (metrics.max_x, max_y) and what shaded it, so
       that the figure can be worked out again from the two BRDFs' formulas at that pixel's vectors
       (docs/user-models.md, "Render against the hemisphere sweep"): specular = e (N.L) ks f. */
    struct render_worst_pixel {
        int valid;
        int x, y;
        double L[3], V[3], N[3];   /* unit directions to the light and the eye; the normal as shaded */
        double n, e;               /* the pixel's shininess; the irradiance at normal incidence */
        double spec_model, spec_reference;   /* the device's specular radiances there */
    } worst;
};

/* Launch times kept per entry, in launch order, for a rank test between runs (compare). */
#define RENDER_MAX_KEPT_REPS 64

struct timed_entry {
    struct model_spec spec;
    int mode;
    int is_model;              /* in the user's list (not only a reference) */
    char name[MODEL_LABEL_MAX + 32];
    double med, min, max;      /* seconds */
    int nreps;                 /* the first min(reps, RENDER_MAX_KEPT_REPS) launches: */
    double rep_s[RENDER_MAX_KEPT_REPS];   /* their seconds */
    double copy_med;           /* the copy kernel's median, interleaved with these reps */
};

struct size_timing {
    int w, h;
    size_t foreground;
    double copy_med;           /* median over every copy launch at this size */
    int nentries;
    struct timed_entry entries[2 * RENDER_MAX_MODELS];
};

/* He's model against Blinn-Phong fitted to it (least squares over the image's specular
 * radiance: n by Brent's method in log n, the scale k in closed form for each n) and the cheap
 * lobes at that n, in the Blinn variable theta_h; every error against He's image. */
struct he_entry {
    char label[MODEL_LABEL_MAX + 16];
    struct image_metrics metrics;           /* against He's image */
    double max_abs_vs_blinn;                /* against the fitted Blinn-Phong image */
    char image[256], error[256], contact[256];
    char signed_error[256];
};
struct he_comparison {
    int done;
    struct model_spec he;
    double n_fit, k_fit;                    /* Blinn-Phong k c^n, ks scaled by k */
    double rel_rms;                         /* sqrt(residual / sum of He's squares) */
    size_t fit_pixels;
    char he_image[256];
    int count;                              /* entries: [0] Blinn-Phong, then the cheap lobes */
    struct he_entry e[RENDER_MAX_MODELS + 1];
};

/* A mesh shaded with a measured material (render --measured) beside the lobes fitted to it
 * (host/measure/measured/measured.c): entry 0 the measured table, then Blinn-Phong, Cook-Torrance
 * Beckmann and GGX at their fits; radiance E (N.L) f with the fit's Lambertian term. */
#define RENDER_MAX_MEASURED 4
#define RENDER_MEASURED_ENTRIES 4
struct render_measured_entry {
    char label[96];
    int fitted;                  /* the fit converged (else the entry is not drawn) */
    double n, ks, kd, f0;        /* the fit (Cook-Torrance: n = 2/alpha^2 - 2) */
    double max_abs, rms;         /* radiance against the measured image, foreground */
};
struct render_measured_result {
    char material[256];
    double peak;                 /* the measured image's largest radiance */
    double check_max_abs_of_peak;   /* device lookup against the host's, sampled pixels */
    long check_pixels;
    int count;
    struct render_measured_entry e[RENDER_MEASURED_ENTRIES];
};

struct scene_result {
    int kind;
    int done;
    char source[600];
    size_t triangles, patches, foreground;
    double raster_seconds;
    struct render_light light;
    struct model_result models[RENDER_MAX_MODELS];
    char grid_contact[256];
    char grid_caption[300];    /* the sphere grid's caption, as drawn */
    double grid_max_of_peak;   /* its error scale: the largest |model - reference| / the row's reference peak */
    int ntimings;
    struct size_timing timings[RENDER_MAX_TIME_SIZES];
    struct he_comparison he;
    int nmeasured;
    struct render_measured_result measured[RENDER_MAX_MEASURED];
};

#define RENDER_MODE_COUNT 7
extern const char *const render_scene_names[RENDER_SCENE_COUNT];
extern const char *const render_mode_names[RENDER_MODE_COUNT];

/* render.json of a run. Returns 0, or non-zero with a message in err. */
int render_write_json(const char *path, const struct cl_session *s, const struct render_options *o,
                      const struct scene_result *res, int display_code_error, char *err,
                      size_t errlen);
/* Progress on stdout: a scene's source, one model's image figures, the scene's device-vs-double
 * check over its models, He's comparison. */
void render_print_scene(const struct scene_result *sr);
void render_print_model(int scene, const char *label, const struct model_result *mr);
void render_print_check(const struct scene_result *sr, int nmodels);
void render_print_he(int scene, const struct he_comparison *hc);
struct gbuffer;
void render_print_measured(int scene, const struct render_measured_result *mr);

/* A mesh's G-buffer g shaded with the measured material mat and with the lobes fitted to it
 * (render_measured.c): images into scene_dir when o->write_images. Returns 0 or an exit code. */
int render_measured_pass(struct render_device *dev, const struct gbuffer *g, const struct render_light *lt,
                         const struct render_options *o, const struct merl_material *mat, const char *scene_dir,
                         struct render_measured_result *res, char *err, size_t errlen);
/* One scene's timings on stdout. */
void render_print_timings(const struct scene_result *sr);

#endif
