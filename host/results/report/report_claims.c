/* report_claims.c - the claims page drawn from rows (report_claims.h). */
#include "report_claims.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* A markdown table cell between its separators. */
static void cell(struct md_buf *b, const char *s)
{
    md_printf(b, " ");
    md_cell_text(b, s);
    md_printf(b, " |");
}

static const char *ctx_or(const struct rdoc *d, const char *key, const char *fallback)
{
    const char *v = d ? rd_ctx_get(&d->ctx, key) : NULL;
    return v ? v : fallback;
}

static const char *key_or(const struct rd_row *r, const char *name, const char *fallback)
{
    const char *v = rd_row_key_value(r, name);
    return v ? v : fallback;
}

void report_physical_section(struct md_buf *b, const struct rdoc *ph)
{
    md_printf(b, "\n## Physically based models: cost, terms, albedo\n\n"
                 "Evaluations per second from full vectors (N, L, V) made in registers, per evaluation three "
                 "normalisations, three dot products and the model (float16, n = %s, the median of %s launches, rows "
                 "interleaved with pow() as every round's reference); ratios are this row's evaluations/s over "
                 "fq2's, Phong's and pow()'s in the same run, compare's estimates on the normalised repetitions, "
                 "with compare's verdict against fq2 and Phong. Check: largest |device - double| over %s random (N, L, V), relative to the sample's peak. "
                 "Albedo: white-furnace albedo at normal incidence (double quadrature).\n\n",
              ctx_or(ph, "n", "?"), ctx_or(ph, "reps", "?"), ctx_or(ph, "check_points", "?"));
    const char *note = rdoc_text_get(ph, "lookup_note");
    if (note)
        md_printf(b, "Note: %s.\n\n", note);
    md_printf(b, "| model | evaluates | G evaluations/s | vs fq2 | vs Phong | vs pow() | check | He terms "
                 "(mean, max) | albedo at normal incidence |\n|---|---|---|---|---|---|---|---|---|\n");
    const struct rd_row *terms = NULL;   /* the first row of He's terms table */
    for (int i = 0; i < ph->nrows; ++i) {
        const struct rd_row *r = &ph->rows[i];
        if (rd_row_key_value(r, "theta")) {
            if (!terms)
                terms = r;
            continue;
        }
        char tm[64] = "", alb[64] = "";
        double mean = rd_row_value(r, "he_terms_mean");
        if (isfinite(mean))
            snprintf(tm, sizeof tm, "%.1f, %.0f", mean, rd_row_value(r, "he_terms_max"));
        if (strcmp(key_or(r, "physically_based", ""), "true") == 0)
            snprintf(alb, sizeof alb, "%.4f", rd_row_value(r, "albedo_normal_incidence"));
        md_printf(b, "| %s | %s | %.3g | %.3gx (%s) | %.3gx (%s) | %.3gx | %.2g %s | %s | %s |\n",
                  key_or(r, "model", r->model), key_or(r, "evaluates", ""), rd_row_value(r, "evaluations_per_s") * 1e-9,
                  rd_row_value(r, "ratio_to_fq2"), rd_row_text_or(r, "vs_fq2", "?"), rd_row_value(r, "ratio_to_phong"),
                  rd_row_text_or(r, "vs_phong", "?"), rd_row_value(r, "ratio_to_pow"),
                  rd_row_value(r, "check_max_abs_of_peak"), rd_row_text_or(r, "check_status", "?"), tm, alb);
    }
    md_printf(b, "\nTerms of He's directional-diffuse sum per evaluation (stopped at float resolution), "
                 "rough aluminium's lambda, tau and index, sigma0 = ratio x lambda; mirror direction / 20 "
                 "degrees past it:\n\n| theta |");
    /* the columns: the ratios named by the first angle's mirror metrics ("terms_mirror@0.01") */
    int ncols = 0;
    for (int m = 0; terms && m < terms->nmetrics; ++m)
        if (strncmp(terms->metrics[m].name, "terms_mirror@", 13) == 0) {
            md_printf(b, " sigma0/lambda = %s |", terms->metrics[m].name + 13);
            ++ncols;
        }
    md_printf(b, "\n|---|");
    for (int j = 0; j < ncols; ++j)
        md_printf(b, "---|");
    md_printf(b, "\n");
    for (int i = 0; i < ph->nrows; ++i) {
        const struct rd_row *r = &ph->rows[i];
        const char *theta = rd_row_key_value(r, "theta");
        if (!theta)
            continue;
        md_printf(b, "| %s |", theta);
        for (int m = 0; m < r->nmetrics; ++m) {
            const char *name = r->metrics[m].name;
            if (strncmp(name, "terms_mirror@", 13) != 0)
                continue;
            char off[RD_NAME + 8];
            snprintf(off, sizeof off, "terms_off@%s", name + 13);
            md_printf(b, " %.0f / %.0f |", r->metrics[m].value, rd_row_value(r, off));
        }
        md_printf(b, "\n");
    }
}

int report_claims_page(struct md_buf *b, const struct rdoc *claims, const struct rdoc *q_sweep,
                       const struct rdoc *physical)
{
    int reproduced = 0, not_reproduced = 0, within_noise = 0;
    for (int i = 0; i < claims->nrows; ++i) {
        const char *v = rd_row_text_or(&claims->rows[i], "verdict", "");
        if (strcmp(v, "reproduced") == 0)
            ++reproduced;
        else if (strcmp(v, "within noise") == 0)
            ++within_noise;
        else
            ++not_reproduced;
    }
    char noise[48] = "";   /* a verdict decided by timings that cannot decide it */
    if (within_noise)
        snprintf(noise, sizeof noise, ", %d within noise", within_noise);
    md_printf(b,
              "# Claims of the papers, re-derived\n\n"
              "%d rows: %d reproduced, %d not reproduced%s. A printed number is reproduced when the measured value is "
              "within one unit of its last printed digit (which accepts rounding or truncation); every other "
              "tolerance is stated in its row. Rows of kind `check` are closed forms the harness itself must meet.\n\n",
              claims->nrows, reproduced, not_reproduced, noise);
    for (int pass = 0; pass < 2; ++pass) {
        md_printf(b, pass == 0 ? "## Claims\n\n" : "\n## Harness checks\n\n");
        md_printf(b, "| id | source | claim | claimed | measured | tolerance | verdict | where / why |\n"
                     "|---|---|---|---|---|---|---|---|\n");
        for (int i = 0; i < claims->nrows; ++i) {
            const struct rd_row *r = &claims->rows[i];
            if ((strcmp(key_or(r, "kind", ""), "claim") == 0) != (pass == 0))
                continue;
            md_printf(b, "|");
            cell(b, key_or(r, "id", r->model));
            cell(b, key_or(r, "source", ""));
            cell(b, rd_row_text_or(r, "claim", ""));
            cell(b, rd_row_text_or(r, "claimed_text", ""));
            cell(b, rd_row_text_or(r, "measured_text", ""));
            cell(b, rd_row_text_or(r, "tolerance", ""));
            md_printf(b, " **");
            md_cell_text(b, rd_row_text_or(r, "verdict", "?"));
            md_printf(b, "** |");
            /* the note, then the method in brackets */
            const char *note = rd_row_text_or(r, "note", "");
            md_printf(b, " ");
            md_cell_text(b, note);
            md_printf(b, "%s(", note[0] ? " " : "");
            md_cell_text(b, rd_row_text_or(r, "method", ""));
            md_printf(b, ") |\n");
        }
    }
    md_printf(b, "\nGrids: claim sweeps %s (both zones), maxima polished in double; Q sweep %s (q_sweep.json).\n",
              ctx_or(claims, "claim grid", "?"), ctx_or(q_sweep, "Q grid", "?"));
    if (physical)
        report_physical_section(b, physical);
    return b->failed ? 3 : 0;
}
