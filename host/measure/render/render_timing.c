/* render_timing.c - the timing of a scene at a size: every entry's shading pass and the copy
 * kernel as items of the measurement runner, rounds in a fresh random order each. */
#define _XOPEN_SOURCE 700
#include "render_internal.h"
#include "errmsg.h"
#include "exitcodes.h"
#include "raster.h"
#include "render_report.h"
#include "runner.h"
#include "stats.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* (all of v sorted, as before the median was shared: the copy's and the entries' times are
   finite or a launch failed, which stops the pass before this) */
static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, stats_cmp_double);
    return stats_median_sorted(v, (size_t)n);
}

/* The models and their references, each once per shading mode, in the order timed. */
static void timed_entries(const struct render_options *o, struct size_timing *st)
{
    st->nentries = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int mi = 0; mi < o->nmodels; mi++) {
            struct model_spec ref;
            const struct model_spec *m = &o->models[mi];
            int mode = render_shading_mode(m);
            if (pass == 1) {
                model_reference_spec(m, &ref);
                mode = render_reference_mode(mode, &ref);
            }
            const struct model_spec *sp = pass == 0 ? m : &ref;
            int found = 0;
            for (int k = 0; k < st->nentries; k++)
                if (st->entries[k].mode == mode && strcmp(st->entries[k].spec.label, sp->label) == 0)
                    found = 1;
            if (found)
                continue;
            struct timed_entry *te = &st->entries[st->nentries++];
            memset(te, 0, sizeof *te);
            te->spec = *sp;
            te->mode = mode;
            te->is_model = pass == 0;
            if (mode == render_shading_mode(sp))
                snprintf(te->name, sizeof te->name, "%s", sp->label);
            else
                snprintf(te->name, sizeof te->name, "%s@%s", sp->label, render_mode_names[mode]);
        }
}

/* A pass of the timing as an item of the measurement runner (host/core/runner.h): one launch
   of the shading kernel of an entry (te) over the G-buffer, or of the copy kernel (te NULL). */
struct pass_item {
    struct render_device *dev;
    const struct gbuffer *g;
    cl_mem gbuf, out_rgba, out_spec;
    const struct timed_entry *te;
    const struct render_light *lt;
    const struct render_options *o;
};

static int pass_item_launch(void *ctx, long iters, double *seconds, char *reason, size_t reason_len)
{
    const struct pass_item *p = ctx;
    (void)iters;   /* a pass is the whole image: not calibrated */
    int rc = p->te ? render_device_shade(p->dev, p->gbuf, p->g->stride, p->g->npix, p->out_rgba, p->out_spec,
                                         &p->te->spec, p->te->mode, p->lt, p->o, NULL, NULL, seconds)
                   : device_copy(p->dev, p->gbuf, p->g->stride, p->g->npix, p->out_rgba, p->out_spec, seconds);
    if (rc) {
        snprintf(reason, reason_len, "an OpenCL error in the timing pass (see above)");
        return -1;
    }
    return 0;
}

/* Timing of one scene at one size by the measurement runner: every entry's shading pass an
   item, the copy kernel (the same G-buffer read, the same image written, no shading) the
   reference timed three times a round; o->reps rounds in a fresh random order each, after
   o->warmup warm-up passes of each. */
int time_pass(struct render_device *dev, const struct scene_data *sd,
              const struct render_options *o, int w, int h, struct size_timing *st,
              char *err, size_t errlen)
{
    struct cl_session *s = dev->s;
    struct gbuffer g;
    struct render_light lt;
    cl_mem gbuf = NULL, out_rgba = NULL, out_spec = NULL;
    struct runner_item *items = NULL;
    struct pass_item *pi = NULL;
    struct runner run;
    int ran = 0;
    int rc = scene_gbuffer(sd, o, w, h, &g, &lt, err, errlen);
    if (rc)
        return rc;
    st->w = w;
    st->h = h;
    st->foreground = g.foreground;
    timed_entries(o, st);
    int n = st->nentries + 1;
    items = calloc((size_t)n, sizeof *items);
    pi = calloc((size_t)n, sizeof *pi);
    if (!items || !pi) {
        set_err(err, errlen, "out of memory");
        rc = EXIT_RUNTIME;
        goto done;
    }
    if ((rc = pass_buffers(s, &g, CL_MEM_READ_ONLY, "", &gbuf, &out_rgba, &out_spec)))
        goto fail;
    for (int k = 0; k < n; k++) {
        pi[k] = (struct pass_item){ dev, &g, gbuf, out_rgba, out_spec, k < st->nentries ? &st->entries[k] : NULL,
                                    &lt, o };
        items[k] = (struct runner_item){ .name = k < st->nentries ? st->entries[k].name : "copy",
                                         .launch = pass_item_launch, .ctx = &pi[k], .calibrate = 0, .iters = 1,
                                         .work_per_iter = (double)g.npix,
                                         .cpu_threads = s->is_cpu ? (int)s->compute_units : 0 };
        /* the runner warms each up once; the rest of o->warmup here */
        for (int r = 1; r < o->warmup; r++) {
            double t;
            char why[RUNNER_REASON];
            if (pass_item_launch(&pi[k], 1, &t, why, sizeof why)) {
                rc = EXIT_RUNTIME;
                goto fail;
            }
        }
    }
    runner_init(&run, items, n);
    run.reference = n - 1;
    run.rounds = o->reps;
    if (runner_run(&run)) {
        set_err(err, errlen, "out of memory");
        rc = EXIT_RUNTIME;
        runner_release(&run);
        goto done;
    }
    ran = 1;
    const struct runner_item *copy = &items[n - 1];
    if (!copy->ok) {
        rc = EXIT_RUNTIME;
        goto fail;
    }
    double *cs = malloc((size_t)copy->nreps * sizeof *cs);
    if (!cs) {
        set_err(err, errlen, "out of memory");
        rc = EXIT_RUNTIME;
        goto done;
    }
    memcpy(cs, copy->seconds, (size_t)copy->nreps * sizeof *cs);
    st->copy_med = median(cs, copy->nreps);
    free(cs);
    for (int k = 0; k < st->nentries; k++) {
        struct timed_entry *te = &st->entries[k];
        struct runner_item *it = &items[k];
        if (!it->ok) {
            rc = EXIT_RUNTIME;
            goto fail;
        }
        int reps = it->nreps;
        te->nreps = reps < RENDER_MAX_KEPT_REPS ? reps : RENDER_MAX_KEPT_REPS;
        memcpy(te->rep_s, it->seconds, (size_t)te->nreps * sizeof *it->seconds);   /* before median() sorts */
        te->med = median(it->seconds, reps);
        te->min = it->seconds[0];
        te->max = it->seconds[reps - 1];
        te->copy_med = st->copy_med;
        if (!(te->med > 0) || !(te->copy_med > 0)) {
            set_err(err, errlen, "%s: the profiling timer gave no time for %s", render_scene_names[sd->kind],
                    te->name);
            rc = EXIT_RUNTIME;
            goto done;
        }
    }
    goto done;
fail:
    if (!err[0])
        set_err(err, errlen, "%s: OpenCL error in the timing pass at %dx%d (see above)",
                render_scene_names[sd->kind], w, h);
    rc = rc ? rc : EXIT_RUNTIME;
done:
    if (ran)
        runner_release(&run);
    free(pi);
    free(items);
    pass_release(out_spec, out_rgba, gbuf, &g);
    return rc;
}
