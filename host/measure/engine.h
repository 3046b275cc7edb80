/* engine.h - the contract every measuring engine of host/measure keeps, one shape for all:
 *
 *   void X_options_default(struct X_options *o);   what the command starts from
 *   int  X_options_check(const struct X_options *o, char *err, size_t errlen);
 *                                                   where flags alone cannot say it: 0, or
 *                                                   EXIT_USAGE with a one-line message
 *   int  X_run(struct cl_session *s, const struct X_options *o, struct X_result *r);
 *                                                   0, or an exit code (exitcodes.h) with its
 *                                                   one-line message on stderr; r may be NULL
 *                                                   where the caller reads nothing back
 *   void X_result_free(struct X_result *r);
 *
 * Every X_options holds a struct engine_io named io: the run folder the engine writes its
 * documents into, and whether its tables and progress stay off standard output. X_result
 * holds what a caller reads back: the figures, and the summary as markdown for report.md.
 *
 * The engines: fit (fit_run, and fit_family_run for the other families), frontier, measured,
 * pbcost, render, reproduce, throughput. render and measured, which also run as a pass
 * inside another engine or as a step of all, leave their message in r->err for the caller to
 * name the pass. X_options_check exists where the flag table cannot check everything (fit,
 * reproduce, throughput: relations between options); the others' options are each checked
 * by their flag's range. Not engines in this sense: accuracy_run and field_run (one model's
 * sweep inside a context the caller opens, for every command that sweeps), energy_run (a part
 * of reproduce) and gate_set_run (the gates of one file). */
#ifndef BRDF_ENGINE_H
#define BRDF_ENGINE_H

struct engine_io {
    const char *out_dir;   /* the run folder the documents go to */
    int quiet;             /* the tables and progress stay off standard output */
};

#endif
