/* cli.h - checked parsing of command-line values. Parsers return 0 or EXIT_USAGE and write
 * a one-line message naming the argument and its accepted range; none calls exit(). */
#ifndef BRDF_CLI_H
#define BRDF_CLI_H

#include <stddef.h>

int cli_parse_double(const char *arg, const char *text, double min, double max,
                     double *out, char *err, size_t errlen);
int cli_parse_long(const char *arg, const char *text, long min, long max,
                   long *out, char *err, size_t errlen);
/* "WxH" with both sides in [1, max_side]. */
int cli_parse_size_wxh(const char *arg, const char *text, long max_side,
                       long *width, long *height, char *err, size_t errlen);
/* The value of flag argv[*i] (either "--flag=value" or "--flag value"); advances *i.
 * Returns NULL and writes a message when the value is missing. `name` is the flag. */
const char *cli_flag_value(int argc, char **argv, int *i, const char *name, char *err, size_t errlen);
/* 1 when argv[i] is `name` or starts with `name=`. */
int cli_flag_is(const char *argv_i, const char *name);
/* prefix and argv[1..argc-1] as one shell command line, each argument that a shell would split or
 * expand in single quotes (a ' inside as '\''), so that the line run again is the same command;
 * cut at len - 1 bytes (an argument that does not fit whole is left out). */
void cli_shell_join(char *out, size_t len, const char *prefix, int argc, char **argv);

/* Device selection flags shared by every command that runs kernels. */
struct device_options {
    int platform;            /* -1: the first platform with a device */
    int device;              /* -1: its first device */
    const char *kernel_dir;  /* NULL: the kernels embedded in the binary */
    double timeout;          /* --timeout: seconds per launch; 0: not given (applied at once) */
};
void device_options_init(struct device_options *o);
/* The device flags themselves are in cli_table.h (CLI_FLAGS_DEVICE). */

/* --device all, or a list (0,1 or P:D pairs), on throughput, accuracy and render: when argv's
 * --device is one, runs cmd once per device (cli_devices.c) and gathers the rows of `file`
 * (its array `rows_key`) tagged with their device, and the rows of CSV file `csv` (NULL: none)
 * with a first column device; returns that exit code. Returns -1 when
 * --device names one device (the command goes on as usual). */
/* After a throughput run with --ab-options: RUN/ab/a/throughput.json (the default variant's rows)
 * and RUN/ab/b/throughput.json (the ab variant's, as the default variant), for compare.
 * Returns 0, or EXIT_RUNTIME with err filled. */
int cli_write_ab(const char *run_dir, const char *ab_options, char *err, size_t errlen);
int cli_per_device(int argc, char **argv, const char *command, int (*cmd)(int, char **), const char *file,
                   const char *rows_key, const char *csv);
int cli_is_device_list(const char *value);

#endif
