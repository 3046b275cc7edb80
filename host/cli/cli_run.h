/* cli_run.h - the steps every measuring command takes around its engine's run, each reporting
 * its own failure as "brdfbench CMD: message" on stderr:
 *   cli_run_session   opens the run (host/core/run.h: its session and what the session's engines
 *                     share) on the device of the device flags: its exit code, 0 when open. The
 *                     one path by which every command opens a device: cli_run_engine, and
 *                     accuracy, all and gate, which make their folders their own way;
 *   cli_run_folder    makes the run folder: a temporary one when `temp` (a --json/--csv document
 *                     without --out, cli_temp_dir), else --out or a new results/<date-time>
 *                     (outdir_for_command); 0 or EXIT_RUNTIME;
 *   cli_run_latest    points results/latest at the run folder when it is a new results/<date-time>
 *                     (no --out, not temporary); 0 or EXIT_RUNTIME;
 *   cli_run_check_documents  checks --json/--csv before the work;
 *   cli_run_deliver   copies the folder's document `name` to the path of `flag` (cli_deliver);
 *                     0 or EXIT_RUNTIME. */
#ifndef BRDFBENCH_CLI_RUN_H
#define BRDFBENCH_CLI_RUN_H

#include <stddef.h>

#include "cli.h"
#include "clsession.h"
#include "run.h"

int cli_run_session(const char *cmd, struct brdf_run *run, const struct device_options *dev);
int cli_run_folder(const char *cmd, const char *out_dir, int temp, char *run_dir, size_t run_dir_len, char *tmp_dir,
                   size_t tmp_dir_len);
int cli_run_latest(const char *cmd, const char *out_dir, const char *tmp_dir, const char *run_dir);
/* Checks --json and --csv paths (either may be NULL) before any work (output_file_check): 0 or
 * EXIT_RUNTIME, so a missing or read-only folder fails at once, not after the measurement. */
int cli_run_check_documents(const char *cmd, const char *json_path, const char *csv_path);
int cli_run_deliver(const char *cmd, const char *run_dir, const char *name, const char *flag, const char *dest);
/* After a run that wrote its folder: cli_run_latest, then the document `name` to --json's path
 * (when json_path), then the temporary folder removed (when tmp_dir names one). 0 or EXIT_RUNTIME. */
int cli_run_finish(const char *cmd, const char *out_dir, const char *tmp_dir, const char *run_dir, const char *name,
                   const char *json_path);

/* The contract of a measuring command: its engine's run as a function of the session, the
 * run folder and whether to keep its tables off standard output. Every measuring command but
 * accuracy (whose folder under results/ is named after its sweep and made after its kernel
 * builds, cmd_accuracy.c), all (its staged folder, cmd_all.c) and gate (no folder) goes through
 * cli_run_engine; those three open their run through cli_run_session, as cli_run_engine does;
 * compare, which opens no device, makes its folder with cli_run_folder after the runs are read. */
typedef int (*cli_engine_fn)(struct cl_session *s, const char *run_dir, int quiet, void *ctx);
/* A check after the session opened and before any folder is made (sizes against the device):
 * 0, or EXIT_USAGE with the message in err. */
typedef int (*cli_engine_check_fn)(struct cl_session *s, void *ctx, char *err, size_t errlen);
struct cli_engine_run {
    const char *cmd;                   /* "frontier": messages start "brdfbench frontier: " */
    struct device_options dev;         /* the device flags */
    const char *out_dir, *json_path;   /* --out and --json (either may be NULL) */
    const char *csv_path;              /* --csv (NULL: none, or the command has none) */
    const char *document;              /* the run folder's file --json delivers: "frontier.json" */
    const char *csv_document;          /* the one --csv delivers: "throughput.csv" (NULL: no --csv) */
    int quiet;                         /* --quiet; out: also set when --json or --csv goes to standard output */
    int complete_on;                   /* an exit code besides 0 after which the folder is complete and
                                          delivered (fit: EXIT_GATE_FAIL, its fit.json says why); 0: none */
    cli_engine_check_fn check;         /* NULL: none */
    cli_engine_fn run;
    void *ctx;                         /* the engine's options */
    char run_dir[4096], tmp_dir[512];  /* out: where the run was written; tmp_dir "" unless temporary */
};
/* The command's fields before its flags are read: no --out, --json or --quiet, the default device. */
void cli_engine_init(struct cli_engine_run *e, const char *cmd, const char *document, cli_engine_fn run, void *ctx);
/* The flags of every such command, writing into e: --out, --json, --quiet and the device flags
 * (cli_table.h). */
#define CLI_FLAGS_ENGINE(E)                                                                                        \
    CLI_FLAG_OUT(&(E)->out_dir, CLI_DEF_OUT "; with --json and no --out, no folder"), CLI_FLAG_JSON(&(E)->json_path), \
        CLI_FLAG_QUIET(&(E)->quiet), CLI_FLAGS_DEVICE(&(E)->dev)

/* Checks --json and --csv, opens the session, runs the check, makes the run folder (a temporary
 * one for --json or --csv without --out), runs the engine, points results/latest at the folder,
 * delivers the documents to --json and --csv, removes a temporary folder, closes the session. Every failure is reported as "brdfbench CMD: message". Returns the engine's exit
 * code, or that of the step that failed. */
int cli_run_engine(struct cli_engine_run *e);

#endif
