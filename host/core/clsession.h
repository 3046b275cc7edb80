/* clsession.h - one OpenCL session per run: platform and device selection, a profiling
 * queue, kernel sources (embedded at build time or read from --kernel-dir), the one
 * program-build helper, and error reporting by name with file:line. */
#ifndef BRDF_CLSESSION_H
#define BRDF_CLSESSION_H

#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>
#include "exitcodes.h"
#include <stddef.h>

/* A growing table kept by a session for a layer above it (room.h grows it). */
struct cl_session_table {
    void *items;
    int count, cap;
};

struct cl_session {
    cl_platform_id platform;
    cl_device_id device;
    cl_context ctx;
    cl_command_queue queue;       /* in order, profiling enabled */
    int platform_index, device_index;
    char platform_name[256], platform_version[256];
    char device_name[256], device_version[256], driver_version[256];
    cl_uint compute_units;
    int is_cpu;                   /* CL_DEVICE_TYPE_CPU: its launches run on this machine's cores */
    int specialise;               /* build one program per built-in model (-DBRDF_ONLY_MODEL), not one for all */
    cl_ulong global_mem, max_alloc;
    int has_fp64;
    int has_fp16;                 /* cl_khr_fp16 (said in an fp16 accuracy row; binary16 is emulated either way) */
    double last_build_seconds;    /* wall time of the latest clsession_build */
    double build_seconds_total;   /* of every build of the session */
    int builds;
    /* What the session's engines share for its life, so that a run holds it in one place
       (host/core/run.h) rather than in file-scope tables: the program cache (host/core/programs.c:
       its builds and host evaluators) and the sweeps already run (accuracy.c's memo). Each
       table's element type is its owner's own. clsession_close calls release_cache and
       release_sweeps first, while the context still exists. */
    struct cl_session_table programs, hosts, sweeps;
    long sweep_reuses;            /* asks for a sweep answered from `sweeps` */
    void (*release_cache)(struct cl_session *s);
    void (*release_sweeps)(struct cl_session *s);
};

/* Name of an OpenCL error code ("CL_BUILD_PROGRAM_FAILURE"). */
const char *cl_error_name(cl_int err);

/* Reports a failed OpenCL call on stderr: call, error name, file:line. */
void cl_report(const char *call, cl_int err, const char *file, int line);
/* Evaluates an OpenCL call returning cl_int; on failure reports it and jumps to `label`
 * with rc = EXIT_RUNTIME (the enclosing function declares `int rc`). */
#define CL_CHECK_GOTO(call, label)                                             \
    do {                                                                       \
        cl_int cl_check_err_ = (call);                                         \
        if (cl_check_err_ != CL_SUCCESS) {                                     \
            cl_report(#call, cl_check_err_, __FILE__, __LINE__);               \
            rc = EXIT_RUNTIME;                                                 \
            goto label;                                                        \
        }                                                                      \
    } while (0)
/* For calls that return an object and set an error out-parameter `e`. */
#define CL_CHECK_ERR_GOTO(e, what, label)                                      \
    do {                                                                       \
        if ((e) != CL_SUCCESS) {                                               \
            cl_report(what, (e), __FILE__, __LINE__);                          \
            rc = EXIT_RUNTIME;                                                 \
            goto label;                                                        \
        }                                                                      \
    } while (0)

/* Information queries, every one checked. A string goes into buf, cut to buflen - 1 bytes when
 * longer (a driver's extension list can be), always NUL-terminated: CL_SUCCESS, or the call's
 * error with buf empty. A value of a fixed size (a number, a bit field): CL_SUCCESS, or the
 * error with the value zeroed. */
cl_int cl_platform_string(cl_platform_id p, cl_platform_info what, char *buf, size_t buflen);
cl_int cl_device_string(cl_device_id d, cl_device_info what, char *buf, size_t buflen);
cl_int cl_device_value(cl_device_id d, cl_device_info what, void *value, size_t size);

/* One kernel argument: its size and where its value is (CL_ARG(x) for a variable x). */
struct cl_arg {
    size_t size;
    const void *value;
};
#define CL_ARG(x) ((struct cl_arg){ sizeof(x), &(x) })
/* Sets n arguments as the kernel's arguments first, first + 1, ...: CL_SUCCESS, or the first
 * failure's error with why (when not NULL) saying which, in one line: "clSetKernelArg(KERNEL,
 * argument I) failed with CL_NAME (code)", KERNEL the kernel's function name. */
cl_int cl_set_args(cl_kernel k, cl_uint first, const struct cl_arg *args, cl_uint n, char *why, size_t whylen);
/* The same, a failure reported on stderr as cl_report does (with file:line): 0 or EXIT_RUNTIME. */
int cl_set_args_report(cl_kernel k, cl_uint first, const struct cl_arg *args, cl_uint n, const char *file, int line);
/* The argument list of the macros below: CL_ARG(a), CL_ARG(b), ... as an array and its count. */
#define CL_ARG_LIST(...)                                                                                             \
    (const struct cl_arg[]){ __VA_ARGS__ }, (cl_uint)(sizeof((struct cl_arg[]){ __VA_ARGS__ }) / sizeof(struct cl_arg))
/* CL_SET_ARGS_GOTO(label, k, first, CL_ARG(a), CL_ARG(b), ...): sets them as arguments first,
 * first + 1, ...; on a failure reports it (kernel, argument, error) and jumps to `label` with
 * rc = EXIT_RUNTIME (the enclosing function declares `int rc`), as CL_CHECK_GOTO. */
#define CL_SET_ARGS_GOTO(label, k, first, ...)                                                                       \
    do {                                                                                                             \
        if (cl_set_args_report((k), (first), CL_ARG_LIST(__VA_ARGS__), __FILE__, __LINE__) != 0) {                   \
            rc = EXIT_RUNTIME;                                                                                       \
            goto label;                                                                                              \
        }                                                                                                            \
    } while (0)
/* CL_SET_ARGS_WHY(k, first, why, whylen, CL_ARG(a), ...): cl_set_args of the list (a cl_int);
 * CL_SET_ARGS(k, first, CL_ARG(a), ...) the same without the words. */
#define CL_SET_ARGS_WHY(k, first, why, whylen, ...) cl_set_args((k), (first), CL_ARG_LIST(__VA_ARGS__), (why), (whylen))
#define CL_SET_ARGS(k, first, ...) cl_set_args((k), (first), CL_ARG_LIST(__VA_ARGS__), NULL, 0)

/* Opens platform/device (indices; -1 = first with a device). Returns 0, EXIT_USAGE for an
 * index out of range, EXIT_RUNTIME, or EXIT_NO_DEVICE with a hint in err. */
int clsession_open(struct cl_session *s, int platform_index, int device_index, char *err, size_t errlen);
void clsession_close(struct cl_session *s);

/* A device of a device list: platform and device indices as clsession_open takes them. */
struct cl_device_ref {
    int platform, device;
};
#define CL_MAX_DEVICE_REFS 16
/* Resolves `--device all` (every device of every platform the ICD loader finds, platform by
 * platform) or a comma-separated list whose entries are D (device D of `platform`, or of the
 * first platform with a device when platform < 0) or P:D; an entry may repeat. Returns the
 * number of devices (1..max), or -EXIT_USAGE (an entry out of range, named with the accepted
 * range) or -EXIT_NO_DEVICE with a message in err. */
int clsession_device_list(const char *text, int platform, struct cl_device_ref *out, int max, char *err,
                          size_t errlen);

/* Kernel sources: embedded copies by default; --kernel-dir reads them from a folder. */
void clsession_set_kernel_dir(const char *dir);
/* The text of kernels/<name> (embedded or from the kernel dir) with its `#include "FILE"`
 * lines replaced by those kernel files' texts; NULL if it or a file it includes is unknown.
 * The caller frees the result. */
char *clsession_kernel_source(const char *name, size_t *len);

/* Builds a program from kernels/<file> (its includes are resolved by the host,
 * clsession_kernel_source) plus optional extra source text appended after it. On failure prints the build log
 * and the options on stderr and returns EXIT_RUNTIME (3). */
int clsession_build(struct cl_session *s, const char *kernel_file, const char *extra_source,
                    const char *options, cl_program *out);
/* clsession_build of kernels/<file> and extra_source (may be NULL), then its kernels names[i]
 * into *kernels[i]; on failure everything made is released (all set to NULL), the OpenCL error
 * is on stderr and the exit code (EXIT_RUNTIME) is returned. */
int clsession_build_kernels(struct cl_session *s, const char *kernel_file, const char *extra_source,
                            const char *options, cl_program *program, int count, const char *const names[],
                            cl_kernel *const kernels[]);
/* Releases the kernels and the program (those not NULL) and sets them to NULL. */
void clsession_release_kernels(cl_program *program, int count, cl_kernel *const kernels[]);
/* Same, but a failed build returns EXIT_USAGE: for user-supplied sources. */
int clsession_build_user(struct cl_session *s, const char *kernel_file, const char *extra_source,
                         const char *options, cl_program *out, int user_line_offset);

/* Runs a point kernel whose arguments first_arg, first_arg + 1, first_arg + 2 are the float
 * buffers c, n and out, 16 values per work-item (vload16/vstore16); the caller has set the
 * arguments before them. count values are padded to a multiple of 16 (n = 1 in the padding)
 * and count results are written to out. Returns 0 or EXIT_RUNTIME. */
int cl_run_points16(struct cl_session *s, cl_kernel k, cl_uint first_arg, const float *c, const float *n,
                    size_t count, float *out);

/* Launch deadlines (docs/architecture.md, habit 12). OpenCL cannot cancel a running kernel, so every wait
 * for a launch is watched by a thread: past the deadline it prints one line naming the kernel
 * and the model, removes the run's unfinished outputs (outdir_remove_own) and ends the process
 * with exit code 3. The deadline is per launch, in seconds. */
#define CLSESSION_DEFAULT_TIMEOUT 300.0
#define CLSESSION_MAX_TIMEOUT 604800.0
/* Where a deadline came from; a later setting replaces an earlier one of the same or a lower
 * rank, so --timeout wins over a gates file's "timeout", which wins over the default. */
enum clsession_timeout_source { TIMEOUT_DEFAULT = 0, TIMEOUT_FILE = 1, TIMEOUT_FLAG = 2 };
void clsession_set_timeout(double seconds, enum clsession_timeout_source source);
double clsession_timeout(void);
/* clFinish on s's queue under the deadline: `kernel` is the launch waited for (its function
 * name goes into the message), `model` the model it evaluates (NULL when none). Returns
 * clFinish's result. */
cl_int clsession_finish(struct cl_session *s, cl_kernel kernel, const char *model);
/* The work-group size of a launch of `global` long-looping work-items (throughput, render): 1 on a
   CPU device (PoCL and llvmpipe spread the groups over their threads; a size of the driver's own
   choosing can put every work-item on one thread), else the largest of 256, 128, 64, 32 that
   divides `global`, so that a GPU's warps run full (a group of 1 runs one lane of 32), or 0 where
   none divides it: then *local_or_null is NULL and the driver chooses. Returns the local size
   pointer for clEnqueueNDRangeKernel (buf or NULL). */
const size_t *clsession_group_size(const struct cl_session *s, size_t global, size_t *buf);
/* The default number of long-looping work-items of a throughput launch: 32 per compute unit on a
   CPU device, 512 per compute unit elsewhere (a GPU needs many warps per multiprocessor to hide
   latency), at most `max`. */
long clsession_default_work_items(const struct cl_session *s, long max);

/* Enqueues kernel over global (and local, or NULL) in `dims` dimensions and waits for it under
 * the deadline. ev (or NULL) receives the launch's event, for its profiling times; the caller
 * releases it. Returns 0, or EXIT_RUNTIME with the failed call reported. */
int clsession_launch(struct cl_session *s, cl_kernel kernel, cl_uint dims, const size_t *global, const size_t *local,
                     const char *model, cl_event *ev);
/* The watchdog by hand: arm before a blocking OpenCL call, disarm after it. */
void clsession_deadline_arm(cl_kernel kernel, const char *model);
void clsession_deadline_disarm(void);
/* The same for a blocking build or kernel creation named by `what` ("building kernels/x.cl
 * (options)"): past a second it prints what is running every 10 s; past the deadline the
 * one-line message names it. */
void clsession_deadline_arm_build(const char *what);
/* Progress lines of long builds on (1, the default) or off (--quiet). */
void clsession_set_progress(int on);
/* clCreateKernel under the deadline, with progress (some drivers compile here). */
cl_kernel clsession_create_kernel(cl_program program, const char *name, cl_int *err);

/* Seconds between a profiling event's start and end; NAN if the timer failed. */
double cl_event_seconds(cl_event ev);
/* The event's time, or `wall` (and *used_wall = 1) where the driver did not fill the
 * profiling events (0 or a nanosecond). */
double cl_event_seconds_or_wall(cl_event ev, double wall, int *used_wall);
/* Monotonic wall clock in seconds. */
double wall_seconds(void);

#endif
