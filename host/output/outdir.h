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
/* Checks before any work that write_file_atomic can write path: standard output and open
 * descriptors pass, a folder is refused, a device or FIFO must be writable, and a file's folder
 * (links followed) must exist and be writable. Returns 0, or -1 with "FLAG: problem". */
int output_file_check(const char *flag, const char *path, char *err, size_t errlen);
/* 1 when two output paths lead to the same place (the same file, device or descriptor, however
 * spelled: links, `-` and /dev/stdout, ./a and a), else 0. */
int output_paths_same(const char *a, const char *b);

/* What this process made, for a run that must stop: every folder created by outdir_prepare or
 * outdir_new_run (and the temporary file of a write in progress) is recorded.
 * outdir_remove_own removes them, the folders with all they hold, newest first; folders that
 * existed before are never removed. It uses only system calls (no allocation, no stdio), so the
 * launch watchdog can call it while the main thread is stopped anywhere. */
void outdir_remove_own(void);
/* Records a scratch folder made elsewhere (a temporary folder) as this process's own: every
 * tidy-up removes it with all it holds. */
void outdir_own(const char *dir);
/* Removes the folders this process made that are still empty (after a refused run). */
void outdir_remove_own_empty(void);
/* Creates dir (and parents) if needed and checks it can be written. Returns 0 or -1; the
 * message starts with "ARG: " when the folder came from a flag (arg = "--out"), and with
 * nothing when the program chose it (arg = NULL). */
int outdir_prepare(const char *dir, const char *arg, char *err, size_t errlen);
/* The same refusals for an output folder that exists already (not a folder, not writable),
 * made before any work and without creating anything: 0 when dir is absent or usable. */
int outdir_check_existing(const char *dir, const char *arg, char *err, size_t errlen);
/* Joins dir and name into out. Returns 0, or -1 when it does not fit. */
int path_join(char *out, size_t outlen, const char *dir, const char *name);
/* 0 when results_root/latest is absent or a symlink (the one this program keeps), else -1 with a
 * message: a folder or file there is refused before a run, not found after it. */
int outdir_check_latest(const char *results_root, char *err, size_t errlen);
/* Creates a new run folder results_root/<YYYY-MM-DD_HHMMSS>[-k] and writes its path to out
 * (after outdir_check_latest). */
int outdir_new_run(const char *results_root, char *out, size_t outlen, char *err, size_t errlen);
/* The folder a command writes into: out_dir (--out) prepared as it is, or when out_dir is NULL
 * a new run folder under "results". Its path goes to run_dir. Returns 0, or -1 with a message. */
int outdir_for_command(const char *out_dir, char *run_dir, size_t run_dir_len, char *err, size_t errlen);
/* Holds an exclusive flock on folder dir until the process ends, so that two runs never write
 * one --out at once (outdir_for_command and outdir_stage_begin take it). Returns 0 (also when
 * dir does not exist), or -1 with "ARG: DIR is being written by another run (process PID)". */
int outdir_lock(const char *dir, const char *arg, char *err, size_t errlen);
/* Points results_root/latest at run_dir (atomically: a new link renamed over the old). */
int outdir_set_latest(const char *results_root, const char *run_dir, char *err, size_t errlen);

/* Marks dir as a run folder: a file written below it (write_file_atomic) never follows a
 * symlink out of it. The folders between dir and the file must be real folders, and a symlink,
 * FIFO or device in the file's place is replaced by a regular file instead of written through.
 * outdir_prepare and outdir_new_run mark the folders they make or check; plot and heatmap
 * mark the run folder they redraw. A path outside every run folder is written as
 * write_file_atomic says (a link is followed: the user named it). */
void outdir_confine(const char *dir);

/* A run folder built beside its final place and swapped in only when complete, so that a run
 * that fails or is stopped (a signal, a deadline) leaves the earlier run in final_dir as it was
 * (docs/architecture.md, habit 5). outdir_stage_begin checks final_dir (an existing folder must
 * be empty or hold only what a run writes: result files, pictures, reports, render/; not the
 * working folder), makes a fresh staging folder beside it (.NAME.partial-PID; inside it when
 * it is a mount point) and writes its path to stage; the run writes there. Returns 0, 2 (bad
 * --out: arg names it in the message) or 3. outdir_stage_commit swaps the staged folder in (an
 * atomic exchange where the file system has one) and removes the earlier run; 0 or -1 with a
 * message. outdir_stage_abandon removes the staging folder. */
int outdir_stage_begin(const char *final_dir, const char *arg, char *stage, size_t stagelen, char *err,
                       size_t errlen);
int outdir_stage_commit(char *err, size_t errlen);
void outdir_stage_abandon(void);

/* What a signal may remove without losing a result: the temporary file of a write in progress,
 * a staged run (outdir_stage_begin) and scratch folders (outdir_own), and the folders this
 * process made that are still empty. A folder that holds a finished result stays (a signal may
 * come after the work, while a table is printed). System calls only. */
void outdir_remove_unfinished(void);
/* Installs handlers for SIGINT, SIGTERM, SIGHUP and SIGQUIT that remove this process's unfinished
 * outputs (outdir_remove_unfinished), say so on stderr and end the process by the same signal. A
 * signal that whoever started brdfbench ignores (nohup, a background job) stays ignored. Also
 * installs a std::terminate handler (terminate.cpp): an uncaught C++ exception in a library
 * (std::bad_alloc in the OpenCL compiler under ulimit -v) ends the run with one line and exit 3. */
void outdir_install_signal_handlers(void);
/* Puts those handlers back in front. The OpenCL compiler (LLVM) installs its own for the same
 * signals when it first builds, to remove its temporary files, and chains to the handler it
 * found; under load that chain has been seen to end the process by the default action instead,
 * leaving a staged run behind. `all` calls this between its steps. */
void outdir_reassert_signal_handlers(void);

#endif
