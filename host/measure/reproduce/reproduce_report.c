/* reproduce_report.c - the writers of the claims run: claims.json, claims.md, q_sweep.json
 * and the printed table (reproduce.c derives the rows, this file writes them). */
#include "reproduce_report.h"

#include "context.h"
#include "jsonw.h"
#include "mdbuf.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A markdown table cell between its separators. */
static void md_cell(struct md_buf *b, const char *s)
{
    md_printf(b, " ");
    md_cell_text(b, s);
    md_printf(b, " |");
}

static const char *verdict_text(const struct claim *c)
{
    return c->reproduced ? "reproduced" : c->undecided ? "within noise" : "not reproduced";
}

char *reproduce_claims_markdown(const struct repro *p)
{
    const struct reproduce_report *r = p->r;
    struct md_buf b;
    md_init(&b);
    char noise[48] = "";   /* a verdict decided by timings that cannot decide it */
    if (r->within_noise)
        snprintf(noise, sizeof noise, ", %d within noise", r->within_noise);
    md_printf(&b,
              "# Claims of the papers, re-derived\n\n"
              "%d rows: %d reproduced, %d not reproduced%s. A printed number is reproduced when the measured value is "
              "within one unit of its last printed digit (which accepts rounding or truncation); every other "
              "tolerance is stated in its row. Rows of kind `check` are closed forms the harness itself must meet.\n\n",
              r->count, r->reproduced, r->not_reproduced, noise);
    for (int pass = 0; pass < 2; ++pass) {
        md_printf(&b, pass == 0 ? "## Claims\n\n" : "\n## Harness checks\n\n");
        md_printf(&b,
                  "| id | source | claim | claimed | measured | tolerance | verdict | where / why |\n"
                  "|---|---|---|---|---|---|---|---|\n");
        for (int i = 0; i < r->count; ++i) {
            const struct claim *c = &r->rows[i];
            if ((strcmp(c->kind, "claim") == 0) != (pass == 0))
                continue;
            md_printf(&b, "|");
            md_cell(&b, c->id);
            md_cell(&b, c->source);
            md_cell(&b, c->text);
            md_cell(&b, c->claimed_text);
            md_cell(&b, c->measured_text);
            md_cell(&b, c->tolerance);
            md_cell(&b, c->reproduced ? "**reproduced**" : c->undecided ? "**within noise**" : "**not reproduced**");
            char why[1024];
            snprintf(why, sizeof why, "%s%s(%s)", c->note, c->note[0] ? " " : "", c->method);
            md_cell(&b, why);
            md_printf(&b, "\n");
        }
    }
    md_printf(&b,
              "\nGrids: claim sweeps n step 1, %ld samples per zone (both zones), maxima polished in double; Q sweep "
              "Q = %g..%g step %g, n in [2, 1000] step %g, %ld samples per zone (q_sweep.json).\n",
              p->o->samples, p->o->q_min, p->nq > 0 ? p->q[p->nq - 1] : p->o->q_max, p->o->q_step, p->o->q_n_step,
              p->o->q_samples);
    if (p->have_physical) {
        char *ph = pbcost_markdown(&p->physical);
        if (ph)
            md_printf(&b, "%s", ph);
        else
            b.failed = 1;
        free(ph);
    }
    if (b.failed) {
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

int reproduce_write_claims_json(const struct repro *p, const char *path, char *err, size_t errlen)
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
    jw_obj_end(&w);
    return jw_write_file_free(&w, path, err, errlen);
}

int reproduce_write_q_sweep_json(const struct repro *p, const char *path, char *err, size_t errlen)
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
    jw_kv_str(&w, "maxima", "device grid, polished in double");
    jw_obj_end(&w);
    jw_obj_end(&w);
    jw_kv_str(&w, "model", "fq:Q=... (f_Q of paper 2) against phong");
    static const char *const keys[4] = { "Q", "max_rel", "max_abs", "max_abs_attenuation" };
    const double *arrs[4] = { p->q, p->q_rel, p->q_abs, p->q_att };
    for (int k = 0; k < 4; ++k) {
        jw_kv_nums(&w, keys[k], arrs[k], (size_t)p->nq);
    }
    jw_kv_nums(&w, "max_rel_at_n", p->q_rel_n, (size_t)p->nq);
    jw_kv_str(&w, "max_abs_what", "over the whole range x in [0, pi/2]; max_abs_attenuation over the attenuation zone");
    jw_kv_obj(&w, "f2");
    jw_kv_num(&w, "max_rel", p->f2_rel);
    jw_kv_num(&w, "max_abs", p->f2_abs);
    jw_kv_str(&w, "what", "cq2 on the same grid: does not depend on Q");
    jw_obj_end(&w);
    jw_kv_obj(&w, "best");
    jw_kv_num(&w, "Q", p->q_best);
    jw_kv_num(&w, "max_rel", p->have_fq_best ? p->fq_best.epicentre.value : NAN);
    jw_kv_num(&w, "max_abs", p->have_fq_best ? p->fq_best.whole.value : NAN);
    jw_kv_num(&w, "host_max_rel", p->q_best_host_rel);
    jw_kv_str(&w, "method", "GSL Brent over Q on the exact per-n max delta (integer n of [2, 1000]), bracketed by the "
                            "sweep's best Q; figures from the device sweep at that Q");
    jw_obj_end(&w);
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
