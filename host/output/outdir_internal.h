/* outdir_internal.h - inside outdir: what its files share. Not an interface for other modules. */
#ifndef BRDF_OUTDIR_INTERNAL_H
#define BRDF_OUTDIR_INTERNAL_H

#include <stddef.h>

#include "outdir.h"

/* The temporary file of the write in progress (outdir_remove_own removes it). */
extern char outdir_own_tmp[OUTDIR_PATH_MAX];
extern volatile int outdir_own_tmp_set;
/* The length of the run folder that path lies in, or 0 (see outdir.c). */
size_t outdir_confined_root(const char *path);

#endif
