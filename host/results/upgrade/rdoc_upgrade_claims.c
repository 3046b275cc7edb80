/* rdoc_upgrade_claims.c - claims.json (brdfbench.claims/1), q_sweep.json (brdfbench.q_sweep/1)
 * and physical.json (brdfbench.physical/1) as rows (rdoc_upgrade_claims.h). Each function
 * rebuilds, from the members the old layout has, the rows the writer of the version written now
 * builds from memory (reproduce_report.c, pbcost_report.c): the same keys, metrics, texts and
 * context lines, formatted the same way, so that the pages drawn from them (report_claims.c)
 * are the pages that version wrote. */
#include "rdoc_upgrade_claims.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report_claims.h"

/* A string member that becomes a key or an attribute (one line) or a text (lines allowed): no
   other control character, which would reach a terminal or a table. */
static int plain(const struct jr_doc *j, const struct jr_value *obj, const char *key, int lines, char *err,
                 size_t errlen)
{
    const struct jr_value *v = jr_get(obj, key);
    if (!v || v->type != JR_STR)
        return 0;
    for (const char *p = v->str; *p; ++p)
        if (((unsigned char)*p < 0x20 && !(lines && *p == '\n')) || *p == 0x7f)
            return jr_fail(j, v, err, errlen, "\"%s\" holds a control character (accepted: %s, as brdfbench writes it)",
                           key, lines ? "text" : "one line of text");
    return 0;
}

/* ---- brdfbench.claims/1 ------------------------------------------------------------------ */

/* The upgrade of brdfbench.claims/1: the context line "claim grid" (and the physically based
 * models' line when the claims carry their cost rows: the page then holds physical.json's
 * section); a row per claim (key id; attributes kind, source; metrics claimed and measured,
 * neither better nor worse, where each is a single number (not null); texts claim, claimed_text, measured_text, tolerance, verdict, note,
 * method). */
int upgrade_claims_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    static const char *const attrs[] = { "kind", "source" };
    static const char *const texts[] = { "claim", "claimed_text", "measured_text", "tolerance", "verdict", "note",
                                         "method" };
    const struct jr_value *claims;
    if (jr_need(j, &j->root, "claims", JR_ARR, &claims, err, errlen))
        return 2;
    const struct jr_value *grid = jr_get(jr_get(&j->root, "context"), "grid");
    char buf[RD_TEXT];
    snprintf(buf, sizeof buf, "n step %g, %ld samples per zone", jr_num_or_nan(grid, "n_step"),
             (long)jr_num_or_nan(grid, "samples_per_zone"));
    rd_ctx_put(&d->ctx, "claim grid", buf);
    for (size_t i = 0; i < claims->count; ++i) {
        const struct jr_value *c = &claims->items[i];
        const char *id;
        if (jr_need_str(j, c, "id", &id, err, errlen) || plain(j, c, "id", 0, err, errlen) ||
            plain(j, c, "kind", 0, err, errlen) || plain(j, c, "source", 0, err, errlen))
            return 2;
        /* the claims run measured the physically based models' cost: its page has their section */
        size_t len = strlen(id);
        if (len > 14 && strcmp(id + len - 14, "-physical-cost") == 0)
            rd_ctx_put(&d->ctx, REPORT_CLAIMS_PHYSICAL_CTX, "physical.json");
        struct rd_row *r = rdoc_row(d, "", id);
        if (!r)
            return 0;
        rd_row_key(r, "id", NULL, id);
        for (size_t k = 0; k < sizeof attrs / sizeof attrs[0]; ++k)
            rd_row_attr(r, attrs[k], jr_str_or(c, attrs[k], ""));
        static const char *const figs[] = { "claimed", "measured" };
        for (size_t k = 0; k < sizeof figs / sizeof figs[0]; ++k) {
            const struct jr_value *v = jr_get(c, figs[k]);
            if (v && v->type == JR_NUM && fabs(v->num) <= RD_MAX_VALUE)
                rd_row_metric(d, r, figs[k], "1", RD_NEITHER, 0, v->num);
            else if (v && v->type != JR_NULL)
                return jr_fail(j, v, err, errlen, "\"%s\" is not a number (accepted: a number in [-1e+100, 1e+100], "
                               "or null when the claim is not a single number)", figs[k]);
        }
        for (size_t k = 0; k < sizeof texts / sizeof texts[0]; ++k) {
            if (plain(j, c, texts[k], 1, err, errlen))
                return 2;
            rd_row_text(d, r, texts[k], jr_str_or(c, texts[k], ""));
        }
    }
    return 0;
}

/* ---- brdfbench.q_sweep/1 ----------------------------------------------------------------- */

/* An array of figures of the layout (one per Q): numbers or null; an error (lower) in
   [0, RD_MAX_VALUE], any other within +-RD_MAX_VALUE. The whole file is not checked by
   compare's rule (its arrays under error names are the layout's), so each is checked here. */
static int figures(const struct jr_doc *j, const char *key, int error, size_t want, double **out, char *err,
                   size_t errlen)
{
    size_t n = 0;
    if (jr_need_num_array(j, &j->root, key, out, &n, err, errlen))
        return 2;
    const struct jr_value *a = jr_get(&j->root, key);
    if (n != want)
        return jr_fail(j, a, err, errlen, "\"%s\" holds %zu values, \"Q\" %zu (accepted: one per Q)", key, n, want);
    for (size_t i = 0; i < n; ++i) {
        double v = (*out)[i];
        if (isnan(v) || (error ? v >= 0 && v <= RD_MAX_VALUE : fabs(v) <= RD_MAX_VALUE))
            continue;
        return jr_fail(j, &a->items[i], err, errlen, "\"%s\" holds %.6g (accepted: %s, or null when not measured)", key,
                       v, error ? "an error in [0, 1e+100]" : "a number in [-1e+100, 1e+100]");
    }
    return 0;
}

/* The upgrade of brdfbench.q_sweep/1: the context line "Q grid"; the texts model, maxima,
 * max_abs_what; a row per Q (key model "fq:Q=Q"; metrics Q, max_rel, max_abs,
 * max_abs_attenuation, max_rel_at_n), cq2's row (f2: max_rel, max_abs, text what) and the row of
 * the minimising Q (Q, max_rel, max_abs, host_max_rel, text method). */
int upgrade_q_sweep_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    static const struct {
        const char *name;
        int error;
    } cols[] = { { "max_rel", 1 }, { "max_abs", 1 }, { "max_abs_attenuation", 1 }, { "max_rel_at_n", 0 } };
    enum { NCOLS = sizeof cols / sizeof cols[0] };
    double *q = NULL, *col[NCOLS] = { NULL };
    size_t nq = 0;
    int rc = 2;
    const struct jr_value *grid = jr_get(jr_get(&j->root, "context"), "grid");
    const struct jr_value *f2 = jr_get(&j->root, "f2"), *best = jr_get(&j->root, "best");
    if (!grid || grid->type != JR_OBJ || !f2 || f2->type != JR_OBJ || !best || best->type != JR_OBJ) {
        jr_fail(j, &j->root, err, errlen, "no context grid, \"f2\" or \"best\" object (accepted: q_sweep.json as "
                "brdfbench writes it)");
        return 2;
    }
    if (jr_need_num_array(j, &j->root, "Q", &q, &nq, err, errlen))
        return 2;
    for (int k = 0; k < NCOLS; ++k)
        if (figures(j, cols[k].name, cols[k].error, nq, &col[k], err, errlen))
            goto done;
    static const char *const words[] = { "model", "max_abs_what" };
    for (size_t k = 0; k < sizeof words / sizeof words[0]; ++k)
        if (plain(j, &j->root, words[k], 1, err, errlen))
            goto done;
    if (plain(j, grid, "maxima", 1, err, errlen) || plain(j, f2, "what", 1, err, errlen) ||
        plain(j, best, "method", 1, err, errlen))
        goto done;
    char buf[RD_TEXT];
    snprintf(buf, sizeof buf, "Q = %g..%g step %g, n in [%g, %g] step %g, %ld samples per zone",
             jr_num_or_nan(grid, "q_min"), jr_num_or_nan(grid, "q_max"), jr_num_or_nan(grid, "q_step"),
             jr_num_or_nan(grid, "n_min"), jr_num_or_nan(grid, "n_max"), jr_num_or_nan(grid, "n_step"),
             (long)jr_num_or_nan(grid, "samples_per_zone"));
    rd_ctx_put(&d->ctx, "Q grid", buf);
    rdoc_text(d, "model", jr_str_or(&j->root, "model", ""));
    rdoc_text(d, "maxima", jr_str_or(grid, "maxima", ""));
    rdoc_text(d, "max_abs_what", jr_str_or(&j->root, "max_abs_what", ""));
    for (size_t i = 0; i < nq; ++i) {
        snprintf(buf, sizeof buf, "fq:Q=%.10g", q[i]);
        struct rd_row *r = rdoc_row(d, "", buf);
        if (!r)
            break;
        rd_row_key(r, "model", NULL, buf);
        rd_row_metric(d, r, "Q", "1", RD_NEITHER, 0, q[i]);
        for (int k = 0; k < NCOLS; ++k)
            rd_row_metric(d, r, cols[k].name, "1", cols[k].error ? RD_LOWER : RD_NEITHER, 0, col[k][i]);
    }
    struct rd_row *r = rdoc_row(d, "", "cq2");
    if (r) {
        rd_row_key(r, "model", NULL, "cq2 (f2 of paper 2)");
        rd_row_metric(d, r, "max_rel", "1", RD_LOWER, 0, jr_num_or_nan(f2, "max_rel"));
        rd_row_metric(d, r, "max_abs", "1", RD_LOWER, 0, jr_num_or_nan(f2, "max_abs"));
        rd_row_text(d, r, "what", jr_str_or(f2, "what", ""));
    }
    if ((r = rdoc_row(d, "", "fq")) != NULL) {
        rd_row_key(r, "model", NULL, "fq at the best Q");
        rd_row_metric(d, r, "Q", "1", RD_NEITHER, 0, jr_num_or_nan(best, "Q"));
        rd_row_metric(d, r, "max_rel", "1", RD_LOWER, 0, jr_num_or_nan(best, "max_rel"));
        rd_row_metric(d, r, "max_abs", "1", RD_LOWER, 0, jr_num_or_nan(best, "max_abs"));
        rd_row_metric(d, r, "host_max_rel", "1", RD_LOWER, 0, jr_num_or_nan(best, "host_max_rel"));
        rd_row_text(d, r, "method", jr_str_or(best, "method", ""));
    }
    rc = 0;
done:
    free(q);
    for (int k = 0; k < NCOLS; ++k)
        free(col[k]);
    return rc;
}

/* ---- brdfbench.physical/1 ---------------------------------------------------------------- */

/* He's terms: a row per angle with the mirror and off-mirror counts per sigma0 / lambda. */
static int he_terms(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    const struct jr_value *he = jr_get(&j->root, "he_terms");
    const struct jr_value *theta = jr_get(he, "theta_deg"), *ratio = jr_get(he, "sigma0_over_lambda");
    const struct jr_value *mirror = jr_get(he, "mirror"), *off = jr_get(he, "off_mirror");
    if (!theta || theta->type != JR_ARR || !ratio || ratio->type != JR_ARR || !mirror || mirror->type != JR_ARR ||
        !off || off->type != JR_ARR || mirror->count != theta->count || off->count != theta->count)
        return jr_fail(j, he ? he : &j->root, err, errlen, "\"he_terms\" without its theta_deg, sigma0_over_lambda, "
                       "mirror and off_mirror tables (accepted: physical.json as brdfbench writes it)");
    for (size_t i = 0; i < theta->count; ++i) {
        const struct jr_value *mi = &mirror->items[i], *oi = &off->items[i];
        if (theta->items[i].type != JR_NUM || mi->type != JR_ARR || oi->type != JR_ARR || mi->count != ratio->count ||
            oi->count != ratio->count)
            return jr_fail(j, mi, err, errlen, "a row of He's terms that is not one number per sigma0/lambda");
        struct rd_row *r = rdoc_row(d, "", "he");
        if (!r)
            return 0;
        char buf[64];
        rd_row_key(r, "table", NULL, "He terms");
        snprintf(buf, sizeof buf, "%g deg", theta->items[i].num);
        rd_row_key(r, "theta", NULL, buf);
        for (size_t k = 0; k < ratio->count; ++k) {
            if (ratio->items[k].type != JR_NUM || mi->items[k].type != JR_NUM || oi->items[k].type != JR_NUM)
                return jr_fail(j, &mi->items[k], err, errlen, "He's terms: a value that is not a number");
            char name[RD_NAME];
            snprintf(name, sizeof name, "terms_mirror@%g", ratio->items[k].num);
            rd_row_metric(d, r, name, "1", RD_NEITHER, 0, mi->items[k].num);
            snprintf(name, sizeof name, "terms_off@%g", ratio->items[k].num);
            rd_row_metric(d, r, name, "1", RD_NEITHER, 0, oi->items[k].num);
        }
    }
    return 0;
}

/* The upgrade of brdfbench.physical/1: the context lines n, reps and check_points, the text
 * lookup_note where the file has it; a row per cost row (key model; attributes evaluates,
 * physically_based; evaluations_per_s timed, its range from the slowest and fastest launches
 * and its normalised repetitions; the ratios, the check, the albedo and He's terms where
 * written; texts vs_fq2, vs_phong, check_status), then He's terms table by angle. */
int upgrade_physical_v1(const struct jr_doc *j, struct rdoc *d, char *err, size_t errlen)
{
    static const struct {
        const char *name;
        int direction;
    } figs[] = { { "ratio_to_fq2", RD_NEITHER }, { "ratio_to_phong", RD_NEITHER }, { "ratio_to_pow", RD_NEITHER },
                 { "check_max_abs_of_peak", RD_LOWER }, { "albedo_normal_incidence", RD_NEITHER },
                 { "he_terms_mean", RD_NEITHER }, { "he_terms_max", RD_NEITHER } };
    const struct jr_value *cost, *rows;
    if (jr_need(j, &j->root, "cost", JR_OBJ, &cost, err, errlen) || jr_need(j, cost, "rows", JR_ARR, &rows, err, errlen))
        return 2;
    char buf[64];
    snprintf(buf, sizeof buf, "%g", jr_num_or_nan(cost, "n"));
    rd_ctx_put(&d->ctx, "n", buf);
    snprintf(buf, sizeof buf, "%.0f", jr_num_or_nan(cost, "reps"));
    rd_ctx_put(&d->ctx, "reps", buf);
    snprintf(buf, sizeof buf, "%.0f", rows->count ? jr_num_or_nan(&rows->items[0], "check_points") : NAN);
    rd_ctx_put(&d->ctx, "check_points", buf);
    if (plain(j, &j->root, "lookup_note", 1, err, errlen))
        return 2;
    if (jr_get(&j->root, "lookup_note"))
        rdoc_text(d, "lookup_note", jr_str_or(&j->root, "lookup_note", ""));
    for (size_t i = 0; i < rows->count; ++i) {
        const struct jr_value *row = &rows->items[i];
        const char *model;
        if (jr_need_str(j, row, "model", &model, err, errlen) || plain(j, row, "evaluates", 0, err, errlen) ||
            plain(j, row, "status", 0, err, errlen) || plain(j, jr_get(row, "vs_fq2"), "verdict", 0, err, errlen) ||
            plain(j, jr_get(row, "vs_phong"), "verdict", 0, err, errlen))
            return 2;
        struct rd_row *r = rdoc_row(d, "", model);
        if (!r)
            return 0;
        rd_row_key(r, "model", NULL, model);
        rd_row_attr(r, "evaluates", jr_str_or(row, "evaluates", ""));
        const struct jr_value *pb = jr_get(row, "physically_based");
        rd_row_attr(r, "physically_based", pb && pb->type == JR_BOOL && pb->num ? "true" : "false");
        struct rd_metric *m = rd_row_metric(d, r, "evaluations_per_s", "1/s", RD_HIGHER, 1,
                                            jr_num_or_nan(row, "evaluations_per_s"));
        if (m) {
            double max_s = jr_num_or_nan(row, "max_s");
            m->lo = max_s > 0 ? jr_num_or_nan(row, "evaluations_per_launch") / max_s : NAN;
            m->hi = jr_num_or_nan(row, "evaluations_per_s_fastest");
            double *norm = NULL;
            size_t n = 0;
            if (jr_get(row, "normalised_reps") &&
                jr_need_num_array(j, row, "normalised_reps", &norm, &n, err, errlen))
                return 2;
            rd_metric_normalised(d, m, norm, (int)n, 0);
            free(norm);
        }
        for (size_t k = 0; k < sizeof figs / sizeof figs[0]; ++k)
            if (jr_get(row, figs[k].name))
                rd_row_metric(d, r, figs[k].name, "1", figs[k].direction, 0, jr_num_or_nan(row, figs[k].name));
        rd_row_text(d, r, "vs_fq2", jr_str_or(jr_get(row, "vs_fq2"), "verdict", "?"));
        rd_row_text(d, r, "vs_phong", jr_str_or(jr_get(row, "vs_phong"), "verdict", "?"));
        rd_row_text(d, r, "check_status", jr_str_or(row, "status", ""));
    }
    return he_terms(j, d, err, errlen);
}
