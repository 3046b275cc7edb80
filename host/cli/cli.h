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
/* As cli_flag_value, for a path: an empty value is refused too. */
const char *cli_path_value(int argc, char **argv, int *i, const char *name, char *err, size_t errlen);
/* The value of flag argv[*i] parsed as cli_parse_double / cli_parse_long do; advances *i.
 * Returns 0 or EXIT_USAGE with a message (a missing value, or one out of [min, max]). */
int cli_double_value(int argc, char **argv, int *i, const char *name, double min, double max,
                     double *out, char *err, size_t errlen);
int cli_long_value(int argc, char **argv, int *i, const char *name, long min, long max,
                   long *out, char *err, size_t errlen);
/* As cli_long_value, and the value must be a multiple of `multiple`. */
int cli_long_multiple_value(int argc, char **argv, int *i, const char *name, long min, long max, long multiple,
                            long *out, char *err, size_t errlen);
/* 1 when argv[i] is `name` or starts with `name=`. */
int cli_flag_is(const char *argv_i, const char *name);
/* size_t multiplication with overflow detection: returns 0 on overflow. */
int cli_mul_size(size_t a, size_t b, size_t *out);

/* Device selection flags shared by every command that runs kernels. */
struct device_options {
    int platform;            /* -1: the first platform with a device */
    int device;              /* -1: its first device */
    const char *kernel_dir;  /* NULL: the kernels embedded in the binary */
    double timeout;          /* --timeout: seconds per launch; 0: not given (applied at once) */
};
#define DEVICE_OPTIONS_HELP \
    "  --platform N       OpenCL platform index (default: the first with a device; see brdfbench list)\n" \
    "  --device N         device index on that platform (default 0)\n" \
    "  --kernel-dir DIR   read kernels/*.cl from DIR instead of the embedded copies\n" \
    "  --timeout SECONDS  deadline of each kernel launch, in [0.01, 604800] (default 300); past it the\n" \
    "                     run stops with exit 3 and its unfinished outputs removed\n"
void device_options_init(struct device_options *o);
/* Consumes argv[*i] if it is a device flag: returns 1 (consumed), 0 (not a device flag) or
 * EXIT_USAGE negated (-2) with a message. Applies --kernel-dir at once. */
int cli_device_flag(int argc, char **argv, int *i, struct device_options *o, char *err, size_t errlen);

/* --device all, or a list (0,1 or P:D pairs), on throughput, accuracy and render: when argv's
 * --device is one, runs cmd once per device (cli_devices.c) and gathers the rows of `file`
 * (its array `rows_key`) tagged with their device; returns that exit code. Returns -1 when
 * --device names one device (the command goes on as usual). */
int cli_per_device(int argc, char **argv, const char *command, int (*cmd)(int, char **), const char *file,
                   const char *rows_key);
int cli_is_device_list(const char *value);
#define DEVICE_LIST_HELP \
    "  --device all|LIST  every OpenCL device of every platform, or a list: 0,1 or P:D pairs (0:0,1:0);\n" \
    "                     one run per device in OUT/devices/<k>/, rows tagged with their device\n"

/* The grid flags --n-min, --n-max and --n-step, each in (0, ACC_MAX_N], as the accuracy and fit
 * commands take them: consumes argv[*i] if it is one of them and returns 1, returns 0 when it is
 * not, or -2 with a message. Ranges against each other are accuracy_grid_check's. */
int accuracy_grid_flag(int argc, char **argv, int *i, double *n_min, double *n_max, double *n_step, char *err,
                       size_t errlen);

/* The flags every command that evaluates models takes; call it in the flag loop like
 * cli_device_flag: returns 1 (consumed), 0 (not one of them) or -2 with a message. */
int usermodel_cli_flag(int argc, char **argv, int *i, char *err, size_t errlen);

#endif
