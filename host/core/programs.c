/* programs.c - the run's device programs and host evaluators, cached per session
 * (see programs.h). */
#include "programs.h"
#include "exitcodes.h"
#include "room.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PROGRAMS_MAX_KERNELS 16

struct program_entry {
    const struct model_runtime *rt;   /* NULL: a built-in model's specialised build */
    int model_id;                     /* that model's kernel id (rt NULL) */
    char *kernel_file, *extra_before, *options;
    cl_program program;
    int kernel_count;
    struct {
        char *name;
        cl_kernel kernel;
    } kernels[PROGRAMS_MAX_KERNELS];
};

/* Host evaluators opened on a session's device. */
struct host_entry {
    const struct model_runtime *rt;
};

/* The session's tables (clsession.h: programs, hosts): the cache lives with the session it
   serves, so a run holds it (host/core/run.h) and closing the session releases it. */
#define ENTRIES(s) ((struct program_entry *)(s)->programs.items)
#define HOSTS(s) ((struct host_entry *)(s)->hosts.items)

/* Room for one more element in the session's table t (room.h): 0, or -1 with a message when
 * memory is out (the table is then unchanged). From the first room on, closing the session
 * releases the tables, also when no entry was added (a build that failed). */
static int make_room(struct cl_session *s, struct cl_session_table *t, size_t size)
{
    void *grown = room_for_one(t->items, t->count, &t->cap, size, 8);
    if (!grown) {
        fprintf(stderr, "brdfbench: out of memory\n");
        return -1;
    }
    t->items = grown;
    s->release_cache = programs_release;
    return 0;
}

static int same_text(const char *a, const char *b) { return strcmp(a ? a : "", b ? b : "") == 0; }

static char *dup_text(const char *t)
{
    t = t ? t : "";
    size_t n = strlen(t) + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, t, n);
    return d;
}

int programs_host(struct cl_session *s, const struct model_spec *m)
{
    const struct model_runtime *rt = m ? models_runtime(m->info) : NULL;
    if (!rt || !rt->open_host)
        return 0;
    for (int i = 0; i < s->hosts.count; ++i)
        if (HOSTS(s)[i].rt == rt)
            return rt->open_host(rt, s);   /* idempotent */
    if (make_room(s, &s->hosts, sizeof(struct host_entry)))
        return EXIT_RUNTIME;
    int rc = rt->open_host(rt, s);
    if (rc)
        return rc;
    HOSTS(s)[s->hosts.count].rt = rt;
    ++s->hosts.count;
    s->release_cache = programs_release;
    return 0;
}

static int entry_add(struct cl_session *s, const char *kernel_file, const char *extra_before, const char *options,
                     const struct model_runtime *rt, int model_id, cl_program program, struct program_entry **out);

/* The cached build of kernel_file + extra_before + rt's text with options, made on first use;
   with rt NULL, of kernel_file + extra_before specialised to the built-in model model_id
   (-DBRDF_ONLY_MODEL: the model dispatch of kernels/brdf_models.h keeps that one case). */
static int entry_for(struct cl_session *s, const char *kernel_file, const char *extra_before, const char *options,
                     const struct model_runtime *rt, int model_id, int ref_id, struct program_entry **out)
{
    for (int i = 0; i < s->programs.count; ++i) {
        struct program_entry *e = &ENTRIES(s)[i];
        if (e->rt == rt && (rt || e->model_id == model_id) && strcmp(e->kernel_file, kernel_file) == 0 &&
            same_text(e->extra_before, extra_before) && same_text(e->options, options)) {
            *out = e;
            return 0;
        }
    }
    if (make_room(s, &s->programs, sizeof(struct program_entry)))
        return EXIT_RUNTIME;
    if (!rt) {
        char opts[1100];
        snprintf(opts, sizeof opts, "%s%s-DBRDF_ONLY_MODEL=%d -DBRDF_ONLY_REF=%d", options ? options : "",
                 options && *options ? " " : "", model_id, ref_id);
        cl_program program = NULL;
        int rc = clsession_build(s, kernel_file, extra_before, opts, &program);
        if (rc)
            return rc;
        return entry_add(s, kernel_file, extra_before, options, NULL, model_id, program, out);
    }
    /* The model's text after the kernel file (and the extra text), with its own options. */
    size_t a = extra_before ? strlen(extra_before) : 0, b = strlen(rt->device_source);
    char *source = malloc(a + b + 2);
    char opts[1100];
    snprintf(opts, sizeof opts, "%s%s%s", options ? options : "", options && *options ? " " : "",
             rt->device_options ? rt->device_options : "");
    if (s->specialise)
        snprintf(opts + strlen(opts), sizeof opts - strlen(opts), " -DBRDF_ONLY_MODEL=%d -DBRDF_ONLY_REF=%d", model_id,
                 ref_id);
    if (!source) {
        fprintf(stderr, "brdfbench: out of memory\n");
        return EXIT_RUNTIME;
    }
    if (a)
        memcpy(source, extra_before, a);
    source[a] = '\n';
    memcpy(source + a + 1, rt->device_source, b + 1);
    cl_program program = NULL;
    int rc = clsession_build_user(s, kernel_file, source, opts, &program, 0);
    free(source);
    if (rc) {
        if (rc == EXIT_USAGE)
            fprintf(stderr, "brdfbench: %s does not compile; the build log above names its lines\n", rt->what);
        return rc;
    }
    return entry_add(s, kernel_file, extra_before, options, rt, -1, program, out);
}

static int entry_add(struct cl_session *s, const char *kernel_file, const char *extra_before, const char *options,
                     const struct model_runtime *rt, int model_id, cl_program program, struct program_entry **out)
{
    struct program_entry *e = &ENTRIES(s)[s->programs.count];
    memset(e, 0, sizeof *e);
    e->rt = rt;
    e->model_id = model_id;
    e->kernel_file = dup_text(kernel_file);
    e->extra_before = dup_text(extra_before);
    e->options = dup_text(options);
    e->program = program;
    ++s->programs.count;
    s->release_cache = programs_release;
    if (!e->kernel_file || !e->extra_before || !e->options) {
        fprintf(stderr, "brdfbench: out of memory\n");
        return EXIT_RUNTIME;
    }
    *out = e;
    return 0;
}

/* The build a model needs beyond the shared program: a user model's, or in a session that
 * specialises a built-in model's own. *e stays NULL when the shared program serves. */
/* ref_given: the reference the build evaluates besides m (NULL: m's own, model_reference_spec). */
static int model_entry_ref(struct cl_session *s, const char *kernel_file, const char *extra_before,
                           const char *options, const struct model_spec *m, const struct model_spec *ref_given,
                           struct program_entry **e)
{
    const struct model_runtime *rt = m ? models_runtime(m->info) : NULL;
    *e = NULL;
    if (!rt && (!m || !s->specialise))
        return 0;
    struct model_spec ref;
    model_reference_spec(m, &ref);
    if (ref_given && ref_given->info != ref.info && s->specialise) {
        /* another reference than the model's own: a build of its own, which the options tell
           apart in the cache (the macro itself is read by no kernel) */
        char opts[1024];
        snprintf(opts, sizeof opts, "%.900s%s-DBRDF_REF_GIVEN=%d", options ? options : "",
                 options && *options ? " " : "", ref_given->info->kernel_id);
        return entry_for(s, kernel_file, extra_before, opts, rt, m->info->kernel_id, ref_given->info->kernel_id, e);
    }
    return entry_for(s, kernel_file, extra_before, options, rt, m->info->kernel_id, ref.info->kernel_id, e);
}

static int model_entry(struct cl_session *s, const char *kernel_file, const char *extra_before, const char *options,
                       const struct model_spec *m, struct program_entry **e)
{
    return model_entry_ref(s, kernel_file, extra_before, options, m, NULL, e);
}

int programs_program(struct cl_session *s, const char *kernel_file, const char *extra_before, const char *options,
                     const struct model_spec *m, cl_program shared, cl_program *out)
{
    struct program_entry *e;
    *out = shared;
    int rc = model_entry(s, kernel_file, extra_before, options, m, &e);
    if (rc || !e)
        return rc;
    *out = e->program;
    return programs_host(s, m);
}

int programs_kernel(struct cl_session *s, const char *kernel_file, const char *options, const struct model_spec *m,
                    const char *kernel_name, cl_kernel shared, cl_kernel *out)
{
    return programs_kernel_ref(s, kernel_file, options, m, NULL, kernel_name, shared, out);
}

int programs_kernel_ref(struct cl_session *s, const char *kernel_file, const char *options, const struct model_spec *m,
                        const struct model_spec *ref, const char *kernel_name, cl_kernel shared, cl_kernel *out)
{
    struct program_entry *e;
    *out = shared;
    int rc = model_entry_ref(s, kernel_file, NULL, options, m, ref, &e);
    if (rc || !e)
        return rc;
    for (int k = 0; k < e->kernel_count; ++k)
        if (strcmp(e->kernels[k].name, kernel_name) == 0) {
            *out = e->kernels[k].kernel;
            return programs_host(s, m);
        }
    if (e->kernel_count >= PROGRAMS_MAX_KERNELS) {
        fprintf(stderr, "brdfbench: more than %d kernels of %s asked for\n", PROGRAMS_MAX_KERNELS, kernel_file);
        return EXIT_RUNTIME;
    }
    cl_int err;
    cl_kernel k = clsession_create_kernel(e->program, kernel_name, &err);
    if (err != CL_SUCCESS) {
        cl_report("clCreateKernel", err, __FILE__, __LINE__);
        return EXIT_RUNTIME;
    }
    char *name = dup_text(kernel_name);
    if (!name) {
        clReleaseKernel(k);
        fprintf(stderr, "brdfbench: out of memory\n");
        return EXIT_RUNTIME;
    }
    e->kernels[e->kernel_count].name = name;
    e->kernels[e->kernel_count].kernel = k;
    ++e->kernel_count;
    *out = k;
    return programs_host(s, m);
}

void programs_release(struct cl_session *s)
{
    for (int i = 0; i < s->programs.count; ++i) {
        struct program_entry *e = &ENTRIES(s)[i];
        for (int k = 0; k < e->kernel_count; ++k) {
            clReleaseKernel(e->kernels[k].kernel);
            free(e->kernels[k].name);
        }
        if (e->program)
            clReleaseProgram(e->program);
        free(e->kernel_file);
        free(e->extra_before);
        free(e->options);
    }
    for (int i = 0; i < s->hosts.count; ++i)
        if (HOSTS(s)[i].rt->close_host)
            HOSTS(s)[i].rt->close_host(HOSTS(s)[i].rt, s);
    free(s->programs.items);
    free(s->hosts.items);
    s->programs = s->hosts = (struct cl_session_table){ NULL, 0, 0 };
}

int programs_build_count(const struct cl_session *s) { return s->programs.count; }
