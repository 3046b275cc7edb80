/* pbcost_report.c - physical.json with its rows, and the table of the physically based models'
 * cost, He's terms per evaluation and their albedo at normal incidence (pbcost.c measures them;
 * the markdown section is drawn from the rows: report_claims.c). */
#include "pbcost.h"

#include "context.h"
#include "exitcodes.h"
#include "outdir.h"
#include "jsonw.h"
#include "mdbuf.h"
#include "rdoc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const kind_names[6] = { "lobe of R.V", "lobe of N.H", "BRDF of (N, L, V)", "pow(R.V, n)",
                                           "user BRDF (N, L, V)", "table lookup" };
#define PBCOST_LOOKUP_NOTE "a measured material's row is a table lookup (the half/difference angles and three loads " \
                           "from a 17.5 MB table in device memory): its cost is memory bandwidth, not arithmetic"

static void jw_terms(struct jw *w, const char *key, const struct pbcost_result *r,
                     const int t[PBCOST_TERMS_THETA][PBCOST_TERMS_RATIO])
{
    jw_kv_arr(w, key);
    for (int i = 0; i < PBCOST_TERMS_THETA; ++i) {
        jw_arr_begin(w);
        for (int j = 0; j < PBCOST_TERMS_RATIO; ++j)
            jw_int(w, t[i][j]);
        jw_arr_end(w);
    }
    jw_arr_end(w);
    (void)r;
}

/* compare's verdict on a row against another (compare.h, compare_speed_rule). */
static void jw_speed(struct jw *w, const char *key, const struct compare_speed *c)
{
    jw_kv_obj(w, key);
    jw_kv_str(w, "verdict", cmp_verdict_name(c->verdict));
    jw_kv_num(w, "ratio", c->ratio);
    jw_kv_num(w, "ci_lo", c->ci_lo);
    jw_kv_num(w, "ci_hi", c->ci_hi);
    jw_kv_num(w, "p", c->p);
    jw_obj_end(w);
}

/* A cost row's figures, in the order physical.json holds them. */
#define F(KIND, MEMBER, KEY) JW_FIELD(KIND, struct pbcost_row, MEMBER, KEY)
static const struct jw_field row_figures[] = {
    F(JWF_LONG, iters, "iterations"), F(JWF_NUM, evals_per_launch, "evaluations_per_launch"),
    F(JWF_NUM, med_s, "median_s"), F(JWF_NUM, min_s, "min_s"), F(JWF_NUM, max_s, "max_s"),
    F(JWF_NUM, evals_per_s, "evaluations_per_s"), F(JWF_NUM, evals_per_s_fastest, "evaluations_per_s_fastest"),
    F(JWF_NUM, ratio_to_fq2, "ratio_to_fq2"), F(JWF_NUM, ratio_to_phong, "ratio_to_phong"),
    F(JWF_NUM, ratio_to_pow, "ratio_to_pow"), F(JWF_NUM, check_max_abs_of_peak, "check_max_abs_of_peak"),
};
#undef F

int pbcost_write_json(const char *path, const struct cl_session *s, const struct pbcost_result *r,
                      const struct rdoc *rows, char *err, size_t errlen)
{
    struct rdoc *own = rows ? NULL : pbcost_rows(r, err, errlen);
    if (!rows && !own)
        return -1;
    struct jw w;
    jw_doc_begin(&w, PBCOST_SCHEMA, s, "");
    jw_obj_end(&w);
    jw_kv_obj(&w, "cost");
    jw_kv_str(&w, "what", "evaluations per second from full vectors made in registers (kernels/throughput.cl, "
                          "tp_vec_*): per evaluation three normalisations, N.L, N.V, L.V and the model; float16, two "
                          "streams per work-item, outputs summed; the rows timed by the runner in interleaved "
                          "rounds with the pow() row as every round's reference; evaluations_per_s from the median "
                          "launch; the ratios are compare's Hodges-Lehmann estimates on the normalised repetitions, "
                          "each with compare's verdict (vs_fq2, vs_phong: rank test at alpha, the interval, the "
                          "minimum effect)");
    jw_kv_num(&w, "alpha", CMP_DEFAULT_ALPHA);
    jw_kv_num(&w, "minimum_effect", CMP_DEFAULT_THRESHOLD);
    jw_kv_num(&w, "n", r->o.n);
    jw_kv_int(&w, "reps", r->o.reps);
    jw_kv_num(&w, "min_time", r->o.min_time);
    jw_kv_int(&w, "work_items", r->work_items);
    jw_kv_arr(&w, "rows");
    for (int i = 0; i < r->count; ++i) {
        const struct pbcost_row *row = &r->rows[i];
        jw_obj_begin(&w);
        jw_kv_str(&w, "model", row->name);
        jw_kv_str(&w, "evaluates", kind_names[row->kind]);
        jw_kv_bool(&w, "physically_based", row->physical);
        jw_kv_fields(&w, row, JW_FIELDS(row_figures));
        jw_kv_nums(&w, "normalised_reps", row->norm_reps, row->nnorm);
        jw_speed(&w, "vs_fq2", &row->vs_fq2);
        jw_speed(&w, "vs_phong", &row->vs_phong);
        jw_kv_int(&w, "check_points", PBCOST_CHECK_POINTS);
        jw_kv_str(&w, "status", row->status);
        if (row->physical) {
            jw_kv_num(&w, "albedo_normal_incidence", row->albedo_normal);
            jw_kv_num(&w, "albedo_quadrature_error", row->albedo_normal_error);
        }
        if (isfinite(row->terms_mean)) {
            jw_kv_num(&w, "he_terms_mean", row->terms_mean);
            jw_kv_num(&w, "he_terms_max", row->terms_max);
        }
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_obj_end(&w);
    jw_kv_obj(&w, "he_terms");
    jw_kv_str(&w, "what", "terms of He's directional-diffuse sum (stopped past the peak m >= g at the first term "
                          "below 2^-24 of the running sum), double host, rough aluminium's lambda = 0.55 um, "
                          "tau = 1 um, index 0.958 + 6.69i, for sigma0 = ratio x lambda; mirror: theta_i = theta_r = "
                          "theta; off: theta_r = min(theta + 20, 89) degrees in the plane of incidence");
    jw_kv_nums(&w, "theta_deg", r->terms_theta, PBCOST_TERMS_THETA);
    jw_kv_nums(&w, "sigma0_over_lambda", r->terms_ratio, PBCOST_TERMS_RATIO);
    jw_terms(&w, "mirror", r, r->terms_mirror);
    jw_terms(&w, "off_mirror", r, r->terms_off);
    jw_obj_end(&w);
    jw_kv_str(&w, "albedo_what", "white-furnace albedo at normal incidence, 2 pi int f(N, V) cos(theta) sin(theta) "
                                 "dtheta (L = N), GSL adaptive quadrature in double; n as in the cost rows for the "
                                 "microfacet models; He with its uniform-diffuse term and the specular term over its "
                                 "1-degree source");
    if (r->o.nmeasured)
        jw_kv_str(&w, "lookup_note", PBCOST_LOOKUP_NOTE);
    jw_kv_num(&w, "seconds", r->seconds);
    rdoc_json_rows_member(&w, rows ? rows : own);
    rdoc_delete(own);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

struct rdoc *pbcost_rows(const struct pbcost_result *r, char *err, size_t errlen)
{
    struct rdoc *d = rdoc_new(PBCOST_SCHEMA, "physical", "physical.json", err, errlen);
    if (!d)
        return NULL;
    char buf[64];
    snprintf(buf, sizeof buf, "%g", r->o.n);
    rd_ctx_put(&d->ctx, "n", buf);
    snprintf(buf, sizeof buf, "%d", r->o.reps);
    rd_ctx_put(&d->ctx, "reps", buf);
    snprintf(buf, sizeof buf, "%d", PBCOST_CHECK_POINTS);
    rd_ctx_put(&d->ctx, "check_points", buf);
    if (r->o.nmeasured)
        rdoc_text(d, "lookup_note", PBCOST_LOOKUP_NOTE);
    for (int i = 0; i < r->count; ++i) {
        const struct pbcost_row *row = &r->rows[i];
        struct rd_row *x = rdoc_row(d, "", row->name);
        if (!x)
            break;
        rd_row_key(x, "model", NULL, row->name);
        rd_row_attr(x, "evaluates", kind_names[row->kind]);
        rd_row_attr(x, "physically_based", row->physical ? "true" : "false");
        /* the rate of the median launch, its range from the slowest and fastest launches, and
           the repetitions normalised by the pow() row of the same round (compare's basis) */
        struct rd_metric *m = rd_row_metric(d, x, "evaluations_per_s", "1/s", RD_HIGHER, 1, row->evals_per_s);
        if (m) {
            m->lo = row->max_s > 0 ? row->evals_per_launch / row->max_s : NAN;
            m->hi = row->evals_per_s_fastest;
            rd_metric_normalised(d, m, row->norm_reps, row->nnorm, 0);
        }
        /* ratios of rates within the run: figures, not a speed to rank runs by */
        rd_row_metric(d, x, "ratio_to_fq2", "1", RD_NEITHER, 0, row->ratio_to_fq2);
        rd_row_metric(d, x, "ratio_to_phong", "1", RD_NEITHER, 0, row->ratio_to_phong);
        rd_row_metric(d, x, "ratio_to_pow", "1", RD_NEITHER, 0, row->ratio_to_pow);
        rd_row_metric(d, x, "check_max_abs_of_peak", "1", RD_LOWER, 0, row->check_max_abs_of_peak);
        if (row->physical)
            rd_row_metric(d, x, "albedo_normal_incidence", "1", RD_NEITHER, 0, row->albedo_normal);
        if (isfinite(row->terms_mean)) {
            rd_row_metric(d, x, "he_terms_mean", "1", RD_NEITHER, 0, row->terms_mean);
            rd_row_metric(d, x, "he_terms_max", "1", RD_NEITHER, 0, row->terms_max);
        }
        rd_row_text(d, x, "vs_fq2", cmp_verdict_name(row->vs_fq2.verdict));
        rd_row_text(d, x, "vs_phong", cmp_verdict_name(row->vs_phong.verdict));
        rd_row_text(d, x, "check_status", row->status);
    }
    /* He's terms: a row per angle, the mirror and off-mirror counts per sigma0 / lambda */
    for (int i = 0; i < PBCOST_TERMS_THETA; ++i) {
        struct rd_row *x = rdoc_row(d, "", "he");
        if (!x)
            break;
        rd_row_key(x, "table", NULL, "He terms");
        snprintf(buf, sizeof buf, "%g deg", r->terms_theta[i]);
        rd_row_key(x, "theta", NULL, buf);
        for (int j = 0; j < PBCOST_TERMS_RATIO; ++j) {
            char name[RD_NAME];
            snprintf(name, sizeof name, "terms_mirror@%g", r->terms_ratio[j]);
            rd_row_metric(d, x, name, "1", RD_NEITHER, 0, r->terms_mirror[i][j]);
            snprintf(name, sizeof name, "terms_off@%g", r->terms_ratio[j]);
            rd_row_metric(d, x, name, "1", RD_NEITHER, 0, r->terms_off[i][j]);
        }
    }
    return rdoc_built(d, err, errlen) ? NULL : d;
}

void pbcost_print_table(FILE *f, const struct pbcost_result *r)
{
    fprintf(f, "physically based models from full vectors (N, L, V), n = %g, median of %d launches; ratios: "
               "compare's estimates on repetitions normalised by pow() in each round, (verdict):\n", r->o.n, r->o.reps);
    fprintf(f, "  %-22s %-20s %12s %9s %9s %9s %10s %6s %12s\n", "model", "evaluates", "G evals/s", "vs fq2",
            "vs Phong", "vs pow()", "check", "status", "albedo(0)");
    for (int i = 0; i < r->count; ++i) {
        const struct pbcost_row *row = &r->rows[i];
        char alb[32] = "-";   /* a lobe or a user BRDF has no albedo figure */
        if (isfinite(row->albedo_normal))
            snprintf(alb, sizeof alb, "%.6g", row->albedo_normal);
        fprintf(f, "  %-22s %-20s %12.4g %8.3gx %8.3gx %8.3gx %10.2g %6s %12s", row->name, kind_names[row->kind],
                row->evals_per_s * 1e-9, row->ratio_to_fq2, row->ratio_to_phong, row->ratio_to_pow,
                row->check_max_abs_of_peak, row->status, alb);
        if (isfinite(row->terms_mean))
            fprintf(f, "  He terms mean %.1f max %.0f", row->terms_mean, row->terms_max);
        fprintf(f, "\n");
    }
    if (r->o.nmeasured)
        fprintf(f, "  note: %s\n", PBCOST_LOOKUP_NOTE);
}
