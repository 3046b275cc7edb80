/* test_cli_table.c - the declarative flag table: values land where the table says, each in
 * its range; a refused value names the flag and its range; a flag of another command is
 * refused with the right name; --help shows every flag of the table (and no renamed one);
 * the same model twice in --models is one; a parameter twice is refused. */
#define _POSIX_C_SOURCE 200809L
#include "check.h"
#include "cli.h"
#include "cli_table.h"
#include "exitcodes.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

static int parse(const struct cli_command *c, struct cli_args *args, char *err, size_t errlen, ...)
{
    char *argv[32];
    int argc = 0;
    argv[argc++] = (char *)c->name;
    va_list ap;
    va_start(ap, errlen);
    for (char *a; (a = va_arg(ap, char *)) != NULL;)
        argv[argc++] = a;
    va_end(ap);
    err[0] = '\0';
    return cli_parse(c, argc, argv, args, err, errlen);
}

int main(void)
{
    double n_min = 2, n_max = 1000, x = 0.5;
    long samples = 4096;
    int quiet = 0, images = 1, reps = 7, x_given = 0;
    const char *out = NULL;
    const struct cli_flag flags[] = {
        CLI_FLAG_N_MIN(&n_min),
        CLI_FLAG_N_MAX(&n_max),
        CLI_FLAG_SAMPLES(&samples),
        CLI_FLAG_OUT(&out, CLI_DEF_OUT),
        CLI_FLAG_QUIET(&quiet),
        { .name = "--no-images", .kind = CLI_SWITCH, .dest = &images, .set = 0, .help = "no pictures" },
        { .name = "--reps", .value = "N", .kind = CLI_INT, .dest = &reps, .min = 1, .max = 1000, .help = "launches" },
        { .name = "--x", .value = "X", .kind = CLI_DOUBLE, .dest = &x, .min = 0, .max = 1, .given = &x_given,
          .help = "a fraction" },
        { .name = "--n", .kind = CLI_RENAMED, .help = "the shininess is --mesh-n X" },
    };
    const struct cli_command cmd = { .name = "demo", .flags = flags, .nflags = 9, .max_positional = 1 };
    struct cli_args args;
    char err[512];

    /* values in both spellings, in their places */
    int rc = parse(&cmd, &args, err, sizeof err, "--n-min", "3.5", "--n-max=20", "--samples", "32", "--quiet",
                   "--no-images", "--reps=3", "--out", "dir", "RUN", NULL);
    CHECK(rc == 0, "rc %d: %s", rc, err);
    CHECK(n_min == 3.5 && n_max == 20 && samples == 32 && quiet == 1 && images == 0 && reps == 3, "values");
    CHECK(out && strcmp(out, "dir") == 0, "out");
    CHECK(args.npositional == 1 && strcmp(args.positional[0], "RUN") == 0, "positional");
    CHECK(x_given == 0 && x == 0.5, "--x untouched and not given");
    CHECK(parse(&cmd, &args, err, sizeof err, "--x", "1", NULL) == 0 && x_given == 1 && x == 1, "--x given");

    /* refusals: one line naming the flag and the accepted range */
    CHECK(parse(&cmd, &args, err, sizeof err, "--samples", "100", NULL) == EXIT_USAGE &&
              strcmp(err, "--samples: 100 is not a multiple of 16 (accepted: a multiple of 16 in [16, 4194304])") == 0,
          "%s", err);
    CHECK(parse(&cmd, &args, err, sizeof err, "--x", "1.5", NULL) == EXIT_USAGE &&
              strcmp(err, "--x: '1.5' is not a finite number in [0, 1]") == 0, "%s", err);
    CHECK(parse(&cmd, &args, err, sizeof err, "--reps", NULL) == EXIT_USAGE &&
              strcmp(err, "--reps: missing value (expected --reps N)") == 0, "%s", err);
    CHECK(parse(&cmd, &args, err, sizeof err, "--quiet=yes", NULL) == EXIT_USAGE &&
              strstr(err, "--quiet: takes no value") == err, "%s", err);
    CHECK(parse(&cmd, &args, err, sizeof err, "--n", "64", NULL) == EXIT_USAGE &&
              strcmp(err, "--n: not a flag of brdfbench demo: the shininess is --mesh-n X") == 0, "%s", err);
    CHECK(parse(&cmd, &args, err, sizeof err, "--n-mi", "3", NULL) == EXIT_USAGE &&
              strcmp(err, "unknown option '--n-mi' (see brdfbench demo --help)") == 0, "a prefix is not the flag: %s", err);
    CHECK(parse(&cmd, &args, err, sizeof err, "a", "b", NULL) == EXIT_USAGE &&
              strcmp(err, "unexpected argument 'b' (see brdfbench demo --help)") == 0, "%s", err);

    /* --help: every flag of the table but the renamed one, with --help and --version */
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    cli_print_help(m, &cmd);
    fclose(m);
    for (int k = 0; k < cmd.nflags; ++k) {
        char head[64];
        snprintf(head, sizeof head, "\n  %s ", flags[k].name);
        if (flags[k].kind == CLI_RENAMED)
            CHECK(strstr(text, head) == NULL, "%s (renamed) is not in --help", flags[k].name);
        else
            CHECK(strstr(text, head) != NULL, "%s in --help:\n%s", flags[k].name, text);
    }
    CHECK(strstr(text, "\n  --help, -h ") && strstr(text, "\n  --version "), "--help and --version in --help");
    /* the range and the default come from the table and the value before parsing */
    CHECK(strstr(text, "(in [1, 1000]; default: 3)") != NULL, "--reps range and default:\n%s", text);
    free(text);

    /* the model list: a model given twice is one; a parameter given twice is refused */
    struct model_spec list[8];
    int n = cli_model_list("fq2,cq2,fq2,fq,fq:Q=0.64", list, 8, err, sizeof err);
    CHECK(n == 3 && strcmp(list[0].label, "fq2") == 0 && strcmp(list[1].label, "cq2") == 0 &&
              strcmp(list[2].info->id, "fq") == 0, "n = %d", n);
    n = cli_model_list("fq:Q=0.5,fq:Q=0.6", list, 8, err, sizeof err);
    CHECK(n == 2, "two values of Q are two models: %d", n);
    CHECK(cli_model_list("fq:Q=0.5,Q=0.6", list, 8, err, sizeof err) < 0 &&
              strstr(err, "model 'fq': parameter Q given twice") == err, "%s", err);
    CHECK_CASE("shell line of a command (run.json's command)");
    {
        /* expected lines written by hand: plain words as they are, a word with a blank, a
           paren, a quote or a glob in single quotes, a ' inside as '\'' */
        char *argv[] = { "all", "--quick", "--model", "q=pow(c, n)", "--out", "res/it's", "*", "" };
        char line[256];
        cli_shell_join(line, sizeof line, "brdfbench all", 8, argv);
        CHECK(strcmp(line, "brdfbench all --quick --model 'q=pow(c, n)' --out 'res/it'\\''s' '*' ''") == 0,
              "quoted line: %s", line);
        char small[32];
        cli_shell_join(small, sizeof small, "brdfbench all", 4, argv);
        CHECK(strcmp(small, "brdfbench all --quick --model") == 0, "an argument that does not fit is left out: %s",
              small);
    }
    return check_summary();
}
