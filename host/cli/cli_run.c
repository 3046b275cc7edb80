/* cli_run.c - the session, run folder, results/latest and --json/--csv steps shared by the
 * measuring commands (cli_run.h). */
#include "cli_run.h"

#include "cli_table.h"
#include "exitcodes.h"
#include "outdir.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static void cli_run_error(const char *cmd, const char *err)
{
    fprintf(stderr, "brdfbench %s: %s\n", cmd, err);
}

int cli_run_session(const char *cmd, struct brdf_run *run, const struct device_options *dev)
{
    char err[1024];
    int rc = brdf_run_open(run, dev->platform, dev->device, err, sizeof err);
    if (rc)
        cli_run_error(cmd, err);
    return rc;
}

int cli_run_folder(const char *cmd, const char *out_dir, int temp, char *run_dir, size_t run_dir_len, char *tmp_dir,
                   size_t tmp_dir_len)
{
    char err[1024];
    if (tmp_dir_len)
        tmp_dir[0] = '\0';
    if (temp) {
        if (cli_temp_dir(tmp_dir, tmp_dir_len, err, sizeof err)) {
            cli_run_error(cmd, err);
            return EXIT_RUNTIME;
        }
        snprintf(run_dir, run_dir_len, "%s", tmp_dir);
    } else if (outdir_for_command(out_dir, run_dir, run_dir_len, err, sizeof err)) {
        cli_run_error(cmd, err);
        return EXIT_RUNTIME;
    }
    return 0;
}

int cli_run_latest(const char *cmd, const char *out_dir, const char *tmp_dir, const char *run_dir)
{
    char err[1024];
    if (out_dir || (tmp_dir && tmp_dir[0]))
        return 0;
    if (outdir_set_latest("results", run_dir, err, sizeof err)) {
        cli_run_error(cmd, err);
        return EXIT_RUNTIME;
    }
    return 0;
}

int cli_run_deliver(const char *cmd, const char *run_dir, const char *name, const char *flag, const char *dest)
{
    char err[1024], src[4200];
    path_join(src, sizeof src, run_dir, name);
    if (cli_deliver(src, flag, dest, err, sizeof err)) {
        cli_run_error(cmd, err);
        return EXIT_RUNTIME;
    }
    return 0;
}

/* A document for standard output is made in a temporary folder first (cli_output_path): the
   folder it is made in (TMPDIR, else /tmp) must take one. */
static int check_temp_base(const char *flag, char *err, size_t errlen)
{
    const char *tmp = getenv("TMPDIR");
    const char *base = tmp && *tmp ? tmp : "/tmp";
    struct stat st;
    if (stat(base, &st) != 0 || !S_ISDIR(st.st_mode) || access(base, W_OK | X_OK) != 0) {
        snprintf(err, errlen, "%s -: cannot make a temporary folder in %s%s: %s", flag, base,
                 tmp && *tmp ? " (TMPDIR)" : "", errno ? strerror(errno) : strerror(ENOTDIR));
        return -1;
    }
    return 0;
}

int cli_run_check_documents(const char *cmd, const char *json_path, const char *csv_path)
{
    char err[1024];
    errno = 0;
    if ((cli_is_stdout(json_path) && check_temp_base("--json", err, sizeof err)) ||
        (cli_is_stdout(csv_path) && check_temp_base("--csv", err, sizeof err))) {
        cli_run_error(cmd, err);
        return EXIT_RUNTIME;
    }
    if ((json_path && output_file_check("--json", json_path, err, sizeof err)) ||
        (csv_path && output_file_check("--csv", csv_path, err, sizeof err))) {
        cli_run_error(cmd, err);
        return EXIT_RUNTIME;
    }
    return 0;
}

int cli_run_finish(const char *cmd, const char *out_dir, const char *tmp_dir, const char *run_dir, const char *name,
                   const char *json_path)
{
    int rc = cli_run_latest(cmd, out_dir, tmp_dir, run_dir);
    if (!rc && json_path)
        rc = cli_run_deliver(cmd, run_dir, name, "--json", json_path);
    cli_temp_dir_remove(tmp_dir);
    return rc;
}

void cli_engine_init(struct cli_engine_run *e, const char *cmd, const char *document, cli_engine_fn run, void *ctx)
{
    memset(e, 0, sizeof *e);
    e->cmd = cmd;
    e->document = document;
    e->run = run;
    e->ctx = ctx;
    device_options_init(&e->dev);
}

int cli_run_engine(struct cli_engine_run *e)
{
    struct brdf_run run;
    struct cl_session *s = &run.s;
    char err[1024];
    const int temp = (e->json_path || e->csv_path) && !e->out_dir;
    e->run_dir[0] = e->tmp_dir[0] = '\0';
    int rc = cli_run_check_documents(e->cmd, e->json_path, e->csv_path);
    if (!rc)
        rc = cli_run_session(e->cmd, &run, &e->dev);
    if (rc)
        return rc;
    if (e->check && (rc = e->check(s, e->ctx, err, sizeof err)) != 0) {
        cli_run_error(e->cmd, err);
        brdf_run_close(&run);
        return rc;
    }
    rc = cli_run_folder(e->cmd, e->out_dir, temp, e->run_dir, sizeof e->run_dir, e->tmp_dir, sizeof e->tmp_dir);
    if (rc) {
        brdf_run_close(&run);
        return rc;
    }
    /* the tables stay off a document on stdout */
    e->quiet = e->quiet || cli_is_stdout(e->json_path) || cli_is_stdout(e->csv_path);
    rc = e->run(s, e->run_dir, e->quiet, e->ctx);
    if (!rc || (e->complete_on && rc == e->complete_on)) {
        int frc = cli_run_latest(e->cmd, e->out_dir, e->tmp_dir, e->run_dir);
        if (!frc && e->json_path)
            frc = cli_run_deliver(e->cmd, e->run_dir, e->document, "--json", e->json_path);
        if (!frc && e->csv_path && e->csv_document)
            frc = cli_run_deliver(e->cmd, e->run_dir, e->csv_document, "--csv", e->csv_path);
        if (frc) rc = frc;
    }
    cli_temp_dir_remove(e->tmp_dir);
    brdf_run_close(&run);
    return rc;
}
