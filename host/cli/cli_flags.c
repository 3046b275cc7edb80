/* cli_flags.c - the flags that several commands share and whose values belong to a lower
 * layer: the n grid (--n-min, --n-max, --n-step) and the user models (--model-file,
 * --model). The engines and the registry take values; only the command layer reads argv. */
#include "cli.h"

#include <stdio.h>

#include "accuracy.h"
#include "usermodel.h"

int accuracy_grid_flag(int argc, char **argv, int *i, double *n_min, double *n_max, double *n_step, char *err,
                       size_t errlen)
{
    static const char *const names[3] = { "--n-min", "--n-max", "--n-step" };
    double *const values[3] = { n_min, n_max, n_step };
    for (int k = 0; k < 3; ++k)
        if (cli_flag_is(argv[*i], names[k]))
            return cli_double_value(argc, argv, i, names[k], k < 2 ? ACC_MIN_N : 1e-300, ACC_MAX_N, values[k], err,
                                    errlen) ? -2 : 1;
    return 0;
}

int usermodel_cli_flag(int argc, char **argv, int *i, char *err, size_t errlen)
{
    const char *a = argv[*i];
    if (cli_flag_is(a, "--model-file")) {
        const char *v = cli_flag_value(argc, argv, i, "--model-file", err, errlen);
        if (!v)
            return -2;
        if (*v == '\0') {
            snprintf(err, errlen, "--model-file: empty file name");
            return -2;
        }
        return usermodel_load_file(v, NULL, err, errlen) ? -2 : 1;
    }
    if (cli_flag_is(a, "--model")) {
        const char *v = cli_flag_value(argc, argv, i, "--model", err, errlen);
        if (!v)
            return -2;
        struct user_model *um = NULL;
        if (usermodel_parse_expression(v, &um, err, errlen) || usermodel_register(um, err, errlen))
            return -2;
        return 1;
    }
    return 0;
}
