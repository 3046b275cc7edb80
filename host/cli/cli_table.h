/* cli_table.h - declarative flag tables: each command lists its flags once (name, value
 * name, type, accepted range, where the value goes, help text, default), and both the parser
 * and `brdfbench COMMAND --help` are made from that list. A flag that several commands take
 * is defined once below (CLI_FLAG_*), so it has one name, one meaning and one help line
 * everywhere. Parsing returns a status and never calls exit(). */
#ifndef BRDF_CLI_TABLE_H
#define BRDF_CLI_TABLE_H

#include <stddef.h>
#include <stdio.h>

#include "accuracy.h"
#include "hemisphere.h"
#include "cli.h"
#include "models.h"

enum cli_kind {
    CLI_SWITCH,   /* no value: stores .set into the int at .dest */
    CLI_TEXT,     /* a string: stores the argument into the const char * at .dest */
    CLI_PATH,     /* as CLI_TEXT, and an empty value is refused */
    CLI_INT,      /* an integer in [min, max] (a multiple of .multiple when set) into an int */
    CLI_LONG,     /* the same into a long */
    CLI_DOUBLE,   /* a finite number in [min, max] into a double */
    CLI_CALL,     /* the value is handed to .call, which checks and stores it */
    CLI_RENAMED   /* not a flag of this command: refused with .help, which names the right one */
};

/* .call: returns 0 or EXIT_USAGE with a one-line message in err. */
typedef int (*cli_call_fn)(const char *flag, const char *value, void *dest, char *err, size_t errlen);

struct cli_flag {
    const char *name;        /* "--n-min" */
    const char *value;       /* the value's name in --help ("X", "N", "DIR"); NULL for a switch */
    enum cli_kind kind;
    void *dest;
    double min, max;         /* accepted range of a number (min 1e-300 reads as "> 0") */
    long multiple;           /* an integer must be a multiple of it (0: any) */
    const char *help;        /* the meaning (--help wraps it) */
    const char *def;         /* the default as --help shows it; NULL: the value at .dest before
                                parsing; "" shows none */
    const char *range;       /* the accepted values as --help shows them; NULL: made from min, max */
    cli_call_fn call;
    int *given;              /* set to 1 when the flag is on the command line (may be NULL) */
    int set;                 /* CLI_SWITCH: the value stored */
};

struct cli_command {
    const char *name;        /* "accuracy" */
    const char *synopsis;    /* after "usage: brdfbench NAME ", e.g. "[OPTIONS]" */
    const char *about;       /* lines that say what the command does, each starting "  " */
    const struct cli_flag *flags;
    int nflags;
    const char *epilog;      /* printed after the flags (may be NULL) */
    int max_positional;      /* bare arguments accepted (collected in positional[]) */
};

#define CLI_MAX_POSITIONAL 64
struct cli_args {
    const char *positional[CLI_MAX_POSITIONAL];
    int npositional;
};

/* cli_parse's outcome besides 0 and EXIT_USAGE: --help or --version was answered on stdout
 * and the command returns EXIT_OK. */
#define CLI_ANSWERED (-1)

/* Parses argv[1..argc-1] against the command's table: "--flag value" or "--flag=value",
 * --help (and -h, which main turns into --help) and --version anywhere. Returns 0,
 * CLI_ANSWERED, or EXIT_USAGE with a one-line message in err (without the command's name). */
int cli_parse(const struct cli_command *c, int argc, char **argv, struct cli_args *args, char *err, size_t errlen);
/* A command's exit after cli_parse returned prc != 0: EXIT_OK for CLI_ANSWERED, else err as
 * "brdfbench NAME: err" on stderr and EXIT_USAGE. */
int cli_parse_exit(const struct cli_command *c, int prc, const char *err);
/* A struct cli_command's table: CLI_TABLE(flags) for .flags and .nflags of the array flags. */
#define CLI_TABLE(F) .flags = (F), .nflags = (int)(sizeof(F) / sizeof((F)[0]))
/* Writes the command's --help from its table (in the format cli_set_help_format chose). */
void cli_print_help(FILE *f, const struct cli_command *c);
/* What --help writes: the text (the default), the command's man page (roff), or its flags for
 * the shell completions, one a line: "FLAG<TAB>VALUE<TAB>HELP" (VALUE empty for a switch). */
enum cli_help_format { CLI_HELP_TEXT, CLI_HELP_MAN, CLI_HELP_WORDS };
/* out NULL: standard output. */
void cli_set_help_format(enum cli_help_format format, FILE *out);
/* The command's one-line summary and example (main.c's command table), for --help and its
 * man page. */
void cli_set_command_info(const char *summary, const char *example);
/* Text as roff (man pages) writes it: backslashes and hyphens escaped, a leading '.' or '\''
 * guarded. */
void cli_write_roff(FILE *f, const char *text);
/* "brdfbench VERSION (REVISION)": what `brdfbench version` and every --version print. */
void cli_print_version(FILE *f);
/* Prints "brdfbench COMMAND: note: ..." on stderr: a harmless oddity of the command line that
 * was resolved (a model given twice). */
void cli_note(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* ---- flags shared by several commands: one definition each -------------------------------- */

/* A destination pointer checked against the type its kind stores (a mismatch is a compiler
   warning: pointer type mismatch in a conditional expression). */
#define CLI_DEST(TYPE, P) ((void *)(1 ? (P) : (TYPE *)0))

#define CLI_FLAG_N_MIN(DEST)                                                                                       \
    { .name = "--n-min", .value = "X", .kind = CLI_DOUBLE, .dest = CLI_DEST(double, DEST), \
      .min = ACC_MIN_N, .max = ACC_MAX_N, \
      .help = "smallest shininess n measured" }
#define CLI_FLAG_N_MAX(DEST)                                                                                       \
    { .name = "--n-max", .value = "X", .kind = CLI_DOUBLE, .dest = CLI_DEST(double, DEST), \
      .min = ACC_MIN_N, .max = ACC_MAX_N, \
      .help = "largest shininess n measured" }
#define CLI_FLAG_N_STEP(DEST)                                                                                      \
    { .name = "--n-step", .value = "X", .kind = CLI_DOUBLE, .dest = CLI_DEST(double, DEST), \
      .min = 1e-300, .max = ACC_MAX_N, \
      .help = "step of n over the grid; real values allowed, n-max always included" }
/* samples per zone per n, a multiple of 16 up to MAX */
/* One --samples range for every command, [ACC_MIN_SAMPLES, ACC_MAX_SAMPLES]; a command that
   must take less says why in RANGE (shown in --help and the man page in place of the range). */
#define CLI_FLAG_SAMPLES_WHY(DEST, MAX, RANGE)                                                                    \
    { .name = "--samples", .value = "N", .kind = CLI_LONG, .dest = CLI_DEST(long, DEST), \
      .min = ACC_MIN_SAMPLES, .max = (MAX), .range = (RANGE), \
      .multiple = 16, .help = "samples per zone and per n of the accuracy sweeps" }
#define CLI_FLAG_SAMPLES(DEST) CLI_FLAG_SAMPLES_WHY(DEST, ACC_MAX_SAMPLES, NULL)
#define CLI_FLAG_MODELS(DEST, GIVEN, DEF)                                                                          \
    { .name = "--models", .value = "LIST", .kind = CLI_TEXT, .dest = CLI_DEST(const char *, DEST), .given = (GIVEN), \
      .help = "models with parameters, comma-separated, e.g. cq2,fq:Q=0.7,lyon:k=4 (see brdfbench list); "        \
              "the same model given twice is measured once",                                                      \
      .def = (DEF) }
#define CLI_DEF_OUT "a new folder results/<date-time>/, and results/latest pointing at it"
#define CLI_FLAG_OUT(DEST, DEF)                                                                                    \
    { .name = "--out", .value = "DIR", .kind = CLI_PATH, .dest = CLI_DEST(const char *, DEST), \
      .help = "write the results into folder DIR", \
      .def = (DEF) }
/* Measured materials (MERL files, docs/measured.md): all, throughput and render. */
#define CLI_FLAG_MEASURED(DEST)                                                                                    \
    { .name = "--measured", .value = "FILE|DIR", .kind = CLI_PATH, .dest = CLI_DEST(const char *, DEST), .def = "", \
      .help = "measured materials: a MERL .binary file or a folder of them; all: measured.json and a section of "  \
              "report.md; throughput: their table lookup as rows of the physically based table (at most 4); "     \
              "render: the teapot and the bunny shaded with each beside the lobes fitted to it (at most 4) "       \
              "(docs/measured.md)" }
/* The heatmaps on one colour scale (heatmaps_shared.h): all, accuracy, plot, heatmap. */
#define CLI_FLAG_SHARED_SCALE(DEST)                                                                                \
    { .name = "--shared-scale", .kind = CLI_SWITCH, .dest = CLI_DEST(int, DEST), .set = 1,                       \
      .help = "draw every model's heatmap on one colour scale per panel (the largest delta and the largest "      \
              "Delta over the run's models), said in each colour bar; heatmaps_shared_scale.png, every model's "  \
              "fields side by side on that scale, is written either way" }
#define CLI_FLAG_QUIET(DEST)                                                                                       \
    { .name = "--quiet", .kind = CLI_SWITCH, .dest = CLI_DEST(int, DEST), .set = 1, \
      .help = "no progress lines, tables or summaries (files are written as without it; warnings "              \
              "and errors are still shown)" }
/* --output of the commands that write one text (report, rows); DEF: where it goes without the flag */
#define CLI_FLAG_OUTPUT(DEST, DEF)                                                                           \
    { .name = "--output", .value = "FILE|-", .kind = CLI_PATH, .dest = CLI_DEST(const char *, DEST), \
      .help = "write to FILE ('-': standard output)", .def = (DEF) }
#define CLI_FLAG_JSON(DEST)                                                                                  \
    { .name = "--json", .value = "FILE|-", .kind = CLI_PATH, .dest = CLI_DEST(const char *, DEST), \
      .help = "write the results as JSON to FILE ('-': standard output)", .def = "" }
#define CLI_FLAG_CSV(DEST)                                                                                   \
    { .name = "--csv", .value = "FILE|-", .kind = CLI_PATH, .dest = CLI_DEST(const char *, DEST), \
      .help = "write the results as CSV to FILE ('-': standard output)", .def = "" }

/* --out, --json and --csv of a command that writes a run folder or, with --json or --csv and no
 * --out, only those documents. */
#define CLI_FLAGS_DOCUMENTS(OUT, JSON, CSV)                                                                        \
    CLI_FLAG_OUT(OUT, CLI_DEF_OUT "; with --json or --csv and no --out, no folder"), CLI_FLAG_JSON(JSON),         \
    CLI_FLAG_CSV(CSV)

/* Device selection (struct device_options, cli.h). */
int cli_call_platform(const char *flag, const char *value, void *dest, char *err, size_t errlen);
int cli_call_device(const char *flag, const char *value, void *dest, char *err, size_t errlen);
int cli_call_kernel_dir(const char *flag, const char *value, void *dest, char *err, size_t errlen);
int cli_call_timeout(const char *flag, const char *value, void *dest, char *err, size_t errlen);
#define CLI_FLAGS_DEVICE(DEV)                                                                                      \
    { .name = "--platform", .value = "N", .kind = CLI_CALL, .dest = (DEV), .call = cli_call_platform,              \
      .help = "OpenCL platform index (see brdfbench list)", .range = "in [0, 63]",                                 \
      .def = "the first with a device" },                                                                         \
    { .name = "--device", .value = "N", .kind = CLI_CALL, .dest = (DEV), .call = cli_call_device,                  \
      .help = "device index on that platform; throughput, accuracy and render also take all (every device of " \
              "every platform) or a list (0,1 or P:D pairs such as 0:0,1:0): one run per device in " \
              "OUT/devices/<k>/, rows tagged with their device", .range = "in [0, 63]", .def = "0" },                                \
    { .name = "--kernel-dir", .value = "DIR", .kind = CLI_CALL, .dest = (DEV), .call = cli_call_kernel_dir,        \
      .help = "read kernels/*.cl from DIR instead of the copies built into the program", .def = "" }, \
    { .name = "--timeout", .value = "SECONDS", .kind = CLI_CALL, .dest = (DEV), .call = cli_call_timeout, \
      .help = "deadline of each kernel launch; past it the run stops with exit 3 and its unfinished outputs " \
              "removed", .range = "in [0.01, 604800]", .def = "300" }

/* --param NAME=VALUE of the commands without a hemisphere sweep (throughput, render): each sets
 * NAME on every listed model that has a parameter NAME (e.g. a .brdf file's bool), checked
 * against the model's range as in a --models spec. */
#define CLI_MAX_MODEL_PARAMS 8
/* one text for --param wherever it is (a flag reads alike in every command) */
#define CLI_HELP_PARAM                                                                                             \
    "a value of a model parameter in its declared range (a .brdf file's bool: 0 or 1, e.g. divide_by_NdotL=0), "  \
    "given to the listed models that have it (accuracy: to each full BRDF, which must have it, or n); repeatable"
struct cli_model_params {
    char text[CLI_MAX_MODEL_PARAMS][128];
    int count;
};
int cli_call_model_param(const char *flag, const char *value, void *dest, char *err, size_t errlen);
/* Applies the values to models[0..count). 0, or EXIT_USAGE with a one-line message (a value out of
 * a model's range, or a NAME no listed model has). */
int cli_apply_model_params(struct model_spec *models, int count, const struct cli_model_params *p, char *err,
                           size_t errlen);
#define CLI_FLAG_MODEL_PARAM(DEST)                                                                                 \
    { .name = "--param", .value = "NAME=VALUE", .kind = CLI_CALL, .call = cli_call_model_param, .dest = (DEST),  \
      .def = "", .help = CLI_HELP_PARAM }

/* User models (host/core/usermodel.h): registered as they are read. */
int cli_call_model_file(const char *flag, const char *value, void *dest, char *err, size_t errlen);
int cli_call_model_expr(const char *flag, const char *value, void *dest, char *err, size_t errlen);
int cli_call_define(const char *flag, const char *value, void *dest, char *err, size_t errlen);
#define CLI_FLAGS_USERMODEL                                                                                        \
    { .name = "-D", .value = "NAME[=VALUE]", .kind = CLI_CALL, .call = cli_call_define, .def = "",                 \
      .help = "define NAME (as VALUE, else 1) for the preprocessor of the GLSL/HLSL model files given after "    \
              "it (#if, #ifdef; docs/user-models.md); repeatable, at most 16" },                                   \
    { .name = "--model-file", .value = "FILE", .kind = CLI_CALL, .call = cli_call_model_file, .def = "",           \
      .help = "add the user model of FILE: OpenCL C (FILE.cl) or GLSL/HLSL (FILE.glsl, FILE.hlsl; see "         \
              "docs/user-models.md); repeatable; the same file twice is read once" },                            \
    { .name = "--model", .value = "NAME=EXPR", .kind = CLI_CALL, .call = cli_call_model_expr, .def = "",           \
      .help = "add a user model given by an expression of c and n, or GLSL/HLSL statements ending in "          \
              "return, e.g. --model 'sq=pow(fmax(0.45*n*(c-1)+1,0),2)' or --model "                              \
              "'q=t = 1 - 0.25*n*(1-c); t = max(t, 0); return t*t*t*t;'; repeatable; the same "                  \
              "NAME=EXPR twice is read once, NAME with another EXPR is refused" }

/* Parses --models text (or the default) into models, merging a model given twice (same label)
 * with a note. Returns the count, or -2 with a message. */
int cli_model_list(const char *text, struct model_spec *out, int max, char *err, size_t errlen);
/* Appends to models[count] (at most max) every user model (--model, --model-file) that the
 * list does not hold, with its default parameters and a note on stderr, so that a model the
 * command line defines is never dropped without a word. Returns the new count, or -2 with a
 * message when the list is full. */
int cli_add_unlisted_user_models(struct model_spec *models, int count, int max, char *err, size_t errlen);
/* The frontier's models when --models is not given (frontier and all): its default set of lobe
 * approximations, then every user model. Returns the count, or -2 with a message. */
int cli_frontier_default_models(struct model_spec *out, int max, char *err, size_t errlen);

/* "-" as an output path: the writer writes into a temporary folder and the document is then
 * copied to standard output. cli_output_path gives the path to hand the writer (path itself
 * unless it is "-"); cli_output_finish copies and removes the temporary file (ok = 0: only
 * removes). Both return 0 or EXIT_RUNTIME with a message. */
struct cli_output {
    const char *path;        /* as given */
    char tmp_dir[256];
    char tmp_path[512];
};
int cli_output_path(struct cli_output *o, const char *path, const char *name, const char **writer_path, char *err,
                    size_t errlen);
int cli_output_finish(struct cli_output *o, int ok, char *err, size_t errlen);
/* A command that writes a folder and takes --json FILE for one of its documents: the folder may
 * be a temporary one (cli_temp_dir, removed with cli_temp_dir_remove, which removes what the
 * run wrote in it, its sub-folders included), and the document is then copied to FILE, or to standard output for "-"
 * (cli_deliver; a regular FILE is replaced atomically). Return 0 or EXIT_RUNTIME with a message. */
int cli_temp_dir(char *dir, size_t len, char *err, size_t errlen);
void cli_temp_dir_remove(const char *dir);
int cli_deliver(const char *src, const char *flag, const char *dest, char *err, size_t errlen);
/* 1 when path means standard output. */
int cli_is_stdout(const char *path);


/* The hemisphere sweep of full BRDFs (accuracy; host/measure/accuracy/hemisphere.h), and the reference of
 * any sweep. PARAM_CALL stores one --param NAME=VALUE (repeatable) into PARAM_DEST. */
#define CLI_FLAGS_FULLBRDF(REF, SWEEP, PARAM_CALL, PARAM_DEST, POINTS, GRID)                                        \
    { .name = "--reference", .value = "SPEC", .kind = CLI_TEXT, .dest = CLI_DEST(const char *, REF), .def = "",    \
      .help = "the reference every model is measured against: a built-in with parameters, e.g. ct-ggx:F0=0.04; "  \
              "for full BRDFs also a full user model (its file, user:NAME or its name) or a measured material "     \
              "(merl:FILE.binary) "                                                                                 \
              "(default: each model's own; a full BRDF's family reference only where it agrees with the model "   \
              "within 1% at the lobe's peak, else refused)" },                                                      \
    { .name = "--axis", .value = "NAME[=MIN:MAX]", .kind = CLI_TEXT, .dest = CLI_DEST(const char *, SWEEP),        \
      .def = "n", .help = "the parameter axis of the hemisphere sweep: n, alpha, roughness or m (converted: "       \
              "alpha = sqrt(2/(n+2)), alpha = roughness^2, Beckmann m = alpha; a user model's own parameter takes "\
              "the value as named), or a parameter of the model over its declared range; PARAM:ROLE gives the "   \
              "model's parameter PARAM the axis of ROLE (n, alpha, roughness or m; the reference converted), "      \
              "e.g. --axis c:alpha for a .brdf file whose c is GGX's alpha" },                                     \
    { .name = "--param", .value = "NAME=VALUE", .kind = CLI_CALL, .call = (PARAM_CALL), .dest = (PARAM_DEST),       \
      .def = "", .help = CLI_HELP_PARAM },                                                                      \
    { .name = "--axis-points", .value = "N", .kind = CLI_INT, .dest = CLI_DEST(int, POINTS), .min = 1,             \
      .max = HEMI_MAX_POINTS, .help = "values of the hemisphere sweep's axis, ends included" },                    \
    { .name = "--hemisphere-grid", .value = "NHxNDxNP", .kind = CLI_TEXT, .dest = CLI_DEST(const char *, GRID),     \
      .def = "48x48x96", .help = "cells of the hemisphere sweep in theta_h (square-root spaced), theta_d and "      \
              "phi_d" }

/* The store of runs (store.h): store and history. */
#define CLI_FLAG_DB(DEST)                                                                                          \
    { .name = "--db", .value = "FILE", .kind = CLI_PATH, .dest = CLI_DEST(const char *, DEST),                    \
      .help = "the store of runs, an SQLite file (brdfbench store add makes it)", .def = "results/history.sqlite" }

#endif
