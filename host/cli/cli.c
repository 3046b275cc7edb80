/* cli.c - checked number and flag parsing for every command. */
#include "cli.h"
#include "exitcodes.h"

#include <ctype.h>
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

#include "clsession.h"

void device_options_init(struct device_options *o)
{
    o->platform = -1;
    o->device = -1;
    o->kernel_dir = NULL;
    o->timeout = 0.0;
}

/* Whether a shell would take the argument as one word as it is: nonempty, and only characters
   that are neither blanks, quotes, globs nor operators. */
static int shell_plain(const char *a)
{
    if (!*a)
        return 0;
    for (const char *p = a; *p; ++p)
        if (!(isalnum((unsigned char)*p) || strchr("_-./:=,+@%", *p)))
            return 0;
    return 1;
}

void cli_shell_join(char *out, size_t len, const char *prefix, int argc, char **argv)
{
    if (!len)
        return;
    size_t used = (size_t)snprintf(out, len, "%s", prefix);
    if (used >= len)
        return;
    char word[4096];
    for (int i = 1; i < argc; ++i) {
        size_t w = 0;
        int plain = shell_plain(argv[i]);
        if (!plain)
            word[w++] = '\'';
        for (const char *p = argv[i]; *p && w + 6 < sizeof word; ++p) {
            if (*p == '\'' && !plain) {
                memcpy(word + w, "'\\''", 4);
                w += 4;
            } else {
                word[w++] = *p;
            }
        }
        if (!plain)
            word[w++] = '\'';
        word[w] = '\0';
        if (used + 1 + w >= len)
            return;   /* a cut argument would be another command */
        used += (size_t)snprintf(out + used, len - used, " %s", word);
    }
}
