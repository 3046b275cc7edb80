/* context.c - date, host and device facts written into every result file. */
#define _POSIX_C_SOURCE 200809L
#include "context.h"

#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

const char *host_cpu_name(void)
{
    static char name[256];
    if (name[0])
        return name;
    snprintf(name, sizeof name, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return name;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "model name", 10) == 0) {
            char *colon = strchr(line, ':');
            if (colon) {
                colon += 1 + (colon[1] == ' ');
                colon[strcspn(colon, "\n")] = '\0';
                snprintf(name, sizeof name, "%s", colon);
            }
            break;
        }
    }
    fclose(f);
    return name;
}

void utc_now_iso(char *buf, size_t len)
{
    time_t now = time(NULL);
    struct tm tmv;
    gmtime_r(&now, &tmv);
    strftime(buf, len, "%Y-%m-%dT%H:%M:%SZ", &tmv);
}

void jw_context_begin(struct jw *w, const struct cl_session *s, const char *build_options)
{
    char date[64];
    utc_now_iso(date, sizeof date);
    jw_kv_obj(w, "context");
    jw_kv_str(w, "date", date);
    jw_kv_str(w, "brdfbench_version", BRDF_VERSION);
    jw_kv_str(w, "git_revision", brdf_git_revision);
    jw_kv_str(w, "host_cpu", host_cpu_name());
    jw_kv_int(w, "host_cores", sysconf(_SC_NPROCESSORS_ONLN));
    if (s) {
        jw_kv_str(w, "platform", s->platform_name);
        jw_kv_str(w, "platform_version", s->platform_version);
        jw_kv_str(w, "device", s->device_name);
        jw_kv_str(w, "device_version", s->device_version);
        jw_kv_str(w, "driver_version", s->driver_version);
        jw_kv_int(w, "compute_units", s->compute_units);
        jw_kv_bool(w, "fp64", s->has_fp64);
    }
    jw_kv_str(w, "build_options", build_options ? build_options : "");
}

void jw_doc_begin(struct jw *w, const char *schema, const struct cl_session *s, const char *build_options)
{
    jw_init(w);
    jw_obj_begin(w);
    jw_kv_str(w, "schema", schema);
    jw_context_begin(w, s, build_options);
}
