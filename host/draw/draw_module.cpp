/* draw_module.cpp - the entry of the drawing module libbrdfbench-draw.so (draw_module.h): hands
 * the main binary the table of draw.h's functions, and gives draw.cpp the host's atomic write
 * and input check under their usual names.
 *
 * The module is built with hidden visibility: only DRAW_MODULE_ENTRY is exported, so the
 * functions below and the module's own draw_* never meet the main binary's symbols of the same
 * names (its forwarders in draw_load.c, its write_file_atomic).
 */
#include "draw_module.h"

extern "C" {
#include "infile.h"
#include "outdir.h"
}

namespace {
const struct draw_host_api *host_api;
}

/* draw.cpp writes every PNG through write_file_atomic and opens what it reads through
 * infile_open; here they are the main binary's (the run folder's confinement is its state). */
extern "C" int write_file_atomic(const char *path, const void *data, size_t len, char *err, size_t errlen)
{
    return host_api->write_file_atomic(path, data, len, err, errlen);
}

extern "C" int infile_open(const char *path, int flags, struct stat *st, char *why, size_t whylen)
{
    return host_api->infile_open(path, flags, st, why, whylen);
}

extern "C" __attribute__((visibility("default"))) const struct draw_module_api *
brdfbench_draw_module(const struct draw_host_api *host)
{
#define DRAW_MODULE_FILL(name) api.name = draw_##name;
    static struct draw_module_api api; /* zero until filled */
    if (!host || !host->write_file_atomic || !host->infile_open) return nullptr;
    host_api = host;
    api.abi = DRAW_MODULE_ABI;
    DRAW_MODULE_FUNCTIONS(DRAW_MODULE_FILL)
#undef DRAW_MODULE_FILL
    return &api;
}
