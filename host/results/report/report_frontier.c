/* report_frontier.c - the "Which lobe to ship" page from frontier.json's rows (report_frontier.h). */
#include "report_frontier.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One model's figures as the page uses them. */
struct fr_model {
    const char *label, *kind;
    double max_rel[2], max_abs[2];   /* [n from 2, n from 16] */
    double rate[2][3];               /* [uniform, varying][min, median, max] */
    double psnr;
    int on_front;
};

/* A figure as a file gives it back: a NaN of either sign is null there, read as NAN (so a page
   made from the rows in memory prints "nan" where the one made from the file does). */
static double fig(double v) { return isnan(v) ? NAN : v; }

static void rate_of(const struct rd_row *r, const char *name, double out[3])
{
    const struct rd_metric *m = rd_row_find(r, name);
    out[0] = m ? fig(m->lo) : NAN;
    out[1] = m ? fig(m->value) : NAN;
    out[2] = m ? fig(m->hi) : NAN;
}

static void model_of(const struct rd_row *r, struct fr_model *m)
{
    static const char *const ranges[2] = { "n_2_1000", "n_16_1000" };
    const char *label = rd_row_key_value(r, "model"), *kind = rd_row_key_value(r, "kind");
    m->label = label ? label : r->label;
    m->kind = kind ? kind : "";
    for (int k = 0; k < 2; ++k) {
        char name[RD_NAME];
        snprintf(name, sizeof name, "%s.max_rel", ranges[k]);
        m->max_rel[k] = fig(rd_row_value(r, name));
        snprintf(name, sizeof name, "%s.max_abs", ranges[k]);
        m->max_abs[k] = fig(rd_row_value(r, name));
    }
    rate_of(r, FRONTIER_RATE_UNIFORM, m->rate[0]);
    rate_of(r, FRONTIER_RATE_VARYING, m->rate[1]);
    m->psnr = rd_row_value(r, "psnr_db");
    m->on_front = rd_row_value(r, "on_front") == 1.0;
}

int report_frontier_drawable(const struct rdoc *d)
{
    for (int i = 0; i < d->nrows; ++i) {
        double v = rd_row_value(&d->rows[i], FRONTIER_RATE_UNIFORM);
        if (isfinite(v) && v > 0)
            return 1;
    }
    return 0;
}

/* The most accurate non-reference model (least max delta, then least max Delta) whose rate
   is at least `budget` (its max rate >= budget: spreads again); -1 if none. */
static int best_within(const struct fr_model *m, int count, double budget, int range)
{
    int best = -1;
    for (int i = 0; i < count; ++i) {
        if (strcmp(m[i].kind, "reference") == 0 || !isfinite(m[i].max_rel[range]) || !isfinite(m[i].rate[0][2]))
            continue;
        if (budget > 0 && m[i].rate[0][2] < budget)
            continue;
        if (best < 0 || m[i].max_rel[range] < m[best].max_rel[range] ||
            (m[i].max_rel[range] == m[best].max_rel[range] && m[i].max_abs[range] < m[best].max_abs[range]))
            best = i;
    }
    return best;
}

/* A context line that is a count ("rounds", "reps"), or 0. */
static int ctx_count(const struct rdoc *d, const char *key)
{
    const char *v = rd_ctx_get(&d->ctx, key);
    return v ? atoi(v) : 0;
}

int report_frontier_page(struct md_buf *b, const struct rdoc *d)
{
    struct fr_model *m = calloc((size_t)(d->nrows > 0 ? d->nrows : 1), sizeof *m);
    if (!m)
        return -1;
    int count = d->nrows, fq2 = -1;
    for (int i = 0; i < count; ++i) {
        model_of(&d->rows[i], &m[i]);
        if (fq2 < 0 && strcmp(m[i].label, "fq2") == 0)
            fq2 = i;
    }
    md_printf(b, "Cost is the device's evaluations/s with n uniform (the median over %d rounds over every model of "
                 "each round's median of %d launches; spreads over the rounds that overlap count as equal), "
                 "accuracy the largest epicentre delta and attenuation Delta (frontier.json, frontier.csv, "
                 "frontier_max_rel.png, frontier_max_abs.png).\n\n", ctx_count(d, "rounds"), ctx_count(d, "reps"));
    md_printf(b, "| model | kind | front | evals/s (uniform) | evals/s (varying) | max delta, n >= 2 | max Delta, n >= 2 "
                 "| max delta, n >= 16 | max Delta, n >= 16 | teapot PSNR (dB) |\n");
    md_printf(b, "|---|---|---|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < count; ++i) {
        md_printf(b, "| %s | %s | %s | %.3g | %.3g | %.4f%% | %.4f | %.4f%% | %.4f | ", m[i].label, m[i].kind,
                  m[i].on_front ? "**yes**" : "", m[i].rate[0][1], m[i].rate[1][1], 100 * m[i].max_rel[0],
                  m[i].max_abs[0], 100 * m[i].max_rel[1], m[i].max_abs[1]);
        if (isfinite(m[i].psnr))
            md_printf(b, "%.1f |\n", m[i].psnr);
        else
            md_printf(b, "%s |\n", rd_row_text_or(&d->rows[i], "psnr_reason", ""));
    }
    md_printf(b, "\nSources (brdfbench list; docs/frontier.md has the formulas and the operation counts):\n\n");
    for (int i = 0; i < count; ++i) {
        md_printf(b, "- `%s`: ", m[i].label);
        md_cell_text(b, rd_row_text_or(&d->rows[i], "source", ""));
        md_printf(b, "\n");
    }
    md_printf(b, "\nThe front: ");
    for (int i = 0, k = 0; i < count; ++i)
        if (m[i].on_front)
            md_printf(b, "%s%s", k++ ? ", " : "", m[i].label);
    md_printf(b, ".\n\n");
    if (fq2 >= 0 && isfinite(m[fq2].rate[0][0])) {
        double fq2_lo = m[fq2].rate[0][0];
        double budgets[3] = { fq2_lo, 0.25 * fq2_lo, 0.0 };
        const char *names[3] = { "at least fq2's rate", "at least a quarter of fq2's rate", "any cost" };
        md_printf(b, "The most accurate approximation (least max delta, then least max Delta; the references excluded) "
                     "for a budget of evaluations/s:\n\n| budget | n from 2 | n from 16 |\n|---|---|---|\n");
        for (int k = 0; k < 3; ++k) {
            md_printf(b, "| %s |", names[k]);
            for (int range = 0; range < 2; ++range) {
                int i = best_within(m, count, budgets[k], range);
                if (i < 0)
                    md_printf(b, " none |");
                else
                    md_printf(b, " %s (%.4f%%, %.4f; %.3g/s) |", m[i].label, 100 * m[i].max_rel[range],
                              m[i].max_abs[range], m[i].rate[0][1]);
            }
            md_printf(b, "\n");
        }
    } else {
        md_printf(b, "fq2 is not in this run (or its rate is missing): no budgets relative to it.\n");
    }
    if (report_frontier_drawable(d))
        md_printf(b, "\n![evaluations/s against max delta](frontier_max_rel.png)\n"
                     "![evaluations/s against max Delta](frontier_max_abs.png)\n");
    else
        md_printf(b, "\nThe plots of evaluations/s against max delta and max Delta are not drawn: no model has a "
                     "measured rate.\n");
    free(m);
    return b->failed ? -1 : 0;
}
