/* frontier.c - the measuring side of `brdfbench frontier` (see frontier.h): cost from the
 * throughput engine (tp_program_rate), accuracy from the accuracy engine (accuracy_run), the
 * teapot's PSNR from the render engine (render_run, read back from its render.json), and the
 * Pareto set. frontier_report.c writes the results. */
#include "frontier.h"
#include "frontier_report.h"
#include "accuracy.h"
#include "exitcodes.h"
#include "outdir.h"
#include "rdoc_read.h"
#include "render.h"
#include "throughput.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct model_ops frontier_ops_of(const struct model_info *info)
{
    struct model_ops none = { 0, 0, 0, 0, 0, "no entry (a user model)" };
    return model_is_builtin(info) ? info->ops : none;
}

void frontier_options_default(struct frontier_options *o)
{
    memset(o, 0, sizeof *o);
    o->samples = 1024;
    o->reps = 3;
    o->rounds = 3;
    o->min_time = 0.02;
    o->image_w = 480;
    o->image_h = 270;
}

/* The frontier's default set: the registry's models by frontier_rank (kernels/brdf_model_list.h),
 * each followed by its frontier_variants. */
int frontier_default_models(struct model_spec *out, int max)
{
    int count = 0;
    char err[256];
    for (int rank = 1; rank <= models_count(); ++rank)
        for (int i = 0; i < models_count(); ++i) {
            const struct model_info *m = models_at(i);
            if (m->frontier_rank != rank)
                continue;
            if (count < max)
                model_spec_default(m, &out[count++]);
            char variants[256];
            snprintf(variants, sizeof variants, "%s", m->frontier_variants ? m->frontier_variants : "");
            char *save = NULL;
            for (char *v = strtok_r(variants, ",", &save); v && count < max; v = strtok_r(NULL, ",", &save))
                if (model_spec_parse(v, &out[count], err, sizeof err) == 0)
                    count++;
        }
    return count;
}

/* a at least as good as b in cost: higher, or the spreads overlap (noise cannot order them) */
static int cost_not_worse(double ahi, double blo) { return ahi >= blo; }
/* a better in cost: its slowest launch beats b's fastest */
static int cost_better(double alo, double bhi) { return alo > bhi; }

void frontier_pareto(const double *rate_lo, const double *rate_hi, const double *max_rel, const double *max_abs,
                     int count, int *on_front)
{
    for (int i = 0; i < count; ++i) {
        on_front[i] = isfinite(rate_lo[i]) && isfinite(max_rel[i]) && isfinite(max_abs[i]);
        for (int j = 0; j < count && on_front[i]; ++j) {
            if (j == i || !isfinite(rate_lo[j]) || !isfinite(max_rel[j]) || !isfinite(max_abs[j]))
                continue;
            int not_worse = cost_not_worse(rate_hi[j], rate_lo[i]) &&
                            max_rel[j] <= max_rel[i] && max_abs[j] <= max_abs[i];
            int better = cost_better(rate_lo[j], rate_hi[i]) || max_rel[j] < max_rel[i] ||
                         max_abs[j] < max_abs[i];
            if (not_worse && better)
                on_front[i] = 0;
        }
    }
}

/* Accuracy: one sweep over [2, 1000]; the [16, 1000] figures from its per-n maxima. */
static int frontier_accuracy(struct cl_session *s, struct frontier_report *r)
{
    struct accuracy_ctx actx;
    memset(&actx, 0, sizeof actx);
    int rc = accuracy_open(&actx, s, "");
    if (rc)
        return rc;
    struct accuracy_grid g = { 2.0, 1000.0, 1.0, r->opt.samples };
    for (int i = 0; i < r->count && !rc; ++i) {
        struct frontier_row *row = &r->rows[i];
        struct accuracy_result res;
        rc = accuracy_run(&actx, &row->spec, &g, &res);
        if (rc)
            break;
        row->max_rel[0] = res.epicentre.value;
        row->max_rel_n[0] = res.epicentre.n;
        row->max_abs[0] = res.attenuation.value;
        row->max_abs_n[0] = res.attenuation.n;
        row->max_rel[1] = row->max_abs[1] = -1;
        for (long k = 0; k < res.n_count; ++k) {
            const struct acc_per_n *p = &res.per_n[k];
            if (p->n < 16.0)
                continue;
            if (p->epi_rel_d.value > row->max_rel[1]) { row->max_rel[1] = p->epi_rel_d.value; row->max_rel_n[1] = p->n; }
            if (p->att_abs_d.value > row->max_abs[1]) { row->max_abs[1] = p->att_abs_d.value; row->max_abs_n[1] = p->n; }
        }
        if (row->max_rel[1] < 0)   /* no finite figure from n = 16 on: none, not -1 */
            row->max_rel[1] = row->max_rel_n[1] = NAN;
        if (row->max_abs[1] < 0)
            row->max_abs[1] = row->max_abs_n[1] = NAN;
        accuracy_result_free(&res);
    }
    accuracy_close(&actx);
    return rc;
}

/* Cost: one throughput program (default build options), every model in both n modes. */
static int frontier_cost(struct cl_session *s, struct frontier_report *r, int quiet)
{
    struct throughput_options to;
    throughput_options_default(&to);
    to.reps = r->opt.reps;
    to.min_time = r->opt.min_time;
    long work_items = 32L * (long)(s->compute_units ? s->compute_units : 1);
    if (work_items > TP_MAX_WORK_ITEMS)
        work_items = TP_MAX_WORK_ITEMS;
    struct model_spec specs[FRONTIER_MAX_MODELS];
    for (int i = 0; i < r->count; ++i)
        specs[i] = r->rows[i].spec;
    struct tp_program prog;
    memset(&prog, 0, sizeof prog);
    int rc = tp_program_build(&prog, s, specs, r->count, TP_VARIANT_DEFAULT, NULL);
    if (rc)
        return rc;
    /* Every model in both n modes in the runner's interleaved rounds (a fresh random order per
       round, the peak kernel timed in each): rounds x reps repetitions per figure. The front is
       decided on the normalised rates (rate / the peak's rate in the same round), so that a
       busy spell on a shared machine, which slows the peak as much as the models, cancels. */
    to.reps = (r->opt.rounds > 0 ? r->opt.rounds : 1) * (r->opt.reps > 0 ? r->opt.reps : 1);
    if (to.reps > TP_MAX_REPS)
        to.reps = TP_MAX_REPS;
    struct tp_timed t[2 * FRONTIER_MAX_MODELS];
    memset(t, 0, sizeof t);
    for (int i = 0; i < r->count; ++i)
        for (int m = 0; m < TP_NMODE_COUNT; ++m)
            t[2 * i + m] = (struct tp_timed){ .m = &r->rows[i].spec, .nmode = m };
    rc = tp_time_set(&prog, t, 2 * r->count, &to, work_items, quiet);
    for (int i = 0; rc == 0 && i < r->count; ++i)
        for (int m = 0; m < TP_NMODE_COUNT; ++m) {
            struct frontier_row *row = &r->rows[i];
            const struct tp_timed *x = &t[2 * i + m];
            if (!x->ok) {
                snprintf(row->rate_reason, sizeof row->rate_reason, "%s", x->reason);
                continue;
            }
            memcpy(row->rate[m], x->rate, sizeof x->rate);
            memcpy(row->norm[m], x->norm, sizeof x->norm);
            if (!quiet)
                fprintf(stderr, "frontier: %-18s %-8s %8.3g G/s, %.4g of peak (%d rounds)\n", row->spec.label,
                        tp_nmode_name(m), row->rate[m][1] * 1e-9, row->norm[m][1], x->nreps);
        }
    tp_program_release(&prog);
    return rc;
}

/* PSNR of the teapot pass: the render engine writes its render.json into a folder of its own
   under the run, read back here. */
static int frontier_psnr(struct cl_session *s, struct frontier_report *r, const char *out_dir)
{
    for (int i = 0; i < r->count; ++i) {
        r->rows[i].psnr_db = NAN;
        snprintf(r->rows[i].psnr_reason, sizeof r->rows[i].psnr_reason, "no image pass");
    }
    if (r->opt.image_w <= 0 || !out_dir)
        return 0;
    struct render_options ro;
    render_options_default(&ro);
    for (int k = 0; k < RENDER_SCENE_COUNT; ++k)
        ro.scene_on[k] = k == RENDER_TEAPOT;
    ro.width = r->opt.image_w;
    ro.height = r->opt.image_h;
    ro.ntime_sizes = 0;
    ro.write_images = 0;
    char dir[4200], path[4300];
    path_join(dir, sizeof dir, out_dir, "frontier_teapot");
    ro.io = (struct engine_io){ dir, 1 };
    ro.nmodels = 0;
    for (int i = 0; i < r->count && ro.nmodels < RENDER_MAX_MODELS; ++i)
        ro.models[ro.nmodels++] = r->rows[i].spec;
    struct render_result res;
    int rc = render_run(s, &ro, &res);
    render_result_free(&res);
    if (rc) {
        for (int i = 0; i < r->count; ++i)
            snprintf(r->rows[i].psnr_reason, sizeof r->rows[i].psnr_reason, "the teapot pass failed (exit %d)", rc);
        fprintf(stderr, "brdfbench frontier: teapot pass: %s\n", res.err);
        return rc == EXIT_USAGE ? 0 : (rc == EXIT_RUNTIME ? 0 : rc);   /* a missing scene file leaves the PSNR out */
    }
    path_join(path, sizeof path, dir, "render.json");
    struct rdoc doc;
    char err[1024];
    if (rdoc_read_file(path, &doc, err, sizeof err)) {
        fprintf(stderr, "brdfbench frontier: %s\n", err);
        return 0;
    }
    /* the teapot's image rows (keys scene "teapot WxH" and model; its timing rows have none) */
    for (int k = 0; k < doc.nrows; ++k) {
        const struct rd_row *row = &doc.rows[k];
        const char *scene = rd_row_key_value(row, "scene"), *model = rd_row_key_value(row, "model");
        if (!scene || !model || strncmp(scene, "teapot ", 7) != 0)
            continue;
        const struct rd_metric *psnr = rd_row_find(row, "psnr_db");
        for (int i = 0; i < r->count; ++i) {
            if (strcmp(r->rows[i].spec.label, model) != 0)
                continue;
            if (!row->ok) {
                snprintf(r->rows[i].psnr_reason, sizeof r->rows[i].psnr_reason, "the teapot pass: %.200s",
                         row->reason);
            } else if (psnr && isfinite(psnr->value)) {
                r->rows[i].psnr_db = psnr->value;
                r->rows[i].psnr_reason[0] = '\0';
            } else {
                snprintf(r->rows[i].psnr_reason, sizeof r->rows[i].psnr_reason,
                         "identical to its reference: PSNR is infinite");
            }
        }
    }
    rdoc_free(&doc);
    return 0;
}

void frontier_result_free(struct frontier_result *r)
{
    free(r->markdown);
    r->markdown = NULL;
}

int frontier_run(struct cl_session *s, const struct frontier_options *o, struct frontier_result *res)
{
    char err[1024];
    double t0 = wall_seconds();
    struct frontier_report *r = calloc(1, sizeof *r);
    if (!r)
        return EXIT_RUNTIME;
    r->opt = *o;
    if (o->model_count > 0) {
        memcpy(r->opt.models, o->models, sizeof o->models);
        r->count = o->model_count;
    } else {
        r->count = frontier_default_models(r->opt.models, FRONTIER_MAX_MODELS);
    }
    r->fq2 = -1;
    for (int i = 0; i < r->count; ++i) {
        struct frontier_row *row = &r->rows[i];
        row->spec = r->opt.models[i];
        row->kind = model_is_builtin(row->spec.info) ? row->spec.info->kind : MODEL_KIND_OTHER;
        row->ops = frontier_ops_of(row->spec.info);
        for (int m = 0; m < 2; ++m)
            row->rate[m][0] = row->rate[m][1] = row->rate[m][2] = row->norm[m][0] = row->norm[m][1] =
                row->norm[m][2] = NAN;
        if (strcmp(row->spec.label, "fq2") == 0)
            r->fq2 = i;
    }
    int rc = frontier_accuracy(s, r);
    if (!rc)
        rc = frontier_cost(s, r, o->io.quiet);
    if (!rc)
        rc = frontier_psnr(s, r, o->io.out_dir);
    if (rc)
        goto done;
    double lo[FRONTIER_MAX_MODELS] = { 0 }, hi[FRONTIER_MAX_MODELS] = { 0 }, rel[FRONTIER_MAX_MODELS] = { 0 },
           ab[FRONTIER_MAX_MODELS] = { 0 };
    int front[FRONTIER_MAX_MODELS] = { 0 };
    for (int i = 0; i < r->count; ++i) {
        /* the normalised rates where the peak was timed, else the absolute ones; two costs whose
           medians are within FRONTIER_MIN_CHANGE of each other (compare's minimum change) are a
           tie: the spread handed to frontier_pareto is median x/ sqrt(1 + FRONTIER_MIN_CHANGE),
           so that two overlap exactly when their medians' ratio is within 1 + FRONTIER_MIN_CHANGE.
           A median over the rounds moves little between runs; a min or a max moves with one
           quiet or busy moment. */
        int nrm = isfinite(r->rows[i].norm[0][1]);
        double med = nrm ? r->rows[i].norm[0][1] : r->rows[i].rate[0][1], half = sqrt(1.0 + FRONTIER_MIN_CHANGE);
        lo[i] = med / half;
        hi[i] = med * half;
        rel[i] = r->rows[i].max_rel[0];
        ab[i] = r->rows[i].max_abs[0];
    }
    frontier_pareto(lo, hi, rel, ab, r->count, front);
    for (int i = 0; i < r->count; ++i)
        r->rows[i].on_front = front[i];
    r->seconds = wall_seconds() - t0;
    if (o->io.out_dir) {
        char path[4300];
        path_join(path, sizeof path, o->io.out_dir, "frontier.json");
        if (frontier_write_json(path, r, s, err, sizeof err) == 0) {
            path_join(path, sizeof path, o->io.out_dir, "frontier.csv");
            if (frontier_write_csv(path, r, err, sizeof err) == 0)
                if (frontier_write_plots(o->io.out_dir, r, err, sizeof err) == 0)
                    err[0] = '\0';
        }
        if (err[0]) {
            fprintf(stderr, "brdfbench frontier: %s\n", err);
            rc = EXIT_RUNTIME;
            goto done;
        }
    }
    if (!o->io.quiet)
        frontier_print(stdout, r);
    if (res)
        res->markdown = frontier_markdown(r);
done:
    free(r);
    return rc;
}
