/* infile.h - opening the files brdfbench reads, so that none of them can block or flood it.
 *
 * Every input goes through infile_open: the path is opened with O_NONBLOCK (a FIFO without a
 * writer or a device does not block the open) and then fstat decides. A regular file (or a
 * link to one) is read; a folder, a FIFO, a socket or a device is refused with a reason, so a
 * FIFO planted in a run folder (accuracy.json, plots.json, field_*.json, brdf_models.h of
 * --kernel-dir) or `--teapot-file /dev/zero` ends with a message instead of a hang or a
 * read of gigabytes. A file named on the command line (a gates file, --model-file) may also
 * be a pipe or FIFO with INFILE_PIPE_OK: `gate <(generate)` is the user's explicit choice.
 * Sizes are checked from fstat before anything is read, and again while reading a pipe.
 */
#ifndef BRDF_INFILE_H
#define BRDF_INFILE_H

#include <stddef.h>
#include <sys/stat.h>

#define INFILE_PIPE_OK 1   /* accept a pipe or FIFO too (read blocking, as the user asked for it) */

/* Opens path for reading. Returns a descriptor (blocking again, close-on-exec), or -1 with the
 * reason in why, without the path: strerror(errno) when it cannot be opened, "is a folder",
 * "is a FIFO, not a regular file", "is a character device, not a regular file", ...
 * *st (may be NULL) receives its fstat. */
int infile_open(const char *path, int flags, struct stat *st, char *why, size_t whylen);

/* The whole file in a malloc'd buffer with a NUL after its len bytes. A file larger than max
 * bytes is refused before it is read (a regular file by its size; a pipe once max + 1 bytes
 * have come). Returns 0; -1 with why as infile_open's or "is larger than MAX bytes (SIZE)";
 * -2 when out of memory; -3 on a read error (why: strerror). */
int infile_read(const char *path, int flags, size_t max, char **buf, size_t *len, char *why, size_t whylen);

/* "a FIFO", "a folder", "a character device", ... for a file type (st_mode). */
const char *infile_kind(mode_t mode);

#endif
