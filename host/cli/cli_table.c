/* cli_table.c - the parser and the --help writer of the declarative flag tables (cli_table.h),
 * the shared flags' value readers, and "-" as an output path. */
#define _XOPEN_SOURCE 700
#include "cli_table.h"

#include "clsession.h"
#include "context.h"
#include "exitcodes.h"
#include "frontier.h"
#include "infile.h"
#include "outdir.h"
#include "shaderlang.h"
#include "usermodel.h"

#include <dirent.h>

#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *current_command = "";


void cli_print_version(FILE *f) { fprintf(f, "brdfbench %s (%s)\n", BRDF_VERSION, brdf_git_revision); }

void cli_note(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "brdfbench %s: note: ", current_command);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

static const struct cli_flag *find_flag(const struct cli_command *c, const char *arg)
{
    for (int k = 0; k < c->nflags; ++k)
        if (cli_flag_is(arg, c->flags[k].name))
            return &c->flags[k];
    return NULL;
}

static int store_value(const struct cli_flag *f, const char *v, char *err, size_t errlen)
{
    long lv;
    switch (f->kind) {
    case CLI_PATH:
        if (!*v) {
            snprintf(err, errlen, "%s: empty path (accepted: a folder or file name)", f->name);
            return EXIT_USAGE;
        }
        /* fall through */
    case CLI_TEXT:
        *(const char **)f->dest = v;
        return 0;
    case CLI_INT:
    case CLI_LONG:
        if (cli_parse_long(f->name, v, (long)f->min, (long)f->max, &lv, err, errlen))
            return EXIT_USAGE;
        if (f->multiple > 0 && lv % f->multiple != 0) {
            snprintf(err, errlen, "%s: %ld is not a multiple of %ld (accepted: a multiple of %ld in [%ld, %ld])",
                     f->name, lv, f->multiple, f->multiple, (long)f->min, (long)f->max);
            return EXIT_USAGE;
        }
        if (f->kind == CLI_INT)
            *(int *)f->dest = (int)lv;
        else
            *(long *)f->dest = lv;
        return 0;
    case CLI_DOUBLE:
        return cli_parse_double(f->name, v, f->min, f->max, (double *)f->dest, err, errlen);
    case CLI_CALL:
        return f->call(f->name, v, f->dest, err, errlen);
    default:
        return 0;
    }
}

static int parse_one(const struct cli_command *c, int argc, char **argv, int *ip, struct cli_args *args,
                     int *options_end, char **inputs, int *ninputs, const char **outputs, const char **output_flags,
                     int *noutputs, char *err, size_t errlen);

/* The flags whose value is a file the command writes (or, --out, a folder it writes into). */
static int is_output_flag(const char *name)
{
    return strcmp(name, "--json") == 0 || strcmp(name, "--csv") == 0 || strcmp(name, "--junit") == 0 ||
           strcmp(name, "--output") == 0 || strcmp(name, "--out") == 0;
}

/* An output that names an input of the same command line replaces what the command reads:
   the same file (however reached: a link, a hard link, ./a and a), or a file that exists in
   a folder given as input (compare A B --json A/throughput.json). report's RUN_DIR/report.md
   is its own output, which report checks itself. Returns 0 or EXIT_USAGE with the message. */
static int output_names_input(const struct cli_command *c, const char *flag, const char *out, char *const *inputs,
                              int ninputs, char *err, size_t errlen)
{
    struct stat so, si;
    if (strcmp(flag, "--out") == 0 || strcmp(out, "-") == 0 || stat(out, &so) != 0 || !S_ISREG(so.st_mode))
        return 0;
    char out_real[PATH_MAX];
    int have_real = realpath(out, out_real) != NULL;
    for (int k = 0; k < ninputs; ++k) {
        if (stat(inputs[k], &si) != 0)
            continue;
        if (S_ISREG(si.st_mode) && si.st_dev == so.st_dev && si.st_ino == so.st_ino) {
            snprintf(err, errlen, "%s: '%s' is '%s', an input of this command (the same file): an output may not "
                     "replace what the command reads (accepted: another file name)", flag, out, inputs[k]);
            return EXIT_USAGE;
        }
        char in_real[PATH_MAX];
        if (S_ISDIR(si.st_mode) && have_real && strcmp(c->name, "report") != 0 && realpath(inputs[k], in_real)) {
            size_t n = strlen(in_real);
            if (strncmp(out_real, in_real, n) == 0 && (out_real[n] == '/' || (n == 1 && in_real[0] == '/'))) {
                snprintf(err, errlen, "%s: '%s' is a file in '%s', an input folder of this command: an output may "
                         "not replace what the command reads (accepted: a file outside the input folders, or a new "
                         "name)", flag, out, inputs[k]);
                return EXIT_USAGE;
            }
        }
    }
    return 0;
}

int cli_parse(const struct cli_command *c, int argc, char **argv, struct cli_args *args, char *err, size_t errlen)
{
    current_command = c->name;
    if (args)
        args->npositional = 0;
    /* the values of the command line: inputs (bare arguments, values of other flags) and
       outputs, checked against each other once all are known */
    char **inputs = calloc((size_t)argc + 1, sizeof *inputs);
    const char **outputs = calloc((size_t)argc + 1, sizeof *outputs);
    const char **output_flags = calloc((size_t)argc + 1, sizeof *output_flags);
    int ninputs = 0, noutputs = 0, rc = 0, options_end = 0;
    if (!inputs || !outputs || !output_flags) {
        free(inputs);
        free(outputs);
        free(output_flags);
        snprintf(err, errlen, "out of memory");
        return EXIT_USAGE;
    }
    for (int i = 1; i < argc && rc == 0; ++i)
        rc = parse_one(c, argc, argv, &i, args, &options_end, inputs, &ninputs, outputs, output_flags, &noutputs, err,
                       errlen);
    for (int k = 0; k < noutputs && rc == 0; ++k)
        rc = output_names_input(c, output_flags[k], outputs[k], inputs, ninputs, err, errlen);
    free(inputs);
    free(outputs);
    free(output_flags);
    return rc;
}

/* One argument of cli_parse (and its value): 0, CLI_ANSWERED or EXIT_USAGE. */
static int parse_one(const struct cli_command *c, int argc, char **argv, int *ip, struct cli_args *args,
                     int *options_end, char **inputs, int *ninputs, const char **outputs, const char **output_flags,
                     int *noutputs, char *err, size_t errlen)
{
    int i = *ip;
    {
        const char *a = argv[i];
        /* "--" ends the options: every later argument is a bare one, even "-x" */
        if (!*options_end && strcmp(a, "--") == 0) {
            *options_end = 1;
            return 0;
        }
        if (strcmp(a, "--help") == 0) {
            cli_print_help(stdout, c);
            return CLI_ANSWERED;
        }
        if (strcmp(a, "--version") == 0) {
            cli_print_version(stdout);
            return CLI_ANSWERED;
        }
        if (*options_end || a[0] != '-' || a[1] == '\0') {   /* a bare argument ("-" included) */
            if (!args || args->npositional >= c->max_positional || args->npositional >= CLI_MAX_POSITIONAL) {
                snprintf(err, errlen, "unexpected argument '%s' (see brdfbench %s --help)", a, c->name);
                return EXIT_USAGE;
            }
            args->positional[args->npositional++] = a;
            inputs[(*ninputs)++] = argv[i];
            return 0;
        }
        const struct cli_flag *f = find_flag(c, a);
        if (!f) {
            snprintf(err, errlen, "unknown option '%s' (see brdfbench %s --help)", a, c->name);
            return EXIT_USAGE;
        }
        if (f->kind == CLI_RENAMED) {
            snprintf(err, errlen, "%s: not a flag of brdfbench %s: %s", f->name, c->name, f->help);
            return EXIT_USAGE;
        }
        if (f->given)
            *f->given = 1;
        if (f->kind == CLI_SWITCH) {
            if (a[strlen(f->name)] == '=') {
                snprintf(err, errlen, "%s: takes no value (got '%s')", f->name, a);
                return EXIT_USAGE;
            }
            *(int *)f->dest = f->set;
            if (strcmp(f->name, "--quiet") == 0)
                clsession_set_progress(0);   /* no progress lines of long builds either */
            return 0;
        }
        if (a[strlen(f->name)] != '=' && i + 1 >= argc) {
            snprintf(err, errlen, "%s: missing value (expected %s %s)", f->name, f->name, f->value);
            return EXIT_USAGE;
        }
        const char *v = cli_flag_value(argc, argv, &i, f->name, err, errlen);
        *ip = i;
        if (!v || store_value(f, v, err, errlen))
            return EXIT_USAGE;
        if (is_output_flag(f->name)) {
            output_flags[*noutputs] = f->name;
            outputs[(*noutputs)++] = v;
        } else {
            inputs[(*ninputs)++] = (char *)v;
        }
    }
    return 0;
}

/* ---- --help ---------------------------------------------------------------------------- */

#define HELP_COLUMN 21
#define HELP_WIDTH 100

/* The accepted values of a number as --help shows them. */
static void range_text(const struct cli_flag *f, char *buf, size_t len)
{
    buf[0] = '\0';
    if (f->range) {
        snprintf(buf, len, "%s", f->range);
    } else if (f->kind == CLI_INT || f->kind == CLI_LONG) {
        if (f->multiple > 0)
            snprintf(buf, len, "a multiple of %ld in [%ld, %ld]", f->multiple, (long)f->min, (long)f->max);
        else
            snprintf(buf, len, "in [%ld, %ld]", (long)f->min, (long)f->max);
    } else if (f->kind == CLI_DOUBLE) {
        if (f->min == 1e-300)
            snprintf(buf, len, "in (0, %g]", f->max);
        else
            snprintf(buf, len, "in [%g, %g]", f->min, f->max);
    }
}

static void default_text(const struct cli_flag *f, char *buf, size_t len)
{
    buf[0] = '\0';
    if (f->def) {
        snprintf(buf, len, "%s", f->def);
        return;
    }
    if (!f->dest)
        return;
    switch (f->kind) {
    case CLI_INT: snprintf(buf, len, "%d", *(const int *)f->dest); break;
    case CLI_LONG: snprintf(buf, len, "%ld", *(const long *)f->dest); break;
    case CLI_DOUBLE: snprintf(buf, len, "%g", *(const double *)f->dest); break;
    case CLI_TEXT:
    case CLI_PATH:
        if (*(const char *const *)f->dest)
            snprintf(buf, len, "%s", *(const char *const *)f->dest);
        break;
    default: break;
    }
}

/* Writes text from column `col`, breaking at spaces before HELP_WIDTH; every
 * further line starts at HELP_COLUMN. */
static void write_wrapped(FILE *out, const char *text, int col)
{
    const char *p = text;
    while (*p) {
        size_t len = strlen(p);
        size_t room = (size_t)(HELP_WIDTH - col);
        if (len > room) {
            size_t cut = room;
            while (cut > 0 && p[cut] != ' ')
                --cut;
            if (cut > 0)
                len = cut;
        }
        fprintf(out, "%.*s\n", (int)len, p);
        p += len;
        while (*p == ' ')
            ++p;
        if (*p)
            fprintf(out, "%*s", HELP_COLUMN, "");
        col = HELP_COLUMN;
    }
}

/* How the process prints a command's --help: main.c sets it around the one command it runs
   (a command's entry point takes only argc and argv), so it is the process's, not a run's. */
static enum cli_help_format help_format = CLI_HELP_TEXT;
static FILE *help_out;
static const char *command_summary, *command_example;

void cli_set_help_format(enum cli_help_format format, FILE *out)
{
    help_format = format;
    help_out = out;
}

void cli_set_command_info(const char *summary, const char *example)
{
    command_summary = summary;
    command_example = example;
}

void cli_write_roff(FILE *f, const char *text)
{
    int line_start = 1;
    for (const char *p = text; *p; ++p) {
        if (line_start && (*p == '.' || *p == '\''))
            fputs("\\&", f);
        if (*p == '\\')
            fputs("\\e", f);
        else if (*p == '-')
            fputs("\\-", f);
        else
            fputc(*p, f);
        line_start = *p == '\n';
    }
}

/* The text of a flag as --help shows it: its help, then its range and default. */
static void flag_text(const struct cli_flag *f, char *text, size_t len)
{
    char range[128], def[256];
    range_text(f, range, sizeof range);
    default_text(f, def, sizeof def);
    size_t used = (size_t)snprintf(text, len, "%s", f->help);
    if ((range[0] || def[0]) && used < len)
        snprintf(text + used, len - used, " (%s%s%s%s)", range, range[0] && def[0] ? "; " : "",
                 def[0] ? "default: " : "", def);
}

/* Lines of text that each begin with two spaces (a command's about and epilog), as roff. */
static void roff_paragraphs(FILE *out, const char *text)
{
    const char *p = text;
    while (*p) {
        const char *eol = strchr(p, '\n');
        size_t n = eol ? (size_t)(eol - p) : strlen(p);
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)n, p);
        const char *q = line;
        while (*q == ' ')
            ++q;
        if (*q) {
            cli_write_roff(out, q);
            fputc('\n', out);
        } else {
            fputs(".PP\n", out);
        }
        p += n;
        if (*p == '\n')
            ++p;
    }
}

/* The command's man page, brdfbench-NAME(1), from the same table as --help. */
static void print_man(FILE *out, const struct cli_command *c)
{
    char upper[64];
    snprintf(upper, sizeof upper, "%s", c->name);
    for (char *p = upper; *p; ++p)
        if (*p >= 'a' && *p <= 'z')
            *p = (char)(*p - 'a' + 'A');
    fprintf(out, ".\\\" brdfbench-%s(1): made by brdfbench help --man %s from its flag table\n", c->name, c->name);
    fprintf(out, ".TH BRDFBENCH\\-%s 1 \"\" \"brdfbench %s\" \"brdfbench manual\"\n", upper, BRDF_VERSION);
    fprintf(out, ".SH NAME\nbrdfbench\\-%s \\- ", c->name);
    cli_write_roff(out, command_summary ? command_summary : c->name);
    fprintf(out, "\n.SH SYNOPSIS\n.B brdfbench %s\n", c->name);
    cli_write_roff(out, c->synopsis ? c->synopsis : "[OPTIONS]");
    fputs("\n", out);
    if (c->about) {
        fputs(".SH DESCRIPTION\n", out);
        roff_paragraphs(out, c->about);
    }
    fputs(".SH OPTIONS\n", out);
    for (int k = 0; k < c->nflags; ++k) {
        const struct cli_flag *f = &c->flags[k];
        if (f->kind == CLI_RENAMED)
            continue;
        char text[1200];
        flag_text(f, text, sizeof text);
        fputs(".TP\n.B ", out);
        cli_write_roff(out, f->name);
        if (f->value) {
            fputs(" \\fI", out);
            cli_write_roff(out, f->value);
            fputs("\\fR", out);
        }
        fputc('\n', out);
        cli_write_roff(out, text);
        fputc('\n', out);
    }
    fputs(".TP\n.B \\-\\-help\\fR, \\fB\\-h\nthis help\n.TP\n.B \\-\\-version\nthe program's version and revision\n", out);
    if (c->epilog) {
        fputs(".SH NOTES\n", out);
        roff_paragraphs(out, c->epilog);
    }
    if (command_example) {
        fputs(".SH EXAMPLE\n.nf\n", out);
        cli_write_roff(out, command_example);
        fputs("\n.fi\n", out);
    }
    fputs(".SH SEE ALSO\n.BR brdfbench (1)\n", out);
}

/* One line per flag for the shell completions. */
static void print_words(FILE *out, const struct cli_command *c)
{
    for (int k = 0; k < c->nflags; ++k) {
        const struct cli_flag *f = &c->flags[k];
        if (f->kind == CLI_RENAMED)
            continue;
        /* the help up to its first ';' or '(' (a short description) */
        char desc[120];
        size_t n = strcspn(f->help, ";(\n\t");
        if (n > sizeof desc - 1)
            n = sizeof desc - 1;
        snprintf(desc, sizeof desc, "%.*s", (int)n, f->help);
        while (n > 0 && desc[n - 1] == ' ')
            desc[--n] = '\0';
        fprintf(out, "%s\t%s\t%s\n", f->name, f->value ? f->value : "", desc);
    }
    fprintf(out, "--help\t\tthis help\n--version\t\tthe program's version and revision\n");
}

void cli_print_help(FILE *out, const struct cli_command *c)
{
    if (help_out)
        out = help_out;
    if (help_format == CLI_HELP_MAN) {
        print_man(out, c);
        return;
    }
    if (help_format == CLI_HELP_WORDS) {
        print_words(out, c);
        return;
    }
    fprintf(out, "usage: brdfbench %s %s\n", c->name, c->synopsis ? c->synopsis : "[OPTIONS]");
    if (c->about)
        fputs(c->about, out);
    for (int k = 0; k < c->nflags; ++k) {
        const struct cli_flag *f = &c->flags[k];
        if (f->kind == CLI_RENAMED)
            continue;
        char head[64], text[1200];
        snprintf(head, sizeof head, "%s%s%s", f->name, f->value ? " " : "", f->value ? f->value : "");
        flag_text(f, text, sizeof text);
        int col = fprintf(out, "  %-*s", HELP_COLUMN - 3, head) + 0;
        if (col >= HELP_COLUMN) {   /* a long flag: the text starts on the next line */
            fprintf(out, "\n%*s", HELP_COLUMN, "");
        } else {
            fputc(' ', out);
        }
        write_wrapped(out, text, HELP_COLUMN);
    }
    fprintf(out, "  %-*s %s\n", HELP_COLUMN - 3, "--help, -h", "this help");
    fprintf(out, "  %-*s %s\n", HELP_COLUMN - 3, "--version", "the program's version and revision");
    if (c->epilog)
        fputs(c->epilog, out);
    if (command_example)
        fprintf(out, "example:\n  %s\n", command_example);
}

/* ---- shared flags ---------------------------------------------------------------------- */

/* A platform or device index, 0 to 63, into *index. */
static int parse_device_index(const char *flag, const char *value, int *index, char *err, size_t errlen)
{
    long v;
    if (cli_parse_long(flag, value, 0, 63, &v, err, errlen))
        return EXIT_USAGE;
    *index = (int)v;
    return 0;
}

int cli_call_platform(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    return parse_device_index(flag, value, &((struct device_options *)dest)->platform, err, errlen);
}

int cli_call_device(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    /* all and lists reach here only in the commands that do not take them (cli_devices.c) */
    if (cli_is_device_list(value)) {
        snprintf(err, errlen, "%s: '%s': all and lists are taken by throughput, accuracy and render "
                 "(accepted here: 0 to 63)", flag, value);
        return EXIT_USAGE;
    }
    return parse_device_index(flag, value, &((struct device_options *)dest)->device, err, errlen);
}

int cli_call_kernel_dir(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    char probe[4096];
    snprintf(probe, sizeof probe, "%s/brdf_models.h", value);
    char why[256];
    int fd = infile_open(probe, 0, NULL, why, sizeof why);
    if (fd < 0) {
        if (strncmp(why, "is ", 3) == 0)   /* there, but a FIFO, a device or a folder */
            snprintf(err, errlen, "%s: %s/brdf_models.h %s (accepted: a kernels/ folder)", flag, value, why);
        else
            snprintf(err, errlen, "%s: %s does not hold brdf_models.h (accepted: a kernels/ folder)", flag, value);
        return EXIT_USAGE;
    }
    close(fd);
    ((struct device_options *)dest)->kernel_dir = value;
    clsession_set_kernel_dir(value);
    return 0;
}

int cli_call_timeout(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    struct device_options *o = dest;
    if (cli_parse_double(flag, value, 0.01, CLSESSION_MAX_TIMEOUT, &o->timeout, err, errlen))
        return EXIT_USAGE;
    clsession_set_timeout(o->timeout, TIMEOUT_FLAG);
    return 0;
}

int cli_call_model_file(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    (void)dest;
    if (*value == '\0') {
        snprintf(err, errlen, "%s: empty file name", flag);
        return EXIT_USAGE;
    }
    /* The same file named twice (by the same or another path, a link) is read once: the
       registry gives the model it defined (usermodel_load_file), and no model is added. */
    const struct user_model *um = NULL;
    int before = usermodel_count();
    if (usermodel_load_file(value, &um, err, errlen))
        return EXIT_USAGE;
    if (um && usermodel_count() == before)
        cli_note("%s %s: the same file as %s, read once", flag, value, um->origin);
    return 0;
}

int cli_call_define(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    (void)dest;
    /* a define changes the files read after it: one after every file would change nothing */
    const struct user_model *last_file = NULL;   /* the latest model file read (the registry's) */
    for (int i = usermodel_count() - 1; i >= 0 && !last_file; --i)
        if (usermodel_at(i)->from_file)
            last_file = usermodel_at(i);
    if (last_file) {
        snprintf(err, errlen, "%s %.60s: given after --model-file %s; put -D before the --model-file flags it is "
                 "for", flag, value, last_file->origin);
        return EXIT_USAGE;
    }
    return shaderlang_define(value, err, errlen);
}

int cli_call_model_param(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    struct cli_model_params *p = dest;
    const char *eq = strchr(value, '=');
    if (!eq || eq == value || !eq[1] || strlen(value) >= sizeof p->text[0]) {
        snprintf(err, errlen, "%s: '%.60s' is not NAME=VALUE (e.g. %s divide_by_NdotL=0)", flag, value, flag);
        return EXIT_USAGE;
    }
    if (p->count >= CLI_MAX_MODEL_PARAMS) {
        snprintf(err, errlen, "%s: more than %d values (accepted: at most %d)", flag, CLI_MAX_MODEL_PARAMS,
                 CLI_MAX_MODEL_PARAMS);
        return EXIT_USAGE;
    }
    snprintf(p->text[p->count++], sizeof p->text[0], "%s", value);
    return 0;
}

int cli_apply_model_params(struct model_spec *models, int count, const struct cli_model_params *p, char *err,
                           size_t errlen)
{
    for (int i = 0; i < p->count; ++i) {
        const char *eq = strchr(p->text[i], '=');
        size_t nlen = (size_t)(eq - p->text[i]);
        int found = 0;
        for (int m = 0; m < count; ++m) {
            const struct model_info *info = models[m].info;
            int k = -1;
            for (int j = 0; j < info->nparams; ++j)
                if (strlen(info->params[j].name) == nlen && strncmp(info->params[j].name, p->text[i], nlen) == 0)
                    k = j;
            if (k < 0)
                continue;
            /* the model's spec again with this value: the spec parser checks the range */
            char spec[512];
            int len = snprintf(spec, sizeof spec, "%s", info->id);
            for (int j = 0; j < info->nparams && len > 0 && (size_t)len < sizeof spec; ++j) {
                if (j == k)
                    len += snprintf(spec + len, sizeof spec - (size_t)len, "%c%s", j ? ',' : ':', p->text[i]);
                else
                    len += snprintf(spec + len, sizeof spec - (size_t)len, "%c%s=%.17g", j ? ',' : ':',
                                    info->params[j].name, models[m].params[j]);
            }
            char inner[400];
            if (len <= 0 || (size_t)len >= sizeof spec || model_spec_parse(spec, &models[m], inner, sizeof inner)) {
                snprintf(err, errlen, "--param %s: %s", p->text[i], len > 0 && (size_t)len < sizeof spec ? inner :
                         "too long");
                return EXIT_USAGE;
            }
            found = 1;
        }
        if (!found) {
            snprintf(err, errlen, "--param: no listed model has a parameter '%.*s' (accepted: a parameter of a "
                                  "model of --models or --model-file; see brdfbench list)", (int)nlen, p->text[i]);
            return EXIT_USAGE;
        }
    }
    return 0;
}

int cli_call_model_expr(const char *flag, const char *value, void *dest, char *err, size_t errlen)
{
    (void)flag;
    (void)dest;
    struct user_model *um = NULL;
    if (usermodel_parse_expression(value, &um, err, errlen))
        return EXIT_USAGE;
    /* NAME=EXPR given again with the same EXPR: one model. Another EXPR under the same name
       is refused by usermodel_register. */
    const struct user_model *had = usermodel_of_info(models_find(um->name));
    if (had && !had->from_file && strcmp(had->formula, um->formula) == 0) {
        cli_note("--model %s: given twice with the same expression, read once", um->name);
        usermodel_free(um);
        return 0;
    }
    return usermodel_register(um, err, errlen) ? EXIT_USAGE : 0;
}

int cli_model_list(const char *text, struct model_spec *out, int max, char *err, size_t errlen)
{
    int n = model_spec_list_parse(text, out, max, err, errlen);
    if (n < 0)
        return n;
    /* The same model with the same parameters (the same canonical label) twice: once. */
    int kept = 0;
    for (int i = 0; i < n; ++i) {
        int seen = 0;
        for (int j = 0; j < kept && !seen; ++j)
            seen = strcmp(out[j].label, out[i].label) == 0;
        if (seen)
            cli_note("--models: %s given twice, measured once", out[i].label);
        else
            out[kept++] = out[i];
    }
    return kept;
}

int cli_add_unlisted_user_models(struct model_spec *models, int count, int max, char *err, size_t errlen)
{
    for (int i = 0; i < usermodel_count(); ++i) {
        const struct user_model *um = usermodel_at(i);
        int listed = 0;
        for (int k = 0; k < count && !listed; ++k)
            listed = models[k].info == &um->info;
        if (listed)
            continue;
        if (count >= max) {
            snprintf(err, errlen, "--models and the user models: at most %d models per run", max);
            return -2;
        }
        model_spec_default(&um->info, &models[count++]);
        cli_note("user model '%s' (%s) is not in --models: measured as well", um->name, um->origin);
    }
    return count;
}

int cli_frontier_default_models(struct model_spec *out, int max, char *err, size_t errlen)
{
    int count = frontier_default_models(out, max);
    return usermodel_append_all(out, &count, max, err, errlen) ? -2 : count;
}

/* ---- "-" as an output path ------------------------------------------------------------- */

int cli_is_stdout(const char *path) { return path && strcmp(path, "-") == 0; }

int cli_output_path(struct cli_output *o, const char *path, const char *name, const char **writer_path, char *err,
                    size_t errlen)
{
    memset(o, 0, sizeof *o);
    o->path = path;
    *writer_path = path;
    if (!cli_is_stdout(path))
        return 0;
    const char *tmp = getenv("TMPDIR");
    snprintf(o->tmp_dir, sizeof o->tmp_dir, "%s/brdfbench-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(o->tmp_dir)) {
        snprintf(err, errlen, "standard output: cannot make a temporary folder %s: %s", o->tmp_dir, strerror(errno));
        o->tmp_dir[0] = '\0';
        return EXIT_RUNTIME;
    }
    snprintf(o->tmp_path, sizeof o->tmp_path, "%s/%s", o->tmp_dir, name);
    *writer_path = o->tmp_path;
    return 0;
}

int cli_output_finish(struct cli_output *o, int ok, char *err, size_t errlen)
{
    if (!o->tmp_dir[0])
        return 0;
    int rc = 0;
    if (ok) {
        FILE *f = fopen(o->tmp_path, "rb");
        char buf[65536];
        size_t got;
        if (!f) {
            snprintf(err, errlen, "standard output: cannot read %s: %s", o->tmp_path, strerror(errno));
            rc = EXIT_RUNTIME;
        } else {
            while ((got = fread(buf, 1, sizeof buf, f)) > 0)
                if (fwrite(buf, 1, got, stdout) != got)
                    break;
            if (ferror(f) || fflush(stdout) != 0 || ferror(stdout)) {
                snprintf(err, errlen, "standard output: write failed: %s", strerror(errno));
                rc = EXIT_RUNTIME;
            }
            fclose(f);
        }
    }
    unlink(o->tmp_path);
    rmdir(o->tmp_dir);
    o->tmp_dir[0] = '\0';
    return rc;
}

int cli_temp_dir(char *dir, size_t len, char *err, size_t errlen)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, len, "%s/brdfbench-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        snprintf(err, errlen, "cannot make a temporary folder %s: %s", dir, strerror(errno));
        dir[0] = '\0';
        return EXIT_RUNTIME;
    }
    return 0;
}

void cli_temp_dir_remove(const char *dir)
{
    if (!dir || !dir[0])
        return;
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *e;
        char path[4096];
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0 ||
                path_join(path, sizeof path, dir, e->d_name) != 0)
                continue;
            /* a folder the run made in it (render/, frontier_teapot/): never a link followed */
            struct stat st;
            if (lstat(path, &st) == 0 && S_ISDIR(st.st_mode))
                cli_temp_dir_remove(path);
            else
                unlink(path);
        }
        closedir(d);
    }
    rmdir(dir);
}

int cli_deliver(const char *src, const char *flag, const char *dest, char *err, size_t errlen)
{
    FILE *f = fopen(src, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot read %s: %s", flag, src, strerror(errno));
        return EXIT_RUNTIME;
    }
    char *data = NULL;
    size_t len = 0, cap = 0, got;
    char buf[65536];
    while ((got = fread(buf, 1, sizeof buf, f)) > 0) {
        if (len + got > cap) {
            size_t nc = (len + got) * 2;
            char *nd = realloc(data, nc);
            if (!nd) {
                free(data);
                fclose(f);
                snprintf(err, errlen, "%s: out of memory", flag);
                return EXIT_RUNTIME;
            }
            data = nd;
            cap = nc;
        }
        memcpy(data + len, buf, got);
        len += got;
    }
    fclose(f);
    int rc = 0;
    if (cli_is_stdout(dest)) {
        if ((len && fwrite(data, 1, len, stdout) != len) || fflush(stdout) != 0) {
            snprintf(err, errlen, "%s: writing standard output failed: %s", flag, strerror(errno));
            rc = EXIT_RUNTIME;
        }
    } else if (write_file_atomic(dest, data ? data : "", len, err, errlen) != 0) {
        rc = EXIT_RUNTIME;
    }
    free(data);
    return rc;
}

int cli_parse_exit(const struct cli_command *c, int prc, const char *err)
{
    if (prc == CLI_ANSWERED)
        return EXIT_OK;
    fprintf(stderr, "brdfbench %s: %s\n", c->name, err);
    return EXIT_USAGE;
}
