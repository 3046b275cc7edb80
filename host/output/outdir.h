/* outdir.h - atomic result files and run folders (docs/architecture.md, habit 5). */
#ifndef BRDF_OUTDIR_H
#define BRDF_OUTDIR_H

#include <stddef.h>

#define OUTDIR_PATH_MAX 4096

/* Writes data to an output path (docs/architecture.md, habits 5 and 12). A regular file (or a new one) is
 * replaced atomically: a temporary file in its real folder (a symlink's final target's folder;
 * the link stays a link), fsync, rename, so a reader sees the old file or the new one, never a
 * part. Everything else is written through, never replaced: `-` and /dev/stdout (standard
 * output, after what stdio holds), /dev/stderr, /dev/fd/N, /proc/self/fd/N, a FIFO, a device,
 * or a symlink to one of these. Returns 0, or -1 with a message. */
int write_file_atomic(const char *path, const void *data, size_t len, char *err, size_t errlen);
/* 1 when two output paths lead to the same place (the same file, device or descriptor, however
 * spelled: links, `-` and /dev/stdout, ./a and a), else 0. */
int output_paths_same(const char *a, const char *b);

/* What this process made, for a run that must stop: every folder created by outdir_prepare or
 * outdir_new_run (and the temporary file of a write in progress) is recorded.
 * outdir_remove_own removes them, the folders with all they hold, newest first; folders that
 * existed before are never removed. It uses only system calls (no allocation, no stdio), so the
 * launch watchdog can call it while the main thread is stopped anywhere. */
void outdir_remove_own(void);
/* Removes the folders this process made that are still empty (after a refused run). */
void outdir_remove_own_empty(void);
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
