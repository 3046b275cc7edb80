/* fuzz_gates.c - libFuzzer target of the gates-file parser (host/results/gate.c on host/output/jsonr.c):
 * any input must be accepted or refused with a message, never crash, hang, leak or read out
 * of bounds. Model files named in the input are looked up in a folder that does not exist.
 * Built and run by scripts/fuzz.sh. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "exitcodes.h"
#include "gate.h"
#include "usermodel.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct gate_set gs;
    char err[2048];
    err[0] = '\0';
    int rc = gate_set_parse_text((const char *)data, size, "fuzz.json", "/nonexistent-brdfbench-fuzz", 0, &gs, err,
                                 sizeof err);
    if (rc == 0) {
        /* A parsed set is complete: every gate has a model, a metric and a bound. */
        for (int i = 0; i < gs.count; ++i)
            if (!gs.gates[i].model.info || !(gs.gates[i].has_min || gs.gates[i].has_max))
                __builtin_trap();
        gate_set_free(&gs);
    } else if (rc != EXIT_USAGE && rc != EXIT_RUNTIME) {
        __builtin_trap();
    } else if (err[0] == '\0' || memchr(err, '\0', sizeof err) == NULL) {
        __builtin_trap();   /* a refusal always says why */
    }
    usermodel_clear_all();
    return 0;
}
