/* context.h - the context block every result file carries (docs/architecture.md, habit 6). */
#ifndef BRDF_CONTEXT_H
#define BRDF_CONTEXT_H

#include "clsession.h"
#include "jsonw.h"

extern const char *brdf_git_revision;   /* generated at build time */
#define BRDF_VERSION "0.1.0"

/* Writes "context": { date, host_cpu, host_cores, platform, platform_version, device,
 * device_version, driver_version, compute_units, build_options, git_revision, version ...
 * and leaves the object open, so the caller can add its own keys (e.g. "grid") before
 * closing it with jw_obj_end. `s` may be NULL (no device used). */
void jw_context_begin(struct jw *w, const struct cl_session *s, const char *build_options);
/* Starts a result document in w: jw_init, the top-level object, "schema": schema and the
 * context block, left open as jw_context_begin leaves it. */
void jw_doc_begin(struct jw *w, const char *schema, const struct cl_session *s, const char *build_options);
/* The host CPU's model name (from /proc/cpuinfo), or "unknown". */
const char *host_cpu_name(void);
/* UTC time now as ISO 8601 text. */
void utc_now_iso(char *buf, size_t len);

#endif
