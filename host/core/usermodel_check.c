/* usermodel_check.c - what a user model's text may not do, and the deadline of its host
 * reference (usermodel_check.h). */
#define _POSIX_C_SOURCE 200809L
#include "usermodel_check.h"
#include "clsession.h"
#include "exitcodes.h"
#include "outdir.h"

#include <ctype.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static int is_ident_start(int c) { return isalpha(c) || c == '_'; }
static int is_ident_char(int c) { return isalnum(c) || c == '_'; }

/* The helpers of kernels/brdf_models.h that a model may call (docs/user-models.md). Every
 * other brdf_*, BRDF_* or brdfbench_* name is brdfbench's own: the wrapper brdf_user_eval and
 * the dispatchers brdf_eval* lead back into the model itself, and a recursion through them
 * crashes the OpenCL compiler (PoCL's clang overflows its stack). */
static int is_allowed_helper(const char *s, size_t n)
{
    static const char *helpers[] = { "brdf_quadratic", "brdf_pow_lobe", "brdf_sin2", "brdf_alpha_from_n",
                                     "brdf_d_beckmann", "brdf_d_ggx", "brdf_phong_norm", "brdf_blinn_norm", NULL };
    for (int i = 0; helpers[i]; ++i)
        if (strlen(helpers[i]) == n && memcmp(s, helpers[i], n) == 0)
            return 1;
    return 0;
}

static int is_reserved_prefix(const char *s, size_t n)
{
    return (n >= 5 && (memcmp(s, "brdf_", 5) == 0 || memcmp(s, "BRDF_", 5) == 0)) ||
           (n >= 10 && memcmp(s, "brdfbench_", 10) == 0);
}

/* The first reserved identifier of a model's text, outside comments, strings and character
 * literals and not inside a number (1e5f): its offset, or -1. Line continuations are removed
 * first by the caller. *paste is set when the text pastes tokens (##), which could build a
 * reserved name out of harmless pieces. */
static long find_reserved_identifier(const char *t, size_t len, size_t *idlen, int *paste)
{
    *paste = 0;
    for (size_t i = 0; i < len;) {
        char ch = t[i];
        if (ch == '/' && i + 1 < len && t[i + 1] == '*') {
            const char *e = NULL;
            for (size_t k = i + 2; k + 1 < len; ++k)
                if (t[k] == '*' && t[k + 1] == '/') {
                    e = t + k;
                    break;
                }
            i = e ? (size_t)(e - t) + 2 : len;
        } else if (ch == '/' && i + 1 < len && t[i + 1] == '/') {
            while (i < len && t[i] != '\n')
                ++i;
        } else if (ch == '"' || ch == '\'') {
            for (++i; i < len && t[i] != ch && t[i] != '\n'; ++i)
                if (t[i] == '\\')
                    ++i;
            ++i;
        } else if (ch == '#' && i + 1 < len && t[i + 1] == '#') {
            *paste = 1;
            return (long)i;
        } else if (isdigit((unsigned char)ch) || (ch == '.' && i + 1 < len && isdigit((unsigned char)t[i + 1]))) {
            /* a number, with its exponent sign and suffix */
            for (++i; i < len; ++i) {
                unsigned char c = (unsigned char)t[i];
                if (isalnum(c) || c == '_' || c == '.')
                    continue;
                if ((c == '+' || c == '-') && strchr("eEpP", t[i - 1]))
                    continue;
                break;
            }
        } else if (is_ident_start((unsigned char)ch)) {
            size_t k = i;
            while (k < len && is_ident_char((unsigned char)t[k]))
                ++k;
            if (is_reserved_prefix(t + i, k - i) && !is_allowed_helper(t + i, k - i)) {
                *idlen = k - i;
                return (long)i;
            }
            i = k;
        } else {
            ++i;
        }
    }
    return -1;
}

/* Recursion: OpenCL C has none, and PoCL's compiler crashes on it (a segmentation fault, not a
 * message). The functions and macros a model file defines are the nodes of a graph, every name
 * one of them uses (in a function's body, in a macro's replacement) an edge; a cycle is refused.
 * t is the text with comments and literals blanked (blank_text). */
#define UM_GRAPH_MAX 256
struct um_graph {
    int count;
    char name[UM_GRAPH_MAX][64];
    int line[UM_GRAPH_MAX];
    unsigned char is_macro[UM_GRAPH_MAX];
    unsigned char edge[UM_GRAPH_MAX][UM_GRAPH_MAX / 8];
};

static int graph_find(const struct um_graph *g, const char *s, size_t n)
{
    for (int i = 0; i < g->count; ++i)
        if (strlen(g->name[i]) == n && memcmp(g->name[i], s, n) == 0)
            return i;
    return -1;
}

static int graph_add(struct um_graph *g, const char *s, size_t n, int line)
{
    int k = graph_find(g, s, n);
    if (k >= 0 || g->count >= UM_GRAPH_MAX || n >= sizeof g->name[0])
        return k;
    memcpy(g->name[g->count], s, n);
    g->name[g->count][n] = '\0';
    g->line[g->count] = line;
    return g->count++;
}

/* Comments, string and character literals become blanks (newlines kept). */
static void blank_text(char *t, size_t len)
{
    for (size_t i = 0; i < len;) {
        if (t[i] == '/' && i + 1 < len && t[i + 1] == '*') {
            size_t k = i + 2;
            while (k + 1 < len && !(t[k] == '*' && t[k + 1] == '/'))
                ++k;
            size_t e = k + 1 < len ? k + 2 : len;
            for (size_t j = i; j < e; ++j)
                if (t[j] != '\n')
                    t[j] = ' ';
            i = e;
        } else if (t[i] == '/' && i + 1 < len && t[i + 1] == '/') {
            while (i < len && t[i] != '\n')
                t[i++] = ' ';
        } else if (t[i] == '"' || t[i] == '\'') {
            char q = t[i];
            t[i++] = ' ';
            while (i < len && t[i] != q && t[i] != '\n') {
                if (t[i] == '\\' && i + 1 < len && t[i + 1] != '\n')
                    t[i++] = ' ';
                t[i++] = ' ';
            }
            if (i < len && t[i] == q)
                t[i++] = ' ';
        } else {
            ++i;
        }
    }
}

/* 1 and the cycle's path in out when node a reaches itself. */
static int graph_cycle_from(const struct um_graph *g, int start, int at, unsigned char *seen, int *path, int depth,
                            int *plen)
{
    path[depth] = at;
    for (int b = 0; b < g->count; ++b) {
        if (!(g->edge[at][b / 8] & (1u << (b % 8))))
            continue;
        if (b == start) {
            *plen = depth + 1;
            return 1;
        }
        if (seen[b])
            continue;
        seen[b] = 1;
        if (depth + 1 < UM_GRAPH_MAX && graph_cycle_from(g, start, b, seen, path, depth + 1, plen))
            return 1;
    }
    return 0;
}

static int check_recursion(const char *t, size_t len, const char *path, char *err, size_t errlen)
{
    struct um_graph *g = calloc(1, sizeof *g);
    if (!g)
        return 0;
    /* pass 1: the nodes (functions defined at depth 0, macros) */
    for (int pass = 0; pass < 2; ++pass) {
        int depth = 0, paren = 0, line = 1, current = -1, macro = -1;
        long cand = -1;
        size_t cand_len = 0;
        int cand_line = 0, bol = 1;
        for (size_t i = 0; i < len;) {
            char ch = t[i];
            if (ch == '\n') {
                ++line;
                bol = 1;
                macro = -1;
                ++i;
                continue;
            }
            if (bol && (ch == ' ' || ch == '\t')) {
                ++i;
                continue;
            }
            if (bol && ch == '#') {
                /* #define NAME ...: the rest of the line is the macro's replacement */
                size_t k = i + 1;
                while (k < len && (t[k] == ' ' || t[k] == '\t'))
                    ++k;
                bol = 0;
                if (len - k > 6 && memcmp(t + k, "define", 6) == 0 && (t[k + 6] == ' ' || t[k + 6] == '\t')) {
                    k += 6;
                    while (k < len && (t[k] == ' ' || t[k] == '\t'))
                        ++k;
                    size_t e = k;
                    while (e < len && is_ident_char((unsigned char)t[e]))
                        ++e;
                    if (e > k) {
                        macro = pass == 0 ? graph_add(g, t + k, e - k, line) : graph_find(g, t + k, e - k);
                        if (macro >= 0)
                            g->is_macro[macro] = 1;
                        i = e;
                        continue;
                    }
                }
                i = k;
                continue;
            }
            bol = 0;
            if (is_ident_start((unsigned char)ch)) {
                size_t k = i;
                while (k < len && is_ident_char((unsigned char)t[k]))
                    ++k;
                int from = macro >= 0 ? macro : depth > 0 ? current : -1;
                if (pass == 1 && from >= 0) {
                    /* a function is reached by a call (NAME followed by '(') or through a macro; a
                       variable that happens to share a function's name is no call */
                    size_t q = k;
                    while (q < len && (t[q] == ' ' || t[q] == '\t' || t[q] == '\n' || t[q] == '\r'))
                        ++q;
                    int to = graph_find(g, t + i, k - i);
                    if (to >= 0 && !g->is_macro[to] && macro < 0 && !(q < len && t[q] == '('))
                        to = -1;
                    if (to >= 0)
                        g->edge[from][to / 8] |= (unsigned char)(1u << (to % 8));
                }
                if (macro < 0 && depth == 0 && paren == 0) {
                    cand = (long)i;
                    cand_len = k - i;
                    cand_line = line;
                }
                i = k;
                continue;
            }
            if (macro < 0) {
                if (ch == '(') {
                    ++paren;
                } else if (ch == ')') {
                    if (paren > 0)
                        --paren;
                } else if (ch == ';' && depth == 0) {
                    cand = -1;
                } else if (ch == '{') {
                    if (depth == 0 && paren == 0 && cand >= 0)
                        current = pass == 0 ? graph_add(g, t + cand, cand_len, cand_line)
                                            : graph_find(g, t + cand, cand_len);
                    ++depth;
                } else if (ch == '}') {
                    if (depth > 0 && --depth == 0) {
                        current = -1;
                        cand = -1;
                    }
                }
            }
            ++i;
        }
    }
    int rc = 0;
    unsigned char seen[UM_GRAPH_MAX];
    int cyc[UM_GRAPH_MAX], plen = 0;
    for (int a = 0; a < g->count && !rc; ++a) {
        memset(seen, 0, sizeof seen);
        if (graph_cycle_from(g, a, a, seen, cyc, 0, &plen)) {
            char chain[512];
            size_t used = 0;
            chain[0] = '\0';
            for (int k = 0; k < plen && used < sizeof chain; ++k)
                used += (size_t)snprintf(chain + used, sizeof chain - used, "%s -> ", g->name[cyc[k]]);
            if (used < sizeof chain)
                snprintf(chain + used, sizeof chain - used, "%s", g->name[a]);
            snprintf(err, errlen, "%s:%d: '%s' calls itself (%s): OpenCL C has no recursion", path, g->line[a],
                     g->name[a], chain);
            rc = EXIT_USAGE;
        }
    }
    free(g);
    return rc;
}

int usermodel_check_text(const char *text, size_t len, const char *what, int is_file, char *err, size_t errlen)
{
    /* the preprocessor joins a line ending in a backslash with the next: so does the check */
    char *t = malloc(len + 1);
    int *line_of = malloc((len + 1) * sizeof *line_of);
    if (!t || !line_of) {
        free(t);
        free(line_of);
        snprintf(err, errlen, "%s: out of memory", what);
        return EXIT_RUNTIME;
    }
    size_t n = 0;
    int line = 1;
    for (size_t i = 0; i < len; ++i) {
        if (text[i] == '\\' && i + 1 < len && (text[i + 1] == '\n' || (text[i + 1] == '\r' && i + 2 < len &&
                                                                       text[i + 2] == '\n'))) {
            i += text[i + 1] == '\r' ? 2 : 1;
            ++line;
            continue;
        }
        line_of[n] = line;
        t[n++] = text[i];
        if (text[i] == '\n')
            ++line;
    }
    t[n] = '\0';
    size_t idlen = 0;
    int paste = 0;
    long at = find_reserved_identifier(t, n, &idlen, &paste);
    int rc = 0;
    if (at < 0 && is_file) {
        blank_text(t, n);
        rc = check_recursion(t, n, what, err, errlen);
    }
    if (at >= 0) {
        char where[600];
        if (is_file)
            snprintf(where, sizeof where, "%s:%d", what, line_of[at]);
        else
            snprintf(where, sizeof where, "%s: character %ld", what, at + 1);
        if (paste)
            snprintf(err, errlen, "%s: token pasting (##) is not accepted in a user model (it could build a name "
                     "of brdfbench's own code)", where);
        else
            snprintf(err, errlen, "%s: identifier '%.*s' is reserved (brdf_*, BRDF_* and brdfbench_* name "
                     "brdfbench's own code, such as the wrapper brdf_user_eval; a model may call only the "
                     "helpers brdf_quadratic, brdf_pow_lobe, brdf_sin2, brdf_alpha_from_n, brdf_d_beckmann, "
                     "brdf_d_ggx, brdf_phong_norm and brdf_blinn_norm)", where, (int)(idlen > 60 ? 60 : idlen),
                     t + at);
        rc = EXIT_USAGE;
    }
    free(t);
    free(line_of);
    return rc;
}

/* ---- the host reference's deadline ------------------------------------------------------ */

/* The host reference is the model's own code run in this process, one call per value: a loop
 * that ends in float on the device but not in double here would hold the run with no message.
 * Each call marks itself (a counter and the point, plain stores); a watcher thread, started with
 * the first call, looks four times a second. A call that has not returned after a second is
 * reported (with the point), again every 10 s, and one that runs past the launch deadline
 * (--timeout, clsession_timeout) ends the run as a runaway kernel does: one line, the run's
 * unfinished outputs removed (outdir_remove_own), exit 3. */
/* Shared with the one watcher thread (pthread_once) of the process: process-wide by nature. */
static _Atomic unsigned long host_seq;
static _Atomic int host_busy;
static const struct user_model *volatile host_model;
static volatile double host_c, host_n;
static pthread_once_t host_watch_once = PTHREAD_ONCE_INIT;

static void *host_watch_main(void *unused)
{
    (void)unused;
    unsigned long last = 0;
    double stuck = 0, reported = 0;
    for (;;) {
        struct timespec ts = { 0, 250000000L };
        nanosleep(&ts, NULL);
        unsigned long seq = atomic_load_explicit(&host_seq, memory_order_relaxed);
        if (!atomic_load_explicit(&host_busy, memory_order_relaxed) || seq != last) {
            last = seq;
            stuck = reported = 0;
            continue;
        }
        stuck += 0.25;
        const struct user_model *um = host_model;
        double limit = clsession_timeout();
        if (stuck >= limit) {
            char msg[1024];
            int n = snprintf(msg, sizeof msg,
                             "brdfbench: the host reference of user model '%s' (%s) ran past its deadline of %g s in "
                             "one evaluation, at c = %.9g, n = %.9g (a loop that does not end in double?; accepted: "
                             "--timeout SECONDS, or \"timeout\" in a gates file); the run is stopped and its "
                             "unfinished outputs removed\n",
                             um ? um->name : "?", um ? um->origin : "?", limit, host_c, host_n);
            ssize_t w = write(2, msg, n > 0 && (size_t)n < sizeof msg ? (size_t)n : strlen(msg));
            (void)w;
            outdir_remove_own();
            _exit(EXIT_RUNTIME);
        }
        if (stuck >= 1.0 && stuck - reported >= (reported ? 10.0 : 1.0)) {
            reported = stuck;
            fprintf(stderr, "brdfbench: the host reference of user model '%s' (%s) has been evaluating one value "
                    "(c = %.9g, n = %.9g) for %.0f s; the run stops at %g s (--timeout)\n", um ? um->name : "?",
                    um ? um->origin : "?", host_c, host_n, stuck, limit);
        }
    }
    return NULL;
}

static void host_watch_start(void)
{
    pthread_attr_t a;
    pthread_t t;
    if (pthread_attr_init(&a) == 0 && pthread_attr_setdetachstate(&a, PTHREAD_CREATE_DETACHED) == 0 &&
        pthread_create(&t, &a, host_watch_main, NULL) != 0)
        fprintf(stderr, "brdfbench: warning: the host reference's deadline cannot be watched (no thread)\n");
    pthread_attr_destroy(&a);
}

void usermodel_watch_begin(const struct user_model *um, double c, double n)
{
    pthread_once(&host_watch_once, host_watch_start);
    host_model = um;
    host_c = c;
    host_n = n;
    atomic_fetch_add_explicit(&host_seq, 1, memory_order_relaxed);
    atomic_store_explicit(&host_busy, 1, memory_order_relaxed);
}

void usermodel_watch_end(void) { atomic_store_explicit(&host_busy, 0, memory_order_relaxed); }


/* ---- names that become file names ------------------------------------------------------ */

/* A plain model name's stem in field_NAME.json and heatmap_NAME.png: field_safe_label keeps
   letters, digits, '.' and '-' and drops '_' (a model name has no ':' or ','). */
static void field_stem(const char *name, char *out, size_t len)
{
    size_t k = 0;
    for (; *name && k + 1 < len; ++name)
        if (*name != '_')
            out[k++] = *name;
    out[k] = '\0';
}

/* a is b followed by suffix */
static int is_suffixed(const char *a, const char *b, const char *suffix)
{
    size_t lb = strlen(b);
    return strncmp(a, b, lb) == 0 && strcmp(a + lb, suffix) == 0;
}

int usermodel_check_file_names(const char *name, char *err, size_t errlen)
{
    /* render writes NAME.png, NAME_error.png and NAME_contact.png per model, contact.png and
       he_LOBE*.png per scene: a user model may not take those stems */
    if (strcmp(name, "contact") == 0 || strncmp(name, "he_", 3) == 0) {
        snprintf(err, errlen, "user model '%s': the name is a file name render keeps for itself (contact, he_*); "
                 "choose another name", name);
        return EXIT_USAGE;
    }
    char mine[USERMODEL_NAME_MAX + 1], theirs[USERMODEL_NAME_MAX + 1];
    field_stem(name, mine, sizeof mine);
    /* the built-in models, then the user models registered before this one */
    for (int i = 0; i < models_count() + usermodel_count(); ++i) {
        const char *other = i < models_count() ? models_at(i)->id : usermodel_at(i - models_count())->name;
        field_stem(other, theirs, sizeof theirs);
        const char *file = NULL;
        if (strcmp(mine, theirs) == 0)
            file = "field_%s.json and heatmap_%s.png";
        else if (is_suffixed(name, other, "_error") || is_suffixed(other, name, "_error"))
            file = "render's %s_error.png";
        else if (is_suffixed(name, other, "_contact") || is_suffixed(other, name, "_contact"))
            file = "render's %s_contact.png";
        if (!file)
            continue;
        char what[200];
        const char *stem = file[0] == 'f' ? mine : strlen(name) < strlen(other) ? name : other;
        snprintf(what, sizeof what, file, stem, stem);
        snprintf(err, errlen, "user model '%s': its files would be those of model '%s' (%s); rename one of the two",
                 name, other, what);
        return EXIT_USAGE;
    }
    return 0;
}
