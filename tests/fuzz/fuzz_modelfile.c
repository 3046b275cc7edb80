/* fuzz_modelfile.c - libFuzzer target of the user-model parsers (host/core/usermodel.c): the model
 * file's header and the one-line --model NAME=EXPR form. Any input must be accepted or
 * refused with a message, never crash, leak or read out of bounds. Built and run by
 * scripts/fuzz.sh. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "usermodel.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[2048];
    struct user_model *um = NULL;
    err[0] = '\0';
    if (usermodel_parse_file_text((const char *)data, size, "fuzz.cl", &um, err, sizeof err) == 0) {
        /* An accepted model names itself and carries the text the device will compile. */
        if (!um || !um->name[0] || !um->device_source || um->info.nparams < 0 || um->info.nparams > 2)
            __builtin_trap();
        if (usermodel_register(um, err, sizeof err) == 0)
            usermodel_clear_all();
    } else if (err[0] == '\0') {
        __builtin_trap();
    }
    /* The same bytes as the value of --model (up to the first NUL). */
    char *arg = malloc(size + 1);
    if (!arg)
        return 0;
    memcpy(arg, data, size);
    arg[size] = '\0';
    um = NULL;
    err[0] = '\0';
    if (usermodel_parse_expression(arg, &um, err, sizeof err) == 0) {
        if (!um || !um->device_source || !strstr(um->device_source, um->formula))
            __builtin_trap();
        usermodel_free(um);
    } else if (err[0] == '\0') {
        __builtin_trap();
    }
    free(arg);
    return 0;
}
