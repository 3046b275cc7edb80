/* cli.c - checked number and flag parsing for every command. */
#include "cli.h"
#include "exitcodes.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cli_parse_double(const char *arg, const char *text, double min, double max,
                     double *out, char *err, size_t errlen)
{
    char *end = NULL;
    errno = 0;
    double v = text ? strtod(text, &end) : 0.0;
    if (!text || *text == '\0' || end == text || *end != '\0' || errno == ERANGE || !isfinite(v) ||
        v < min || v > max) {
        snprintf(err, errlen, "%s: '%s' is not a finite number in [%g, %g]", arg, text ? text : "",
                 min, max);
        return EXIT_USAGE;
    }
    *out = v;
    return 0;
}

int cli_parse_long(const char *arg, const char *text, long min, long max,
                   long *out, char *err, size_t errlen)
{
    char *end = NULL;
    errno = 0;
    long v = text ? strtol(text, &end, 10) : 0;
    if (!text || *text == '\0' || end == text || *end != '\0' || errno == ERANGE || v < min || v > max) {
        snprintf(err, errlen, "%s: '%s' is not an integer in [%ld, %ld]", arg, text ? text : "", min, max);
        return EXIT_USAGE;
    }
    *out = v;
    return 0;
}

int cli_parse_size_wxh(const char *arg, const char *text, long max_side,
                       long *width, long *height, char *err, size_t errlen)
{
    const char *x = text ? strpbrk(text, "xX") : NULL;
    char wbuf[32];
    if (!x || (size_t)(x - text) >= sizeof wbuf) {
        snprintf(err, errlen, "%s: '%s' is not WxH with W and H integers in [1, %ld]", arg,
                 text ? text : "", max_side);
        return EXIT_USAGE;
    }
    memcpy(wbuf, text, (size_t)(x - text));
    wbuf[x - text] = '\0';
    long w, h;
    char dummy[8];
    if (cli_parse_long(arg, wbuf, 1, max_side, &w, dummy, sizeof dummy) ||
        cli_parse_long(arg, x + 1, 1, max_side, &h, dummy, sizeof dummy)) {
        snprintf(err, errlen, "%s: '%s' is not WxH with W and H integers in [1, %ld]", arg, text, max_side);
        return EXIT_USAGE;
    }
    *width = w;
    *height = h;
    return 0;
}

int cli_flag_is(const char *argv_i, const char *name)
{
    size_t n = strlen(name);
    return strncmp(argv_i, name, n) == 0 && (argv_i[n] == '\0' || argv_i[n] == '=');
}

const char *cli_flag_value(int argc, char **argv, int *i, const char *name, char *err, size_t errlen)
{
    const char *a = argv[*i];
    size_t n = strlen(name);
    if (a[n] == '=')
        return a + n + 1;
    if (*i + 1 >= argc) {
        snprintf(err, errlen, "%s: missing value", name);
        return NULL;
    }
    return argv[++*i];
}

const char *cli_path_value(int argc, char **argv, int *i, const char *name, char *err, size_t errlen)
{
    const char *v = cli_flag_value(argc, argv, i, name, err, errlen);
    if (v && !*v) {
        snprintf(err, errlen, "%s: empty path (accepted: a folder or file name)", name);
        return NULL;
    }
    return v;
}

int cli_double_value(int argc, char **argv, int *i, const char *name, double min, double max,
                     double *out, char *err, size_t errlen)
{
    const char *v = cli_flag_value(argc, argv, i, name, err, errlen);
    return v ? cli_parse_double(name, v, min, max, out, err, errlen) : EXIT_USAGE;
}

int cli_long_value(int argc, char **argv, int *i, const char *name, long min, long max,
                   long *out, char *err, size_t errlen)
{
    const char *v = cli_flag_value(argc, argv, i, name, err, errlen);
    return v ? cli_parse_long(name, v, min, max, out, err, errlen) : EXIT_USAGE;
}

int cli_long_multiple_value(int argc, char **argv, int *i, const char *name, long min, long max, long multiple,
                            long *out, char *err, size_t errlen)
{
    if (cli_long_value(argc, argv, i, name, min, max, out, err, errlen))
        return EXIT_USAGE;
    if (*out % multiple != 0) {
        snprintf(err, errlen, "%s: %ld is not a multiple of %ld (accepted: a multiple of %ld in [%ld, %ld])", name,
                 *out, multiple, multiple, min, max);
        return EXIT_USAGE;
    }
    return 0;
}

int cli_mul_size(size_t a, size_t b, size_t *out)
{
    if (a != 0 && b > SIZE_MAX / a)
        return 0;
    *out = a * b;
    return 1;
}

#include "clsession.h"

void device_options_init(struct device_options *o)
{
    o->platform = -1;
    o->device = -1;
    o->kernel_dir = NULL;
    o->timeout = 0.0;
}

int cli_device_flag(int argc, char **argv, int *i, struct device_options *o, char *err, size_t errlen)
{
    const char *a = argv[*i];
    long v;
    if (cli_flag_is(a, "--platform") || cli_flag_is(a, "--device")) {
        const char *name = cli_flag_is(a, "--platform") ? "--platform" : "--device";
        const char *val = cli_flag_value(argc, argv, i, name, err, errlen);
        if (val && name[2] == 'd' && cli_is_device_list(val)) {
            snprintf(err, errlen, "--device: '%s': all and lists are taken by throughput, accuracy and render "
                     "(accepted here: 0 to 63)", val);
            return -2;
        }
        if (!val || cli_parse_long(name, val, 0, 63, &v, err, errlen))
            return -2;
        if (name[2] == 'p')
            o->platform = (int)v;
        else
            o->device = (int)v;
        return 1;
    }
    if (cli_flag_is(a, "--kernel-dir")) {
        const char *val = cli_flag_value(argc, argv, i, "--kernel-dir", err, errlen);
        if (!val)
            return -2;
        char probe[4096];
        snprintf(probe, sizeof probe, "%s/brdf_models.h", val);
        FILE *f = fopen(probe, "r");
        if (!f) {
            snprintf(err, errlen, "--kernel-dir: %s does not hold brdf_models.h (accepted: a kernels/ folder)", val);
            return -2;
        }
        fclose(f);
        o->kernel_dir = val;
        clsession_set_kernel_dir(val);
        return 1;
    }
    if (cli_flag_is(a, "--timeout")) {
        if (cli_double_value(argc, argv, i, "--timeout", 0.01, CLSESSION_MAX_TIMEOUT, &o->timeout, err, errlen))
            return -2;
        clsession_set_timeout(o->timeout, TIMEOUT_FLAG);
        return 1;
    }
    return 0;
}
