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
    #define F(KIND, MEMBER, KEY) JW_FIELD(KIND, struct cl_session, MEMBER, KEY)
    static const struct jw_field device[] = {
        F(JWF_TEXT, platform_name, "platform"), F(JWF_TEXT, platform_version, "platform_version"),
        F(JWF_TEXT, device_name, "device"), F(JWF_TEXT, device_version, "device_version"),
        F(JWF_TEXT, driver_version, "driver_version"), F(JWF_UINT, compute_units, "compute_units"),
        F(JWF_BOOL, has_fp64, "fp64"),
    };
    #undef F
    if (s) jw_kv_fields(w, s, JW_FIELDS(device));
    jw_kv_str(w, "build_options", build_options ? build_options : "");
}

void jw_doc_begin(struct jw *w, const char *schema, const struct cl_session *s, const char *build_options)
{
    jw_init(w);
    jw_obj_begin(w);
    jw_kv_str(w, "schema", schema);
    jw_context_begin(w, s, build_options);
}
