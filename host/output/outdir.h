/* outdir.h - atomic result files and run folders (DESIGN.md, habit 5). */
#ifndef BRDF_OUTDIR_H
#define BRDF_OUTDIR_H

#include <stddef.h>

/* Writes data to path through a temporary file in the same folder, fsync and rename, so a
 * reader sees the old file or the new one, never a part. Returns 0, or -1 with a message. */
int write_file_atomic(const char *path, const void *data, size_t len, char *err, size_t errlen);
/* Creates dir (and parents) if needed and checks it can be written. Returns 0 or -1; the
 * message starts with "ARG: " when the folder came from a flag (arg = "--out"), and with
 * nothing when the program chose it (arg = NULL). */
int outdir_prepare(const char *dir, const char *arg, char *err, size_t errlen);
/* Joins dir and name into out. Returns 0, or -1 when it does not fit. */
int path_join(char *out, size_t outlen, const char *dir, const char *name);
/* Creates a new run folder results_root/<YYYY-MM-DD_HHMMSS>[-k] and writes its path to out. */
int outdir_new_run(const char *results_root, char *out, size_t outlen, char *err, size_t errlen);
/* The folder a command writes into: out_dir (--out) prepared as it is, or when out_dir is NULL
 * a new run folder under "results". Its path goes to run_dir. Returns 0, or -1 with a message. */
int outdir_for_command(const char *out_dir, char *run_dir, size_t run_dir_len, char *err, size_t errlen);
/* Points results_root/latest at run_dir (atomically: a new link renamed over the old). */
int outdir_set_latest(const char *results_root, const char *run_dir, char *err, size_t errlen);

#endif
