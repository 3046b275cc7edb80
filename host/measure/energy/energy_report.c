/* energy_report.c - energy.json and the printed tables of the energy checks (energy.c
 * measures them into struct energy_summary; this file writes them). */
#include "energy_report.h"

#include "context.h"
#include "exitcodes.h"
#include "jsonw.h"
#include "outdir.h"
#include "rdoc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The keys of a worst pair's members: n, N, L, V and the value both ways. The two reciprocity
 * sections write the same members under their own names. */
struct worst_pair_keys {
    const char *n, *nrm, *l, *v, *lv, *vl;
};
static const struct worst_pair_keys recip_keys = { "n", "N", "L", "V", "f_LV", "f_VL" };
static const struct worst_pair_keys pass_keys = { "worst_n", "worst_N", "worst_L", "worst_V", "worst_S_LV",
                                                  "worst_S_VL" };

/* The pair a reciprocity check found worst: its n, its directions and the value each way. */
static void jw_worst_pair(struct jw *w, const struct worst_pair_keys *k, double n, const double *nrm,
                          const double *l, const double *v, double lv, double vl)
{
    jw_kv_num(w, k->n, n);
    jw_kv_nums(w, k->nrm, nrm, 3);
    jw_kv_nums(w, k->l, l, 3);
    jw_kv_nums(w, k->v, v, 3);
    jw_kv_num(w, k->lv, lv);
    jw_kv_num(w, k->vl, vl);
}

static void jw_recip(struct jw *w, const char *key, const struct recip_worst *r)
{
    jw_kv_obj(w, key);
    jw_kv_num(w, "max_diff_of_peak", r->diff);
    if (r->eval_error > 0)
        jw_kv_num(w, "max_eval_error_of_peak", r->eval_error);
    jw_worst_pair(w, &recip_keys, r->n, r->nrm, r->l, r->v, r->f_lv, r->f_vl);
    jw_obj_end(w);
}

static const char *mode_name(int mode)
{
    switch (mode) {
    case ALBEDO_PSI: return "lobe f(cos psi) around R";
    case ALBEDO_HALF: return "lobe f(cos theta_h) as the BRDF";
    case ALBEDO_MICRO: return "D / (4 cos theta_i cos theta_o), F = G = 1";
    case ALBEDO_DCOS: return "D cos theta_h over the whole half-vector hemisphere";
    }
    return "?";
}

/* One model of energy.json's "albedo": its table, maximum and normal incidence. */
static void json_albedo_model(struct jw *w, const struct energy_summary *sum, const struct energy_model_summary *ms)
{
    int cols = ms->cols;
    jw_obj_begin(w);
    jw_kv_str(w, "model", ms->spec.label);
    jw_kv_str(w, "integrand", mode_name(ms->mode));
    jw_kv_arr(w, "albedo");
    for (int i = 0; i < ENERGY_N_COUNT; ++i) {
        jw_arr_begin(w);
        for (int j = 0; j < cols; ++j)
            jw_num(w, ms->albedo[i * cols + j]);
        jw_arr_end(w);
    }
    jw_arr_end(w);
    jw_kv_num(w, "max_albedo", ms->max_albedo);
    jw_kv_num(w, "max_at_n", ms->max_at_n);
    jw_kv_num(w, "max_at_theta_i_deg", ms->max_at_theta_deg);
    jw_kv_num(w, "refine_change", ms->refine_change);
    jw_kv_arr(w, "normal_incidence");
    for (int i = 0; i < ENERGY_N_COUNT; ++i) {
        double dev = ms->albedo[i * cols];
        jw_obj_begin(w);
        jw_kv_num(w, "n", ms->normal_n[i]);
        jw_kv_num(w, "device", dev);
        if (ms->normal_derivation[i]) {
            jw_kv_num(w, "closed_form", ms->normal_closed[i]);
            jw_kv_num(w, "diff", fabs(dev - ms->normal_closed[i]));
            jw_kv_str(w, "derivation", ms->normal_derivation[i]);
        } else {
            jw_kv_num(w, "closed_form", NAN);
            jw_kv_str(w, "reason", "no closed form derived");
        }
        jw_obj_end(w);
    }
    jw_arr_end(w);
    jw_kv_num(w, "normal_incidence_max_diff", ms->normal_max_diff);
    jw_kv_bool(w, "energy_conserving", ms->max_albedo <= 1.0 + sum->quadrature_tolerance);
    if (ms->mode == ALBEDO_MICRO)
        jw_kv_str(w, "note", "D alone, without the masking term G: the albedo grows towards grazing "
                             "incidence; the distribution's own check is its normalisation (D cos)");
    jw_obj_end(w);
}

static void json_albedo(struct jw *w, const struct energy_summary *sum)
{
    jw_kv_obj(w, "albedo");
    jw_kv_str(w, "definition", "a(theta_i) = int over the upper hemisphere of f(L, V) cos(theta_o) dw_o, "
                               "N = z, L = (sin theta_i, 0, cos theta_i)");
    jw_kv_str(w, "quadrature", "device (float): composite Gauss-Legendre, 16 nodes per panel, in the lobe's polar "
                               "angle (psi around R, or theta_h around N), panels from x_e(n)/4 doubling to pi/2 "
                               "plus the integrand's kinks; azimuth exact (psi) or 1024-point trapezoid (theta_h); "
                               "polar sum in double on the host");
    jw_kv_num(w, "tolerance", sum->quadrature_tolerance);
    jw_kv_nums(w, "n", sum->table_n, ENERGY_N_COUNT);
    jw_kv_arr(w, "theta_i_deg");
    for (int j = 0; j < ENERGY_THETA_COUNT; ++j)
        jw_num(w, 5.0 * j);
    jw_arr_end(w);
    jw_kv_arr(w, "models");
    for (int mi = 0; mi < sum->count; ++mi)
        json_albedo_model(w, sum, &sum->models[mi]);
    jw_arr_end(w);
    jw_obj_end(w);
}

/* A reciprocity section of energy.json: its pairs, what it compares, then a record per model,
 * written by `model`. */
static void json_recip_section(struct jw *w, const char *name, long pairs, const char *what, int count,
                               const struct energy_summary *sum,
                               void (*model)(struct jw *w, const struct energy_summary *sum, int i))
{
    jw_kv_obj(w, name);
    jw_kv_int(w, "pairs", pairs);
    jw_kv_str(w, "what", what);
    jw_kv_arr(w, "models");
    for (int i = 0; i < count; ++i) {
        jw_obj_begin(w);
        model(w, sum, i);
        jw_obj_end(w);
    }
    jw_arr_end(w);
    jw_obj_end(w);
}

static void json_reciprocity_model(struct jw *w, const struct energy_summary *sum, int i)
{
    const struct recip_summary *rs = &sum->recip[i];
    jw_kv_str(w, "model", rs->spec.label);
    jw_kv_str(w, "lobe", rs->spec.info->lobe == LOBE_PSI ? "psi" : "theta_h");
    jw_recip(w, "device_worst", &rs->device);
    jw_recip(w, "host_worst", &rs->host);
}

static void json_reciprocity_pass_model(struct jw *w, const struct energy_summary *sum, int i)
{
    const struct recip_pass_summary *q = &sum->pass[i];
    jw_kv_str(w, "model", q->spec.label);
    jw_kv_int(w, "shading_mode", q->mode);
    jw_kv_int(w, "pairs_lit_both_ways", q->lit);
    jw_kv_num(w, "device_max_rel_diff", q->device_worst);
    jw_kv_num(w, "host_max_rel_diff", q->host_worst);
    jw_worst_pair(w, &pass_keys, q->n, q->nrm, q->l, q->v, q->s_lv, q->s_vl);
}

/* The two reciprocity sections: the lobes' formulas, then the image pass. */
static void json_reciprocity(struct jw *w, const struct energy_summary *sum)
{
    json_recip_section(w, "reciprocity", sum->recip_pairs,
                       "f(L, V) against f(V, L) at random (N, L, V), L and V in N's hemisphere (half of the V "
                       "within 3 x_e(n) of L's mirror direction), n log-uniform in [2, 1000]; the lobe's cosine "
                       "computed as an image pass does (R = 2(N.L)N - L, or H = normalize(L + V)); "
                       "difference relative to the lobe's peak f(c = 1, n)",
                       sum->recip_count, sum, json_reciprocity_model);
    json_recip_section(w, "reciprocity_image_pass", sum->recip_pairs,
                       "kernels/shade.cl (the image pass) shades each pixel twice with eye and point light "
                       "swapped; S = specular / (E (N.L) ks) compared, relative to the larger value (floor: 1e-6 "
                       "of the lobe's peak); Cook-Torrance for the microfacet models; host: the pass's double "
                       "reference (render_shade_ref)",
                       sum->pass_count, sum, json_reciprocity_pass_model);
}

/* energy.json's rows, built from the summary in memory: a row per model and integrand of the
   albedo tables (keys check "albedo", model, integrand: the largest albedo with the n and
   theta_i where it is reached, neither better higher nor lower; the change when the quadrature
   is refined and the largest difference from the closed form at normal incidence, errors), a
   row per model of the lobes' reciprocity (keys check "reciprocity", model; attribute lobe: the
   worst |f(L,V) - f(V,L)| of the peak on the device with its n and its evaluation error, and on
   the host) and a row per model of the image pass's (keys check "reciprocity_image_pass", model,
   shading mode: the worst relative difference on the device and on the host, the pairs lit
   both ways). The context: the quadrature's tolerance and the reciprocity's pairs per model. */
static void energy_rows(struct rdoc *d, const struct energy_summary *sum)
{
    char text[RD_TEXT];
    snprintf(text, sizeof text, "%.17g", sum->quadrature_tolerance);
    rd_ctx_put(&d->ctx, "energy quadrature tolerance", text);
    snprintf(text, sizeof text, "%ld", sum->recip_pairs);
    rd_ctx_put(&d->ctx, "energy reciprocity pairs", text);
    for (int i = 0; i < sum->count; ++i) {
        const struct energy_model_summary *m = &sum->models[i];
        struct rd_row *r = rdoc_row(d, "", m->spec.label);
        if (!r)
            return;
        rd_row_key(r, "check", NULL, "albedo");
        rd_row_key(r, "model", NULL, m->spec.label);
        rd_row_key(r, "integrand", NULL, mode_name(m->mode));
        rd_row_metric(d, r, "max_albedo", "1", RD_NEITHER, 0, m->max_albedo);
        rd_row_metric(d, r, "max_at_n", "1", RD_NEITHER, 0, m->max_at_n);
        rd_row_metric(d, r, "max_at_theta_i_deg", "deg", RD_NEITHER, 0, m->max_at_theta_deg);
        rd_row_metric(d, r, "refine_change", "1", RD_LOWER, 0, m->refine_change);
        rd_row_metric(d, r, "normal_incidence_max_diff", "1", RD_LOWER, 0, m->normal_max_diff);
    }
    for (int i = 0; i < sum->recip_count; ++i) {
        const struct recip_summary *rs = &sum->recip[i];
        struct rd_row *r = rdoc_row(d, "", rs->spec.label);
        if (!r)
            return;
        rd_row_key(r, "check", NULL, "reciprocity");
        rd_row_key(r, "model", NULL, rs->spec.label);
        rd_row_attr(r, "lobe", rs->spec.info->lobe == LOBE_PSI ? "psi" : "theta_h");
        rd_row_metric(d, r, "device.max_diff_of_peak", "1", RD_LOWER, 0, rs->device.diff);
        rd_row_metric(d, r, "device.at_n", "1", RD_NEITHER, 0, rs->device.n);
        if (rs->device.eval_error > 0)   /* written where the device's values were compared with double */
            rd_row_metric(d, r, "device.max_eval_error_of_peak", "1", RD_LOWER, 0, rs->device.eval_error);
        rd_row_metric(d, r, "host.max_diff_of_peak", "1", RD_LOWER, 0, rs->host.diff);
    }
    for (int i = 0; i < sum->pass_count; ++i) {
        const struct recip_pass_summary *q = &sum->pass[i];
        struct rd_row *r = rdoc_row(d, "", q->spec.label);
        if (!r)
            return;
        rd_row_key(r, "check", NULL, "reciprocity_image_pass");
        rd_row_key(r, "model", NULL, q->spec.label);
        snprintf(text, sizeof text, "%d", q->mode);
        rd_row_key(r, "shading_mode", "mode ", text);
        rd_row_metric(d, r, "device_max_rel_diff", "1", RD_LOWER, 0, q->device_worst);
        rd_row_metric(d, r, "host_max_rel_diff", "1", RD_LOWER, 0, q->host_worst);
        rd_row_metric(d, r, "pairs_lit_both_ways", "1", RD_NEITHER, 0, (double)q->lit);
    }
}

int energy_write(const struct cl_session *s, struct energy_summary *sum, int keep_json, const char *out_dir)
{
    int rc = 0;
    char err[512];
    struct rdoc *d = rdoc_new(ENERGY_SCHEMA, "energy", "energy.json", err, sizeof err);
    if (d) {
        energy_rows(d, sum);
        if (rdoc_built(d, err, sizeof err))
            d = NULL;
    }
    if (!d) {
        fprintf(stderr, "brdfbench: energy.json: %s\n", err);
        return EXIT_RUNTIME;
    }
    struct jw w;
    jw_doc_begin(&w, ENERGY_SCHEMA, s, "");
    jw_obj_end(&w);
    json_albedo(&w, sum);
    json_reciprocity(&w, sum);
    jw_kv_num(&w, "seconds", sum->seconds);
    rdoc_json_rows_member(&w, d);
    rdoc_delete(d);
    jw_obj_end(&w);
    if (keep_json && !w.out.failed) {
        /* the caller may write the text later, beside its own files */
        sum->json = malloc(w.out.len + 2);
        if (sum->json) {
            memcpy(sum->json, w.out.s, w.out.len);
            memcpy(sum->json + w.out.len, "\n", 2);
        }
    }
    if (out_dir) {
        char path[4200];
        path_join(path, sizeof path, out_dir, "energy.json");
        if (jw_write_file(&w, path, err, sizeof err)) {
            fprintf(stderr, "brdfbench: %s\n", err);
            rc = EXIT_RUNTIME;
        }
    }
    jw_free(&w);
    return rc;
}

void energy_print_table(FILE *f, const struct energy_summary *sum)
{
    fprintf(f, "energy: directional albedo on the device, n in {2, 4, 10, 100, 1000}, theta_i 0..85 deg step 5\n");
    fprintf(f, "  %-10s %-48s %10s %7s %6s  %12s  %10s\n", "model", "integrand", "max albedo", "at n", "at deg",
            "normal: |dev-closed|", "refine chg");
    for (int i = 0; i < sum->count; ++i) {
        const struct energy_model_summary *m = &sum->models[i];
        fprintf(f, "  %-10s %-48s %10.6f %7g %6g  %12.3g  %10.3g\n", m->spec.label, mode_name(m->mode), m->max_albedo,
                m->max_at_n, m->max_at_theta_deg, m->normal_max_diff, m->refine_change);
    }
    fprintf(f, "reciprocity: %ld random (N, L, V) per model; worst |f(L,V) - f(V,L)| / peak\n", sum->recip_pairs);
    for (int i = 0; i < sum->recip_count; ++i) {
        const struct recip_summary *r = &sum->recip[i];
        fprintf(f, "  %-22s device (float) %9.3g at n = %-8.4g (its evaluation error %9.3g)  host (double) %9.3g\n",
                r->spec.label, r->device.diff, r->device.n, r->device.eval_error, r->host.diff);
    }
    fprintf(f, "reciprocity of the image pass (kernels/shade.cl, eye and light swapped): worst relative difference\n");
    for (int i = 0; i < sum->pass_count; ++i)
        fprintf(f, "  %-22s mode %d  device %9.3g  host %9.3g  (%ld pairs lit both ways)\n", sum->pass[i].spec.label,
                sum->pass[i].mode, sum->pass[i].device_worst, sum->pass[i].host_worst, sum->pass[i].lit);
}
