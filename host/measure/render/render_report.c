/* render_report.c - the writers of the image passes: render.json with its rows (what report.md's
 * image passes are drawn from) and the lines printed per scene (render.c measures, this file
 * writes). */
#include "render_report.h"

#include "context.h"
#include "jsonw.h"
#include "rdoc.h"
#include "schemas.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double mpix(const struct size_timing *st, double seconds)
{
    return (double)st->w * st->h / seconds * 1e-6;
}

/* The entry of a model's reference in the same shading mode. */
static const struct timed_entry *reference_entry(const struct size_timing *st,
                                                 const struct timed_entry *te)
{
    struct model_spec ref;
    model_reference_spec(&te->spec, &ref);
    for (int k = 0; k < st->nentries; k++)
        if (st->entries[k].mode == render_reference_mode(te->mode, &ref) &&
            strcmp(st->entries[k].spec.label, ref.label) == 0)
            return &st->entries[k];
    return NULL;
}

/* A lobe model (not Cook-Torrance): the speed target applies to these. */
static int is_lobe_entry(const struct timed_entry *te)
{
    return te->mode == SHADE_LOBE_PSI || te->mode == SHADE_LOBE_THETA_H;
}

#define SPEED_TARGET_FRACTION 0.5

/* "key": [a, b] and "key": [x, y, z] */
static void jw_kv_int_pair(struct jw *w, const char *key, long long a, long long b)
{
    jw_kv_arr(w, key);
    jw_int(w, a);
    jw_int(w, b);
    jw_arr_end(w);
}

/* The figures as they are shown: none of them when some pixels' errors are not finite (a
   model that is NaN somewhere is not "max |error| 0"). */
static struct image_metrics shown(const struct image_metrics *mt)
{
    struct image_metrics s = *mt;
    if (s.nonfinite)
        s.max_abs = s.mean_abs = s.rmse = s.psnr_db = s.share_above = NAN;
    return s;
}

double render_max_of_peak(const struct image_metrics *mt)
{
    return mt->peak_reference > 0 ? mt->max_abs / mt->peak_reference : NAN;
}

static void write_metrics_json(struct jw *w, const struct image_metrics *mt_in, double threshold)
{
    struct image_metrics sm = shown(mt_in);
    const struct image_metrics *mt = &sm;
    jw_kv_obj(w, "metrics");
    jw_kv_str(w, "quantity", "specular radiance |model - reference| (linear, E = 1 units)");
    jw_kv_int(w, "pixels", (long long)mt->pixels);
    jw_kv_num(w, "max_abs", mt->max_abs);
    jw_kv_str(w, "max_abs_unit", "specular radiance, absolute (light irradiance E = 1)");
    /* the same maximum relative to the reference's peak: the scale of the sphere grid */
    jw_kv_num(w, "max_abs_of_reference_peak", render_max_of_peak(mt));
    jw_kv_num(w, "mean_abs", mt->mean_abs);
    jw_kv_num(w, "rmse", mt->rmse);
    jw_kv_num(w, "psnr_db", mt->psnr_db);
    jw_kv_str(w, "psnr_basis", "8-bit sRGB colours of the foreground, peak 255");
    if (mt->nonfinite) {
        jw_kv_str(w, "status", "nonfinite");
        jw_kv_int(w, "nonfinite_pixels", (long long)mt->nonfinite);
        jw_kv_str(w, "reason", "the model's radiance is NaN or Inf at some foreground pixels: no error figure");
    } else if (!isfinite(mt->psnr_db)) {
        jw_kv_str(w, "psnr_status", mt->pixels ? "identical images: PSNR is infinite"
                                               : "no foreground pixels");
    }
    jw_kv_num(w, "threshold", threshold);
    jw_kv_num(w, "share_above_threshold", mt->share_above);
    jw_kv_num(w, "peak_reference", mt->peak_reference);
    jw_obj_end(w);
}

static void write_measured(struct jw *w, const struct scene_result *sr);

/* The He comparison of a scene (render_report.h, struct he_comparison). */
static void write_he_json(struct jw *w, const struct he_comparison *hc, double threshold)
{
    jw_kv_obj(w, "he_comparison");
    jw_kv_str(w, "model", hc->he.label);
    jw_kv_str(w, "method", "Blinn-Phong k E (N.L) ks c^n (c = N.H) fitted to He's specular radiance by least squares "
                           "over the foreground: k in closed form for each n, n by Brent's method in log n; the "
                           "cheap lobes (quadratic and rational families) shaded at that n and k in theta_h; errors "
                           "against He's image");
    jw_kv_num(w, "n_fit", hc->n_fit);
    jw_kv_num(w, "k_fit", hc->k_fit);
    jw_kv_num(w, "relative_rms_residual", hc->rel_rms);
    jw_kv_int(w, "fit_pixels", (long long)hc->fit_pixels);
    jw_kv_str(w, "he_image", hc->he_image);
    jw_kv_arr(w, "entries");
    for (int k = 0; k < hc->count; k++) {
        const struct he_entry *en = &hc->e[k];
        jw_obj_begin(w);
        jw_kv_str(w, "name", en->label);
        write_metrics_json(w, &en->metrics, threshold);
        jw_kv_num(w, "max_abs_vs_blinn_fit", en->max_abs_vs_blinn);
        if (en->error[0]) {
            jw_kv_obj(w, "files");
            if (en->image[0])
                jw_kv_str(w, "image", en->image);
            jw_kv_str(w, "error", en->error);
            if (en->signed_error[0])
                jw_kv_str(w, "signed_error", en->signed_error);
            if (en->contact[0])
                jw_kv_str(w, "contact_sheet", en->contact);
            jw_obj_end(w);
        }
        jw_obj_end(w);
    }
    jw_arr_end(w);
    jw_obj_end(w);
}

/* The options of the run in render.json. */
static void write_options_json(struct jw *w, const struct render_options *o)
{
    jw_kv_obj(w, "options");
    jw_kv_int_pair(w, "image_size", o->width, o->height);
    jw_kv_arr(w, "timing_sizes");
    for (int i = 0; i < o->ntime_sizes; i++) {
        jw_arr_begin(w);
        jw_int(w, o->time_w[i]);
        jw_int(w, o->time_h[i]);
        jw_arr_end(w);
    }
    jw_arr_end(w);
    jw_kv_int(w, "reps", o->reps);
    jw_kv_int(w, "warmup", o->warmup);
    jw_kv_nums(w, "sphere_shininess", o->sphere_n, (size_t)o->ncols);
    jw_kv_num(w, "mesh_shininess", o->mesh_n);
    jw_kv_int(w, "teapot_tessellation", o->tess);
    jw_kv_str(w, "light", o->point_light ? "point" : "directional");
    jw_kv_num(w, "exposure", o->exposure);
    jw_kv_num(w, "kd", o->kd);
    jw_kv_num(w, "ks", o->ks);
    jw_kv_num(w, "ambient", o->ambient);
    jw_kv_num(w, "schlick_f0", o->f0);
    jw_kv_nums(w, "tint", o->tint, 3);
    jw_kv_int(w, "reference_samples_per_model", o->ref_samples);
    jw_obj_end(w);
}

/* A scene's source, geometry, light and image in render.json. */
static void write_scene_setup_json(struct jw *w, int si, const struct scene_result *sr,
                                   const struct render_options *o)
{
    jw_kv_str(w, "scene", render_scene_names[si]);
    jw_kv_str(w, "source", sr->source);
    if (si == RENDER_TEAPOT) {
        jw_kv_str(w, "package", RENDER_TEAPOT_PACKAGE);
        jw_kv_int(w, "patches", (long long)sr->patches);
    } else if (si == RENDER_BUNNY) {
        jw_kv_str(w, "package", RENDER_BUNNY_PACKAGE);
    }
    if (si != RENDER_SPHERES)
        jw_kv_int(w, "triangles", (long long)sr->triangles);
    jw_kv_obj(w, "light");
    jw_kv_str(w, "kind", sr->light.point ? "point" : "directional");
    jw_kv_nums(w, sr->light.point ? "position" : "direction", sr->light.light, 3);
    jw_kv_num(w, "intensity", sr->light.intensity);
    jw_kv_nums(w, "eye", sr->light.eye, 3);
    jw_obj_end(w);
    jw_kv_obj(w, "image");
    jw_kv_int(w, "width", o->width);
    jw_kv_int(w, "height", o->height);
    jw_kv_int(w, "foreground_pixels", (long long)sr->foreground);
    jw_kv_num(w, "gbuffer_seconds", sr->raster_seconds);
    if (sr->grid_contact[0]) {
        jw_kv_str(w, "contact_sheet", sr->grid_contact);
        jw_kv_str(w, "contact_sheet_caption", sr->grid_caption);
        jw_kv_num(w, "contact_sheet_error_scale_of_reference_peak", sr->grid_max_of_peak);
    }
    jw_obj_end(w);
}

/* One model of a scene in render.json: its files, error figures and the double check. */
static void write_model_json(struct jw *w, int si, const struct model_result *mr,
                             const struct model_spec *m, double threshold)
{
    jw_obj_begin(w);
    jw_kv_str(w, "model", m->label);
    jw_kv_str(w, "family", model_family_name(m->info->family));
    jw_kv_str(w, "reference", mr->ref.label);
    jw_kv_str(w, "shading", render_mode_names[mr->mode]);
    if (si == RENDER_SPHERES) {
        jw_kv_int_pair(w, "grid_rows", mr->y0, mr->y1);
    }
    if (mr->image[0]) {
        jw_kv_obj(w, "files");
        jw_kv_str(w, "image", mr->image);
        jw_kv_str(w, "error_image", mr->error);
        if (mr->signed_error[0])
            jw_kv_str(w, "signed_error_image", mr->signed_error);
        jw_kv_str(w, "contact_sheet", mr->contact);
        jw_obj_end(w);
        jw_kv_str(w, "contact_sheet_caption", mr->contact_caption);   /* as drawn */
    }
    write_metrics_json(w, &mr->metrics, threshold);
    if (mr->worst.valid) {
        const struct render_worst_pixel *wp = &mr->worst;
        jw_kv_obj(w, "worst_pixel");
        jw_kv_str(w, "what", "the pixel of max_abs: specular radiance = e (N.L) ks f(L, V) for the model and its "
                             "reference; L, V unit directions to the light and the eye, N the normal as shaded");
        jw_kv_int_pair(w, "pixel", wp->x, wp->y);
        jw_kv_nums(w, "L", wp->L, 3);
        jw_kv_nums(w, "V", wp->V, 3);
        jw_kv_nums(w, "N", wp->N, 3);
        jw_kv_num(w, "n", wp->n);
        jw_kv_num(w, "irradiance", wp->e);
        jw_kv_num(w, "specular_model", wp->spec_model);
        jw_kv_num(w, "specular_reference", wp->spec_reference);
        jw_obj_end(w);
    }
    jw_kv_obj(w, "double_reference_check");
    jw_kv_int(w, "samples", mr->check.samples);
    jw_kv_num(w, "max_abs_specular_difference", mr->check.max_abs);
    jw_kv_num(w, "double_value_there", mr->check.value_at_max);
    jw_kv_num(w, "peak_specular", mr->check.peak);
    jw_kv_num(w, "relative_to_peak", mr->check.relative_to_peak);
    jw_kv_num(w, "bound", mr->check.bound);
    jw_kv_str(w, "bound_rule", "1e-3 of the sampled peak specular radiance; 8-bit "
              "colours within 2 codes of the exact curve");
    jw_kv_int(w, "max_code_difference", mr->check.max_code);
    jw_kv_bool(w, "within_bound", mr->check.within);
    jw_obj_end(w);
    jw_obj_end(w);
}

/* One timed entry of a size in render.json: its times, share of the copy and speed-up. */
static void write_timed_entry_json(struct jw *w, const struct size_timing *st,
                                   const struct timed_entry *te)
{
    const struct timed_entry *re = reference_entry(st, te);
    double frac = te->copy_med / te->med;
    jw_obj_begin(w);
    jw_kv_str(w, "name", te->name);
    jw_kv_str(w, "model", te->spec.label);
    jw_kv_str(w, "shading", render_mode_names[te->mode]);
    jw_kv_bool(w, "selected_model", te->is_model);
    jw_kv_num(w, "median_ms", te->med * 1e3);
    jw_kv_num(w, "min_ms", te->min * 1e3);
    jw_kv_num(w, "max_ms", te->max * 1e3);
    jw_kv_num(w, "mpixel_per_s", mpix(st, te->med));
    jw_kv_arr(w, "mpixel_per_s_reps");
    for (int k = 0; k < te->nreps; k++)
        jw_num(w, mpix(st, te->rep_s[k]));
    jw_arr_end(w);
    jw_kv_num(w, "copy_median_ms_interleaved", te->copy_med * 1e3);
    jw_kv_num(w, "fraction_of_copy", frac);
    if (is_lobe_entry(te)) {
        jw_kv_num(w, "target_fraction", SPEED_TARGET_FRACTION);
        jw_kv_bool(w, "target_met", frac >= SPEED_TARGET_FRACTION);
    }
    if (re) {
        jw_kv_str(w, "reference", re->name);
        jw_kv_num(w, "speedup_vs_reference", re->med / te->med);
    }
    jw_obj_end(w);
}

/* A scene's timings in render.json: per size the copy kernel and every timed entry. */
static void write_timings_json(struct jw *w, const struct scene_result *sr)
{
    jw_kv_arr(w, "timings");
    for (int ti = 0; ti < sr->ntimings; ti++) {
        const struct size_timing *st = &sr->timings[ti];
        jw_obj_begin(w);
        jw_kv_int(w, "width", st->w);
        jw_kv_int(w, "height", st->h);
        jw_kv_int(w, "foreground_pixels", (long long)st->foreground);
        jw_kv_obj(w, "copy");
        jw_kv_int(w, "bytes_per_pixel", RENDER_DEVICE_BYTES_PER_PIXEL);
        jw_kv_num(w, "median_ms", st->copy_med * 1e3);
        jw_kv_num(w, "mpixel_per_s", mpix(st, st->copy_med));
        jw_kv_num(w, "gbyte_per_s",
                  (double)st->w * st->h * RENDER_DEVICE_BYTES_PER_PIXEL / st->copy_med * 1e-9);
        jw_obj_end(w);
        jw_kv_arr(w, "entries");
        for (int k = 0; k < st->nentries; k++)
            write_timed_entry_json(w, st, &st->entries[k]);
        jw_arr_end(w);
        jw_obj_end(w);
    }
    jw_arr_end(w);
}

/* A row's error figures against its reference, with its status: none of them where they are not
   finite (a NaN pixel: the row is then failed, its figures null; the PSNR of identical images). */
static void image_error_metrics(struct rdoc *d, struct rd_row *r, const struct image_metrics *sm)
{
    if (sm->nonfinite)
        rd_row_fail(r, "nonfinite", "the model's radiance is NaN or Inf at some foreground pixels: no error figure");
    const struct { const char *name, *unit; int direction; double v; } errs[] = {
        { "max_abs", "1", RD_LOWER, sm->max_abs }, { "rmse", "1", RD_LOWER, sm->rmse },
        { "psnr_db", "dB", RD_HIGHER, sm->psnr_db }, { "share_above_threshold", "1", RD_LOWER, sm->share_above } };
    for (size_t k = 0; k < sizeof errs / sizeof errs[0]; ++k)
        if (isfinite(errs[k].v) || !r->ok)
            rd_row_metric(d, r, errs[k].name, errs[k].unit, errs[k].direction, 0, errs[k].v);
}

/* A scene's He comparison: a row for the Blinn-Phong fit to He's image (n_fit, k_fit: neither;
   its relative rms residual), then one per model shaded at that n (max_abs, mean_abs against
   He's image, max_abs_vs_blinn_fit; text contact_sheet). Keys scene "NAME WxH", against (He's
   model), shaded_by; attributes scene_name and he ("fit" or "entry"). */
static void he_rows(struct rdoc *d, int si, const struct he_comparison *hc, const char *scene)
{
    for (int k = -1; k < hc->count; k++) {
        struct rd_row *r = rdoc_row(d, "", k < 0 ? hc->he.label : hc->e[k].label);
        if (!r)
            return;
        rd_row_key(r, "scene", NULL, scene);
        rd_row_key(r, "against", NULL, hc->he.label);
        rd_row_key(r, "shaded_by", NULL, k < 0 ? "Blinn-Phong fit" : hc->e[k].label);
        rd_row_attr(r, "scene_name", render_scene_names[si]);
        rd_row_attr(r, "he", k < 0 ? "fit" : "entry");
        if (k < 0) {
            rd_row_metric(d, r, "n_fit", "1", RD_NEITHER, 0, hc->n_fit);
            rd_row_metric(d, r, "k_fit", "1", RD_NEITHER, 0, hc->k_fit);
            rd_row_metric(d, r, "relative_rms_residual", "1", RD_LOWER, 0, hc->rel_rms);
            continue;
        }
        const struct he_entry *en = &hc->e[k];
        struct image_metrics sm = shown(&en->metrics);
        if (sm.nonfinite)
            rd_row_fail(r, "nonfinite", "the model's radiance is NaN or Inf at some foreground pixels: no error figure");
        const struct { const char *name; double v; } errs[] = {
            { "max_abs", sm.max_abs }, { "mean_abs", sm.mean_abs }, { "max_abs_vs_blinn_fit", en->max_abs_vs_blinn } };
        for (size_t q = 0; q < sizeof errs / sizeof errs[0]; ++q)
            if (isfinite(errs[q].v) || !r->ok)
                rd_row_metric(d, r, errs[q].name, "1", RD_LOWER, 0, errs[q].v);
        if (en->error[0] && en->contact[0])
            rd_row_text(d, r, "contact_sheet", en->contact);
    }
}

/* A scene's rows: one per model with its image's error figures against its reference (none
   where they are not finite: a NaN pixel, or the PSNR of identical images) and the share of
   pixels above the threshold; attributes scene_name and reference; texts: the device-vs-double
   check's verdict, the picture files and, on the scene's first model, the scene's source, its
   contact sheet and the size its timings' table shows (the first timed). Then one row per timed
   entry and image size with its speed, range and launches, its fraction of the copy kernel and
   speed-up against its reference (attributes size and selected_model); then He's comparison
   (he_rows). */
static void scene_rows(struct rdoc *d, int si, const struct scene_result *sr, const struct render_options *o)
{
    char scene[RD_TEXT];
    snprintf(scene, sizeof scene, "%s %gx%g", render_scene_names[si], (double)o->width, (double)o->height);
    for (int mi = 0; mi < o->nmodels; mi++) {
        const struct model_result *mr = &sr->models[mi];
        struct image_metrics sm = shown(&mr->metrics);
        struct rd_row *r = rdoc_row(d, "", o->models[mi].label);
        if (!r)
            return;
        rd_row_key(r, "scene", NULL, scene);
        rd_row_key(r, "model", NULL, o->models[mi].label);
        rd_row_attr(r, "scene_name", render_scene_names[si]);
        rd_row_attr(r, "reference", mr->ref.label);
        image_error_metrics(d, r, &sm);
        rd_row_text(d, r, "double_reference_check", mr->check.within ? "within bound" : "outside bound");
        if (mr->image[0]) {
            rd_row_text(d, r, "image", mr->image);
            rd_row_text(d, r, "error_image", mr->error);
            if (mr->signed_error[0])
                rd_row_text(d, r, "signed_error_image", mr->signed_error);
            rd_row_text(d, r, "contact_sheet", mr->contact);
        }
        if (mi == 0) {
            rd_row_text(d, r, "scene_source", sr->source);
            if (sr->grid_contact[0])
                rd_row_text(d, r, "scene_contact_sheet", sr->grid_contact);
            if (sr->ntimings > 0)
                rd_row_textf(d, r, "scene_timed_size", "%d x %d", sr->timings[0].w, sr->timings[0].h);
        }
    }
    for (int ti = 0; ti < sr->ntimings; ti++) {
        const struct size_timing *st = &sr->timings[ti];
        char metric[64], size[28];
        snprintf(size, sizeof size, "%gx%g", (double)st->w, (double)st->h);
        for (int k = 0; k < st->nentries; k++) {
            const struct timed_entry *te = &st->entries[k];
            const struct timed_entry *re = reference_entry(st, te);
            struct rd_row *r = rdoc_row(d, "", te->spec.label);
            if (!r)
                return;
            rd_row_key(r, "scene", NULL, render_scene_names[si]);
            rd_row_key(r, "entry", NULL, te->name);
            rd_row_attr(r, "size", size);
            rd_row_attr(r, "selected_model", te->is_model ? "true" : "false");
            const double v = mpix(st, te->med);
            snprintf(metric, sizeof metric, "mpixel_per_s@%s", size);
            struct rd_metric *m = rd_row_metric(d, r, metric, "Mpixel/s", RD_HIGHER, 1, v);
            if (m && isfinite(v)) {
                /* Mpixel/s is inversely proportional to the time: the slowest launch gives lo */
                m->lo = v * (te->med * 1e3) / (te->max * 1e3);
                m->hi = v * (te->med * 1e3) / (te->min * 1e3);
                double reps[RENDER_MAX_KEPT_REPS];
                for (int q = 0; q < te->nreps; q++)
                    reps[q] = mpix(st, te->rep_s[q]);
                rd_metric_reps(d, m, reps, te->nreps);
            }
            snprintf(metric, sizeof metric, "fraction_of_copy@%s", size);
            rd_row_metric(d, r, metric, "1", RD_HIGHER, 0, te->copy_med / te->med);
            if (re) {
                snprintf(metric, sizeof metric, "speedup_vs_reference@%s", size);
                rd_row_metric(d, r, metric, "1", RD_HIGHER, 0, re->med / te->med);
            }
        }
    }
    if (sr->he.done)
        he_rows(d, si, &sr->he, scene);
}

int render_write_json(const char *path, const struct cl_session *s, const struct render_options *o,
                      const struct scene_result *res, int display_code_error, char *err,
                      size_t errlen)
{
    struct rdoc *d = rdoc_new(RENDER_SCHEMA, "render", "render.json", err, errlen);
    if (!d)
        return -1;
    for (int si = 0; si < RENDER_SCENE_COUNT; si++)
        if (res[si].done)
            scene_rows(d, si, &res[si], o);
    if (rdoc_built(d, err, errlen))
        return -1;
    struct jw w;
    jw_doc_begin(&w, RENDER_SCHEMA, s, "");
    jw_kv_int(&w, "work_items_per_launch", render_work_items(s));
    jw_kv_str(&w, "timing", "OpenCL profiling events (kernel start to end); median of reps after "
              "warm-up launches of the same NDRange; each timed launch follows a copy-kernel launch");
    jw_obj_end(&w);

    write_options_json(&w, o);

    jw_kv_obj(&w, "display");
    jw_kv_str(&w, "curve", "channel k: sRGB8(1 - exp(-exposure tint_k radiance))");
    jw_kv_int(&w, "table_bins", DISPLAY_BINS);
    jw_kv_int(&w, "table_max_code_error", display_code_error);
    jw_obj_end(&w);

    jw_kv_arr(&w, "scenes");
    for (int si = 0; si < RENDER_SCENE_COUNT; si++) {
        const struct scene_result *sr = &res[si];
        if (!sr->done)
            continue;
        jw_obj_begin(&w);
        write_scene_setup_json(&w, si, sr, o);
        jw_kv_arr(&w, "models");
        for (int mi = 0; mi < o->nmodels; mi++)
            write_model_json(&w, si, &sr->models[mi], &o->models[mi], o->threshold);
        jw_arr_end(&w);
        if (sr->he.done)
            write_he_json(&w, &sr->he, o->threshold);
        if (sr->nmeasured)
            write_measured(&w, sr);
        write_timings_json(&w, sr);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    rdoc_json_rows_member(&w, d);
    rdoc_delete(d);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

void render_print_scene(const struct scene_result *sr)
{
    printf("%s: %s", render_scene_names[sr->kind], sr->source);
    if (sr->kind != RENDER_SPHERES)
        printf(" (%zu triangles)", sr->triangles);
    printf("\n");
    fflush(stdout);
}

void render_print_model(int scene, const char *label, const struct model_result *mr)
{
    struct image_metrics sm = shown(&mr->metrics);
    /* |model - reference|: absolute radiance first, then relative to the reference's peak (the
       sphere grid's scale); the device-vs-double check is a third figure, of its own peak */
    printf("  %-8s %-12s max |err| %-9.3g radiance (%.3g of ref peak %.3g)  mean %-9.3g psnr %5.1f dB%s  "
           "device vs double %s (%.2g of peak)\n",
           render_scene_names[scene], label, sm.max_abs, render_max_of_peak(&sm), sm.peak_reference, sm.mean_abs,
           isfinite(sm.psnr_db) || sm.nonfinite ? sm.psnr_db : INFINITY, sm.nonfinite ? " (NOT FINITE)" : "", mr->check.within ? "ok" : "OUT OF BOUND",
           mr->check.relative_to_peak);
    fflush(stdout);
}

void render_print_check(const struct scene_result *sr, int nmodels)
{
    double worst = 0;
    int codes = 0, samples = 0, within = 1;
    for (int mi = 0; mi < nmodels; mi++) {
        const struct reference_check *c = &sr->models[mi].check;
        worst = fmax(worst, c->relative_to_peak);
        codes = c->max_code > codes ? c->max_code : codes;
        samples += c->samples;
        within &= c->within;
    }
    printf("  %s: device vs double reference on %d sampled pixels: max |difference| of the specular radiance %.2g of "
           "the peak (bound 1e-3), colours within %d code%s of the exact display curve: %s\n",
           render_scene_names[sr->kind], samples, worst, codes, codes == 1 ? "" : "s",
           within ? "within the bound" : "OUT OF BOUND");
}

void render_print_he(int scene, const struct he_comparison *hc)
{
    printf("  %s: %s against Blinn-Phong fitted to it: n = %.4g, k = %.4g, relative rms residual %.3g (%zu "
           "pixels)\n", render_scene_names[scene], hc->he.label, hc->n_fit, hc->k_fit, hc->rel_rms, hc->fit_pixels);
    for (int k = 0; k < hc->count; k++)
        printf("    %-28s vs He: max %-9.3g mean %-9.3g  vs Blinn-Phong fit: max %.3g\n", hc->e[k].label,
               hc->e[k].metrics.max_abs, hc->e[k].metrics.mean_abs, hc->e[k].max_abs_vs_blinn);
    fflush(stdout);
}

void render_print_measured(int scene, const struct render_measured_result *mr)
{
    printf("  %s: measured material %s (peak radiance %.4g; device lookup vs host on %ld pixels: %.2g of the "
           "peak)\n", render_scene_names[scene], mr->material, mr->peak, mr->check_pixels, mr->check_max_abs_of_peak);
    for (int k = 1; k < mr->count; k++) {
        const struct render_measured_entry *en = &mr->e[k];
        if (!en->fitted)
            printf("    %-22s not fitted\n", en->label);
        else
            printf("    %-22s n %-9.4g ks %-9.4g kd %-9.4g F0 %-7.3g vs measured: max %-9.3g rms %.3g\n", en->label,
                   en->n, en->ks, en->kd, en->f0, en->max_abs, en->rms);
    }
    fflush(stdout);
}

/* A scene's measured comparisons in render.json. */
static void write_measured(struct jw *w, const struct scene_result *sr)
{
    jw_kv_arr(w, "measured");
    for (int m = 0; m < sr->nmeasured; m++) {
        const struct render_measured_result *mr = &sr->measured[m];
        jw_obj_begin(w);
        jw_kv_str(w, "material", mr->material);
        jw_kv_str(w, "quantity", "radiance E (N.L) f of the whole BRDF, |fit - measured| over the foreground");
        jw_kv_num(w, "peak_radiance", mr->peak);
        jw_kv_num(w, "check_max_abs_of_peak", mr->check_max_abs_of_peak);
        jw_kv_int(w, "check_pixels", mr->check_pixels);
        jw_kv_str(w, "check_status", mr->check_max_abs_of_peak <= 1e-3 ? "ok" : "check");
        jw_kv_arr(w, "fits");
        for (int k = 1; k < mr->count; k++) {
            const struct render_measured_entry *en = &mr->e[k];
            jw_obj_begin(w);
            jw_kv_str(w, "fit", en->label);
            jw_kv_bool(w, "fitted", en->fitted);
            if (!en->fitted) {   /* nothing drawn: the fit did not converge (measured.json says why) */
                jw_kv_str(w, "status", "not fitted");
                jw_obj_end(w);
                continue;
            }
            jw_kv_num(w, "n", en->n);
            jw_kv_num(w, "ks", en->ks);
            jw_kv_num(w, "kd", en->kd);
            if (k > 1)   /* Cook-Torrance only */
                jw_kv_num(w, "f0", en->f0);
            jw_kv_num(w, "max_abs", en->max_abs);
            jw_kv_num(w, "rms", en->rms);
            jw_obj_end(w);
        }
        jw_arr_end(w);
        jw_obj_end(w);
    }
    jw_arr_end(w);
}

void render_print_timings(const struct scene_result *sr)
{
    for (int ti = 0; ti < sr->ntimings; ti++) {
        const struct size_timing *st = &sr->timings[ti];
        printf("  %s %dx%d: copy %.0f Mpixel/s (%.1f GB/s)\n", render_scene_names[sr->kind], st->w, st->h,
               mpix(st, st->copy_med),
               (double)st->w * st->h * RENDER_DEVICE_BYTES_PER_PIXEL / st->copy_med * 1e-9);
        for (int k = 0; k < st->nentries; k++) {
            const struct timed_entry *te = &st->entries[k];
            const struct timed_entry *re = reference_entry(st, te);
            printf("    %-34s %8.1f Mpixel/s  %5.1f%% of copy  %5.2fx vs %s\n", te->name,
                   mpix(st, te->med), 100.0 * te->copy_med / te->med,
                   re ? re->med / te->med : NAN, re ? re->name : "-");
        }
    }
    fflush(stdout);
}
