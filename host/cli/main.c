/* main.c - the brdfbench command line: dispatches to one subcommand; `help` writes a command's
 * help, the man pages and the shell completions, all from the commands' flag tables. */
#define _POSIX_C_SOURCE 200809L   /* open_memstream */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_table.h"
#include "commands.h"
#include "context.h"
#include "exitcodes.h"
#include "outdir.h"

struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *help;
    const char *example;   /* one command line, shown by --help and the man page */
};

static int cmd_help(int argc, char **argv);

static const struct command commands[] = {
    { "list", cmd_list, "the models (formulas, parameters, references) and the OpenCL devices",
      "brdfbench list --json -" },
    { "accuracy", cmd_accuracy, "dense-grid accuracy sweep of models on the OpenCL device",
      "brdfbench accuracy --models fq2,cq2,lyon:k=2 --n-min 2 --n-max 1000 --out results/acc" },
    { "all", cmd_all, "the main job: every sweep, heatmap, plot and report.md in results/<date-time>/",
      "brdfbench all --quick --models fq2,cq2,phong" },
    { "plot", cmd_plot, "redraw every picture of a run folder from its JSON (no device)",
      "brdfbench plot results/latest" },
    { "report", cmd_report, "rebuild report.md of a run folder from its files alone (no device)",
      "brdfbench report results/latest --output -" },
    { "rows", cmd_rows, "the figures of result files as rows: keys, metrics with unit and direction (md, csv, json)",
      "brdfbench rows results/latest/throughput.json --format csv" },
    { "heatmap", cmd_heatmap, "redraw the heatmaps of a run folder from its field JSON (no device)",
      "brdfbench heatmap results/latest --label fq2" },
    { "gate", cmd_gate, "accuracy gates for CI: checks figures of a gates file against bounds (JUnit, JSON)",
      "brdfbench gate gates.json --junit gates.xml" },
    { "render", cmd_render, "full-image shading passes (spheres, teapot, bunny): error images, metrics, Mpixel/s",
      "brdfbench render --scene spheres --models phong,fq2,cq2" },
    { "reproduce", cmd_reproduce, "re-derive every claim of both papers: claims.json, claims.md and a table",
      "brdfbench reproduce --out results/claims" },
    { "fit", cmd_fit, "the cosine-quadratic family's accuracy limit and its best affine k(n) (quad:a=..,b=..)",
      "brdfbench fit --n-min 2 --n-max 1000" },
    { "throughput", cmd_throughput, "evaluations/s of every model vs pow(), tuned C and the device peak; build-option variants",
      "brdfbench throughput --models fq2,phong,phongpow" },
    { "version", cmd_version, "the program's version and git revision (also --version after any command)",
      "brdfbench version" },
    { "compare", cmd_compare, "runs side by side against a baseline: faster/slower/same, accuracy changes (no device)",
      "brdfbench compare results/before results/after" },
    /* more commands below, one per line */
    { "frontier", cmd_frontier, "cost against accuracy of every lobe approximation: the Pareto front, plots, which to ship",
      "brdfbench frontier --out results/frontier" },
    { "measured", cmd_measured, "measured materials (MERL files): Blinn-Phong and Cook-Torrance fits, every cheap lobe against them",
      "brdfbench measured merl/gold-metallic-paint.binary" },
    { "store", cmd_store, "the store of runs (SQLite): add run folders, list them, export them as rows documents",
      "brdfbench store add results/latest --db results/history.sqlite" },
    { "history", cmd_history, "each row's series over stored runs or run folders: change points, trend picture, CI check",
      "brdfbench history --db results/history.sqlite --fail-if-slower 10" },
    { "help", cmd_help, "a command's options (help COMMAND), its man page, or the shell completions",
      "brdfbench help accuracy" },
};
#define NCOMMANDS (sizeof commands / sizeof commands[0])

static void usage(FILE *f)
{
    fprintf(f, "usage: brdfbench COMMAND [OPTIONS]   (brdfbench COMMAND --help for its options)\n\ncommands:\n");
    for (size_t i = 0; i < NCOMMANDS; ++i)
        fprintf(f, "  %-12s %s\n", commands[i].name, commands[i].help);
}

static const struct command *find_command(const char *name)
{
    for (size_t i = 0; i < NCOMMANDS; ++i)
        if (strcmp(name, commands[i].name) == 0)
            return &commands[i];
    return NULL;
}

static int unknown_command(const char *name)
{
    fprintf(stderr, "brdfbench: unknown command '%s' (accepted:", name);
    for (size_t i = 0; i < NCOMMANDS; ++i)
        fprintf(stderr, " %s", commands[i].name);
    fprintf(stderr, ")\n");
    return EXIT_USAGE;
}

/* Runs a command's --help in the given format into out. */
static int command_help(const struct command *c, enum cli_help_format format, FILE *out)
{
    char name[64], help[] = "--help";
    snprintf(name, sizeof name, "%s", c->name);
    char *argv[] = { name, help, NULL };
    cli_set_command_info(c->help, c->example);
    cli_set_help_format(format, out);
    int rc = c->run(2, argv);
    cli_set_help_format(CLI_HELP_TEXT, NULL);
    return rc;
}

/* brdfbench(1): the commands and where their pages are. */
static void print_main_man(FILE *f)
{
    fprintf(f, ".\\\" brdfbench(1): made by brdfbench help --man from its command table\n");
    fprintf(f, ".TH BRDFBENCH 1 \"\" \"brdfbench %s\" \"brdfbench manual\"\n", BRDF_VERSION);
    fprintf(f, ".SH NAME\nbrdfbench \\- accuracy and throughput harness for BRDF lobe models\n");
    fprintf(f, ".SH SYNOPSIS\n.B brdfbench\n\\fICOMMAND\\fR [OPTIONS]\n");
    fprintf(f, ".SH DESCRIPTION\nEach command has its own page, \\fBbrdfbench\\-COMMAND\\fR(1), and its "
               "options in \\fBbrdfbench help COMMAND\\fR.\n.SH COMMANDS\n");
    for (size_t i = 0; i < NCOMMANDS; ++i) {
        fprintf(f, ".TP\n.B %s\n", commands[i].name);
        cli_write_roff(f, commands[i].help);
        fprintf(f, " (\\fBbrdfbench\\-%s\\fR(1))\n", commands[i].name);
    }
    fprintf(f, ".SH EXIT STATUS\n0 success, 1 a gate or a compare condition failed, 2 bad usage or input, "
               "3 a runtime or OpenCL error, 77 no OpenCL device.\n.SH SEE ALSO\n");
    for (size_t i = 0; i < NCOMMANDS; ++i)
        fprintf(f, ".BR brdfbench\\-%s (1)%s\n", commands[i].name, i + 1 < NCOMMANDS ? "," : "");
}

/* A command's flags, as print_words writes them ("FLAG\tVALUE\tHELP" lines), read back. */
struct flag_word {
    char name[40], value[24], desc[120];
};
static int command_words(const struct command *c, struct flag_word *w, int max)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (!m)
        return -1;
    command_help(c, CLI_HELP_WORDS, m);
    fclose(m);
    int n = 0;
    for (char *line = buf, *next; line && *line && n < max; line = next) {
        next = strchr(line, '\n');
        if (next)
            *next++ = '\0';
        char *t1 = strchr(line, '\t'), *t2 = t1 ? strchr(t1 + 1, '\t') : NULL;
        if (!t2)
            continue;
        *t1 = *t2 = '\0';
        snprintf(w[n].name, sizeof w[n].name, "%s", line);
        snprintf(w[n].value, sizeof w[n].value, "%s", t1 + 1);
        snprintf(w[n].desc, sizeof w[n].desc, "%s", t2 + 1);
        ++n;
    }
    free(buf);
    return n;
}

static int is_path_value(const char *v)
{
    return strstr(v, "FILE") || strstr(v, "DIR") || strstr(v, "PATH");
}

#define MAX_WORDS 96

/* The case branches of a completion script: "    COMMAND)" for every command, then what `branch`
 * writes for that shell from the command's flags. */
static void print_command_branches(FILE *f, void (*branch)(FILE *f, const struct command *c,
                                                           const struct flag_word *w, int n))
{
    struct flag_word w[MAX_WORDS];
    for (size_t i = 0; i < NCOMMANDS; ++i) {
        int n = command_words(&commands[i], w, MAX_WORDS);
        fprintf(f, "    %s)\n", commands[i].name);
        branch(f, &commands[i], w, n);
    }
}

/* bash: the command's flags, and those that take a path. */
static void bash_branch(FILE *f, const struct command *c, const struct flag_word *w, int n)
{
    (void)c;
    fprintf(f, "        flags=\"");
    for (int k = 0; k < n; ++k)
        fprintf(f, "%s%s", k ? " " : "", w[k].name);
    fprintf(f, "\"\n        paths=\"");
    int first = 1;
    for (int k = 0; k < n; ++k)
        if (is_path_value(w[k].value)) {
            fprintf(f, "%s%s", first ? "" : " ", w[k].name);
            first = 0;
        }
    fprintf(f, "\" ;;\n");
}

static void print_bash_completion(FILE *f)
{
    fprintf(f, "# bash completion for brdfbench: made by brdfbench help --completion bash from its flag tables\n");
    fprintf(f, "_brdfbench() {\n    local cur=\"${COMP_WORDS[COMP_CWORD]}\" prev=\"${COMP_WORDS[COMP_CWORD-1]}\"\n");
    fprintf(f, "    local commands=\"");
    for (size_t i = 0; i < NCOMMANDS; ++i)
        fprintf(f, "%s ", commands[i].name);
    fprintf(f, "\"\n");
    fprintf(f, "    if [ \"$COMP_CWORD\" -eq 1 ]; then\n        COMPREPLY=($(compgen -W \"$commands\" -- \"$cur\"))\n"
               "        return\n    fi\n    local flags=\"\" paths=\"\"\n    case \"${COMP_WORDS[1]}\" in\n");
    print_command_branches(f, bash_branch);
    fprintf(f, "    esac\n    if [ \"${COMP_WORDS[1]}\" = help ] && [[ \"$cur\" != -* ]]; then\n"
               "        COMPREPLY=($(compgen -W \"$commands\" -- \"$cur\"))\n        return\n    fi\n");
    fprintf(f, "    local p\n    for p in $paths; do\n        if [ \"$prev\" = \"$p\" ]; then\n"
               "            COMPREPLY=($(compgen -f -- \"$cur\"))\n            return\n        fi\n    done\n");
    fprintf(f, "    if [[ \"$cur\" == -* ]]; then\n        COMPREPLY=($(compgen -W \"$flags\" -- \"$cur\"))\n"
               "    else\n        COMPREPLY=($(compgen -f -- \"$cur\"))\n    fi\n}\n");
    fprintf(f, "complete -F _brdfbench brdfbench\n");
}

/* A description in a single-quoted zsh word: quotes closed and reopened; inside an _arguments
 * spec's [DESC] (brackets) also its brackets and backslashes escaped. */
static void zsh_desc(FILE *f, const char *s, int brackets)
{
    for (const char *p = s; *p; ++p) {
        if (*p == '\'')
            fputs("'\\''", f);
        else if (brackets && (*p == '[' || *p == ']' || *p == '\\'))
            fprintf(f, "\\%c", *p);
        else
            fputc(*p, f);
    }
}

/* zsh: an _arguments spec per flag; help takes a command, the others files. */
static void zsh_branch(FILE *f, const struct command *c, const struct flag_word *w, int n)
{
    fprintf(f, "        _arguments \\\n");
    for (int k = 0; k < n; ++k) {
        fprintf(f, "            '%s[", w[k].name);
        zsh_desc(f, w[k].desc, 1);
        fprintf(f, "]");
        if (w[k].value[0])
            fprintf(f, ":%s:%s", w[k].value, is_path_value(w[k].value) ? "_files" : "");
        fprintf(f, "' \\\n");
    }
    if (strcmp(c->name, "help") == 0) {
        fprintf(f, "            '1:command:(");
        for (size_t j = 0; j < NCOMMANDS; ++j)
            fprintf(f, "%s%s", j ? " " : "", commands[j].name);
        fprintf(f, ")' ;;\n");
    } else {
        fprintf(f, "            '*:argument:_files' ;;\n");
    }
}

static void print_zsh_completion(FILE *f)
{
    fprintf(f, "#compdef brdfbench\n# zsh completion for brdfbench: made by brdfbench help --completion zsh from "
               "its flag tables\n_brdfbench() {\n    local -a commands\n    commands=(\n");
    for (size_t i = 0; i < NCOMMANDS; ++i) {
        fprintf(f, "        '%s:", commands[i].name);
        zsh_desc(f, commands[i].help, 0);
        fprintf(f, "'\n");
    }
    fprintf(f, "    )\n");
    fprintf(f, "    if (( CURRENT == 2 )); then\n        _describe 'command' commands\n        return\n    fi\n"
               "    local cmd=$words[2]\n    shift words\n    (( CURRENT-- ))\n    case $cmd in\n");
    print_command_branches(f, zsh_branch);
    fprintf(f, "    esac\n}\n_brdfbench \"$@\"\n");
}

/* Writes to path (NULL: standard output) through a temporary file, so a failure leaves no half file. */
static int write_output(const char *path, void (*writer)(FILE *, const void *), const void *arg)
{
    if (!path) {
        writer(stdout, arg);
        return fflush(stdout) ? EXIT_RUNTIME : EXIT_OK;
    }
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        fprintf(stderr, "brdfbench help: cannot write %s: %s\n", tmp, strerror(errno));
        return EXIT_RUNTIME;
    }
    writer(f, arg);
    int bad = ferror(f);
    if (fclose(f) || bad || rename(tmp, path)) {
        fprintf(stderr, "brdfbench help: cannot write %s: %s\n", path, strerror(errno));
        remove(tmp);
        return EXIT_RUNTIME;
    }
    return EXIT_OK;
}

static void write_main_man(FILE *f, const void *arg) { (void)arg; print_main_man(f); }
static void write_command_man(FILE *f, const void *arg) { command_help(arg, CLI_HELP_MAN, f); }
static void write_bash(FILE *f, const void *arg) { (void)arg; print_bash_completion(f); }
static void write_zsh(FILE *f, const void *arg) { (void)arg; print_zsh_completion(f); }

/* brdfbench help [COMMAND | --man [COMMAND] | --man-dir DIR | --completion bash|zsh [FILE]] */
static int cmd_help(int argc, char **argv)
{
    int man = 0;
    const char *man_dir = NULL, *shell = NULL;
    const struct cli_flag flags[] = {
        { .name = "--man", .kind = CLI_SWITCH, .dest = &man, .set = 1,
          .help = "write the man page of COMMAND (roff), or without COMMAND brdfbench(1)" },
        { .name = "--man-dir", .value = "DIR", .kind = CLI_PATH, .dest = &man_dir, .def = "",
          .help = "write every man page into folder DIR: brdfbench.1 and brdfbench-COMMAND.1" },
        { .name = "--completion", .value = "SHELL", .kind = CLI_TEXT, .dest = &shell, .def = "",
          .range = "bash or zsh", .help = "write the shell completion script, to the FILE given after it or "
                                          "to standard output" },
    };
    const struct cli_command cmd = {
        .name = "help",
        .synopsis = "[COMMAND | --man [COMMAND] | --man-dir DIR | --completion bash|zsh [FILE]]",
        .about = "  Writes a command's options (as COMMAND --help does), its man page, or the shell\n"
                 "  completions; all of them are made from the commands' flag tables.\n",
        CLI_TABLE(flags),
        .max_positional = 1,
    };
    struct cli_args args;
    char err[512];
    int prc = cli_parse(&cmd, argc, argv, &args, err, sizeof err);
    if (prc)
        return cli_parse_exit(&cmd, prc, err);
    const char *word = args.npositional ? args.positional[0] : NULL;
    if ((man != 0) + (man_dir != NULL) + (shell != NULL) > 1) {
        fprintf(stderr, "brdfbench help: --man, --man-dir and --completion: one at a time\n");
        return EXIT_USAGE;
    }
    if (shell) {
        if (strcmp(shell, "bash") != 0 && strcmp(shell, "zsh") != 0) {
            fprintf(stderr, "brdfbench help: --completion: '%s' is not a shell of the completions (accepted: bash, "
                            "zsh)\n", shell);
            return EXIT_USAGE;
        }
        return write_output(word, strcmp(shell, "bash") == 0 ? write_bash : write_zsh, NULL);
    }
    if (man_dir) {
        if (word) {
            fprintf(stderr, "brdfbench help: --man-dir writes every page: no COMMAND (got '%s')\n", word);
            return EXIT_USAGE;
        }
        char path[4096];
        snprintf(path, sizeof path, "%s/brdfbench.1", man_dir);
        int rc = write_output(path, write_main_man, NULL);
        for (size_t i = 0; i < NCOMMANDS && rc == EXIT_OK; ++i) {
            snprintf(path, sizeof path, "%s/brdfbench-%s.1", man_dir, commands[i].name);
            rc = write_output(path, write_command_man, &commands[i]);
        }
        return rc;
    }
    if (!word) {
        if (man)
            return write_output(NULL, write_main_man, NULL);
        usage(stdout);
        return EXIT_OK;
    }
    const struct command *c = find_command(word);
    if (!c)
        return unknown_command(word);
    return man ? write_output(NULL, write_command_man, c) : command_help(c, CLI_HELP_TEXT, NULL);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return EXIT_USAGE;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        usage(stdout);
        return EXIT_OK;
    }
    if (strcmp(argv[1], "--version") == 0) {
        cli_print_version(stdout);
        return EXIT_OK;
    }
    /* -h is --help for every command (no command takes -h otherwise). */
    static char help_flag[] = "--help";
    for (int i = 2; i < argc; ++i)
        if (strcmp(argv[i], "-h") == 0)
            argv[i] = help_flag;
    /* a run stopped by a signal leaves no half-written outputs (outdir.h) */
    outdir_install_signal_handlers();
    const struct command *c = find_command(argv[1]);
    if (!c)
        return unknown_command(argv[1]);
    cli_set_command_info(c->help, c->example);
    int rc = c->run(argc - 1, argv + 1);
    /* A run that failed leaves no empty folder it made (a folder that existed stays). */
    if (rc != EXIT_OK && rc != EXIT_GATE_FAIL)
        outdir_remove_own_empty();
    return rc;
}
