/* reproduce_report.c - the writers of the claims run: the rows of claims.json and q_sweep.json
 * (and physical.json's, pbcost_rows), the files with their rows, claims.md drawn from the same
 * rows (report_claims.h) and the printed table (reproduce.c derives the claims, this file
 * writes them). */
#include "reproduce_report.h"

#include "context.h"
#include "jsonw.h"
#include "mdbuf.h"
#include "rdoc.h"
#include "report_claims.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* q_sweep.json's words, in its layout and in its rows */
#define Q_SWEEP_MODEL "fq:Q=... (f_Q of paper 2) against phong"
#define Q_SWEEP_MAXIMA "device grid, polished in double"
#define Q_SWEEP_MAX_ABS_WHAT "over the whole range x in [0, pi/2]; max_abs_attenuation over the attenuation zone"
#define Q_SWEEP_F2_WHAT "cq2 on the same grid: does not depend on Q"
#define Q_SWEEP_BEST_METHOD "GSL Brent over Q on the exact per-n max delta (integer n of [2, 1000]), bracketed by " \
                            "the sweep's best Q; figures from the device sweep at that Q"

static const char *verdict_text(const struct claim *c)
{
    return c->reproduced ? "reproduced" : c->undecided ? "within noise" : "not reproduced";
}

/* claims.json's rows (report_claims.h): a row per claim with its figures and words. */
static struct rdoc *claims_rows(const struct repro *p, char *err, size_t errlen)
{
    const struct reproduce_report *r = p->r;
    struct rdoc *d = rdoc_new(CLAIMS_SCHEMA, "claims", "claims.json", err, errlen);
    if (!d)
        return NULL;
    char buf[RD_TEXT];
    snprintf(buf, sizeof buf, "n step %g, %ld samples per zone", 1.0, p->o->samples);
    rd_ctx_put(&d->ctx, "claim grid", buf);
    if (p->have_physical)
        rd_ctx_put(&d->ctx, REPORT_CLAIMS_PHYSICAL_CTX, "physical.json");
    for (int i = 0; i < r->count; ++i) {
        const struct claim *c = &r->rows[i];
        struct rd_row *x = rdoc_row(d, "", c->id);
        if (!x)
            break;
        rd_row_key(x, "id", NULL, c->id);
        rd_row_attr(x, "kind", c->kind);
        rd_row_attr(x, "source", c->source);
        /* what was claimed and what was measured: figures with no better or worse (a verdict
           is the distance between them, given as a text); a claim that is not a single number
           has none (compare would read a null as a figure that failed) */
        if (isfinite(c->claimed))
            rd_row_metric(d, x, "claimed", "1", RD_NEITHER, 0, c->claimed);
        if (isfinite(c->measured))
            rd_row_metric(d, x, "measured", "1", RD_NEITHER, 0, c->measured);
        rd_row_text(d, x, "claim", c->text);
        rd_row_text(d, x, "claimed_text", c->claimed_text);
        rd_row_text(d, x, "measured_text", c->measured_text);
        rd_row_text(d, x, "tolerance", c->tolerance);
        rd_row_text(d, x, "verdict", verdict_text(c));
        rd_row_text(d, x, "note", c->note);
        rd_row_text(d, x, "method", c->method);
    }
    return rdoc_built(d, err, errlen) ? NULL : d;
}

/* q_sweep.json's rows: a row per Q (max_rel, max_abs, max_abs_attenuation, max_rel_at_n), cq2's
   row on the same grid and the row of the minimising Q; the grid as the context line "Q grid". */
static struct rdoc *q_sweep_rows(const struct repro *p, char *err, size_t errlen)
{
    struct rdoc *d = rdoc_new(Q_SWEEP_SCHEMA, "q_sweep", "q_sweep.json", err, errlen);
    if (!d)
        return NULL;
    char buf[RD_TEXT];
    snprintf(buf, sizeof buf, "Q = %g..%g step %g, n in [%g, %g] step %g, %ld samples per zone", p->o->q_min,
             p->nq > 0 ? p->q[p->nq - 1] : p->o->q_max, p->o->q_step, 2.0, 1000.0, p->o->q_n_step, p->o->q_samples);
    rd_ctx_put(&d->ctx, "Q grid", buf);
    rdoc_text(d, "model", Q_SWEEP_MODEL);
    rdoc_text(d, "maxima", Q_SWEEP_MAXIMA);
    rdoc_text(d, "max_abs_what", Q_SWEEP_MAX_ABS_WHAT);
    for (int i = 0; i < p->nq; ++i) {
        snprintf(buf, sizeof buf, "fq:Q=%.10g", p->q[i]);
        struct rd_row *x = rdoc_row(d, "", buf);
        if (!x)
            break;
        rd_row_key(x, "model", NULL, buf);
        rd_row_metric(d, x, "Q", "1", RD_NEITHER, 0, p->q[i]);
        rd_row_metric(d, x, "max_rel", "1", RD_LOWER, 0, p->q_rel[i]);
        rd_row_metric(d, x, "max_abs", "1", RD_LOWER, 0, p->q_abs[i]);
        rd_row_metric(d, x, "max_abs_attenuation", "1", RD_LOWER, 0, p->q_att[i]);
        rd_row_metric(d, x, "max_rel_at_n", "1", RD_NEITHER, 0, p->q_rel_n[i]);
    }
    struct rd_row *x = rdoc_row(d, "", "cq2");
    if (x) {
        rd_row_key(x, "model", NULL, "cq2 (f2 of paper 2)");
        rd_row_metric(d, x, "max_rel", "1", RD_LOWER, 0, p->f2_rel);
        rd_row_metric(d, x, "max_abs", "1", RD_LOWER, 0, p->f2_abs);
        rd_row_text(d, x, "what", Q_SWEEP_F2_WHAT);
    }
    if ((x = rdoc_row(d, "", "fq")) != NULL) {
        rd_row_key(x, "model", NULL, "fq at the best Q");
        rd_row_metric(d, x, "Q", "1", RD_NEITHER, 0, p->q_best);
        rd_row_metric(d, x, "max_rel", "1", RD_LOWER, 0, p->have_fq_best ? p->fq_best.epicentre.value : NAN);
        rd_row_metric(d, x, "max_abs", "1", RD_LOWER, 0, p->have_fq_best ? p->fq_best.whole.value : NAN);
        rd_row_metric(d, x, "host_max_rel", "1", RD_LOWER, 0, p->q_best_host_rel);
        rd_row_text(d, x, "method", Q_SWEEP_BEST_METHOD);
    }
    return rdoc_built(d, err, errlen) ? NULL : d;
}

int reproduce_rows(const struct repro *p, struct repro_rows *rows, char *err, size_t errlen)
{
    memset(rows, 0, sizeof *rows);
    if (!(rows->claims = claims_rows(p, err, errlen)) || !(rows->q_sweep = q_sweep_rows(p, err, errlen)) ||
        (p->have_physical && !(rows->physical = pbcost_rows(&p->physical, err, errlen)))) {
        reproduce_rows_free(rows);
        return -1;
    }
    return 0;
}

void reproduce_rows_free(struct repro_rows *rows)
{
    rdoc_delete(rows->claims);
    rdoc_delete(rows->q_sweep);
    rdoc_delete(rows->physical);
    memset(rows, 0, sizeof *rows);
}

char *reproduce_claims_markdown(const struct repro_rows *rows)
{
    struct md_buf b;
    md_init(&b);
    if (report_claims_page(&b, rows->claims, rows->q_sweep, rows->physical)) {
        md_free(&b);
        return NULL;
    }
    return b.s;
}

static void jw_claim(struct jw *w, const struct claim *c)
{
    #define F(KIND, MEMBER, KEY) JW_FIELD(KIND, struct claim, MEMBER, KEY)
    static const struct jw_field head[] = {
        F(JWF_TEXT, id, "id"), F(JWF_TEXT, kind, "kind"), F(JWF_TEXT, source, "source"), F(JWF_TEXT, text, "claim"),
        F(JWF_TEXT, claimed_text, "claimed_text"), F(JWF_NUM, claimed, "claimed"),
    };
    #undef F
    jw_obj_begin(w);
    jw_kv_fields(w, c, JW_FIELDS(head));
    if (!isfinite(c->claimed))
        jw_kv_str(w, "claimed_reason", "not a single number (see claimed_text)");
    jw_kv_str(w, "measured_text", c->measured_text);
    jw_kv_num(w, "measured", c->measured);
    if (!isfinite(c->measured))
        jw_kv_str(w, "measured_reason", "not a single number (see measured_text)");
    jw_kv_str(w, "tolerance", c->tolerance);
    jw_kv_str(w, "verdict", verdict_text(c));
    jw_kv_str(w, "note", c->note);
    jw_kv_str(w, "method", c->method);
    jw_obj_end(w);
}

int reproduce_write_claims_json(const struct repro *p, const struct rdoc *rows, const char *path, char *err,
                                size_t errlen)
{
    const struct reproduce_report *r = p->r;
    struct jw w;
    jw_doc_begin(&w, CLAIMS_SCHEMA, p->s, p->actx.build_options);
    jw_kv_obj(&w, "grid");
    jw_kv_int(&w, "samples_per_zone", p->o->samples);
    jw_kv_num(&w, "n_step", 1.0);
    jw_kv_str(&w, "paper1_range", "n in [16, 1000]");
    jw_kv_str(&w, "paper2_range", "n in [2, 1000]");
    jw_kv_bool(&w, "grid_check", p->o->grid_check);
    jw_obj_end(&w);
    jw_obj_end(&w);
    jw_kv_obj(&w, "summary");
    #define F(KIND, MEMBER, KEY) JW_FIELD(KIND, struct reproduce_report, MEMBER, KEY)
    static const struct jw_field summary[] = {
        F(JWF_INT, count, "rows"), F(JWF_INT, reproduced, "reproduced"), F(JWF_INT, not_reproduced, "not_reproduced"),
        F(JWF_INT, within_noise, "within_noise"),
    };
    #undef F
    jw_kv_fields(&w, r, JW_FIELDS(summary));
    jw_kv_str(&w, "tolerance_rule", "a printed number: within one unit of its last printed digit; otherwise as stated "
                                    "per row");
    jw_obj_end(&w);
    jw_kv_arr(&w, "claims");
    for (int i = 0; i < r->count; ++i)
        jw_claim(&w, &r->rows[i]);
    jw_arr_end(&w);
    jw_kv_num(&w, "seconds", r->seconds);
    rdoc_json_rows_member(&w, rows);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

int reproduce_write_q_sweep_json(const struct repro *p, const struct rdoc *rows, const char *path, char *err,
                                 size_t errlen)
{
    struct jw w;
    jw_doc_begin(&w, Q_SWEEP_SCHEMA, p->s, p->actx.build_options);
    jw_kv_obj(&w, "grid");
    jw_kv_num(&w, "q_min", p->o->q_min);
    jw_kv_num(&w, "q_max", p->nq > 0 ? p->q[p->nq - 1] : p->o->q_max);
    jw_kv_num(&w, "q_step", p->o->q_step);
    jw_kv_num(&w, "n_min", 2);
    jw_kv_num(&w, "n_max", 1000);
    jw_kv_num(&w, "n_step", p->o->q_n_step);
    jw_kv_int(&w, "samples_per_zone", p->o->q_samples);
    jw_kv_str(&w, "maxima", Q_SWEEP_MAXIMA);
    jw_obj_end(&w);
    jw_obj_end(&w);
    jw_kv_str(&w, "model", Q_SWEEP_MODEL);
    static const char *const keys[4] = { "Q", "max_rel", "max_abs", "max_abs_attenuation" };
    const double *arrs[4] = { p->q, p->q_rel, p->q_abs, p->q_att };
    for (int k = 0; k < 4; ++k) {
        jw_kv_nums(&w, keys[k], arrs[k], (size_t)p->nq);
    }
    jw_kv_nums(&w, "max_rel_at_n", p->q_rel_n, (size_t)p->nq);
    jw_kv_str(&w, "max_abs_what", Q_SWEEP_MAX_ABS_WHAT);
    jw_kv_obj(&w, "f2");
    jw_kv_num(&w, "max_rel", p->f2_rel);
    jw_kv_num(&w, "max_abs", p->f2_abs);
    jw_kv_str(&w, "what", Q_SWEEP_F2_WHAT);
    jw_obj_end(&w);
    jw_kv_obj(&w, "best");
    jw_kv_num(&w, "Q", p->q_best);
    jw_kv_num(&w, "max_rel", p->have_fq_best ? p->fq_best.epicentre.value : NAN);
    jw_kv_num(&w, "max_abs", p->have_fq_best ? p->fq_best.whole.value : NAN);
    jw_kv_num(&w, "host_max_rel", p->q_best_host_rel);
    jw_kv_str(&w, "method", Q_SWEEP_BEST_METHOD);
    jw_obj_end(&w);
    rdoc_json_rows_member(&w, rows);
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

void reproduce_print_table(FILE *f, const struct repro *p)
{
    const struct reproduce_report *r = p->r;
    fprintf(f, "%-15s %-30s %-22s %-44s %s\n", "id", "source", "claimed", "measured", "verdict");
    for (int i = 0; i < r->count; ++i) {
        const struct claim *c = &r->rows[i];
        fprintf(f, "%-15s %-30s %-22s %-44s %s\n", c->id, c->source, c->claimed_text, c->measured_text,
                c->reproduced ? "REPRODUCED" : c->undecided ? "WITHIN NOISE" : "NOT REPRODUCED");
        fprintf(f, "    claim: %s\n    tolerance: %s\n", c->text, c->tolerance);
        if (c->note[0])
            fprintf(f, "    why: %s\n", c->note);
    }
    fprintf(f, "\n%d rows: %d reproduced, %d not reproduced", r->count, r->reproduced, r->not_reproduced);
    if (r->within_noise)
        fprintf(f, ", %d within noise", r->within_noise);
    fprintf(f, " (%.1f s)\n", r->seconds);
}
