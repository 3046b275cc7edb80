/* cmd_list.c - `brdfbench list`: the model registry and the OpenCL platforms and devices, as
 * text or (--json) as a JSON document. */
#include "schemas.h"
#include "cli_table.h"
#include "clsession.h"
#include "commands.h"
#include "context.h"
#include "exitcodes.h"
#include "jsonw.h"
#include "models.h"

#include <stdio.h>
#include <string.h>


struct device_entry {
    char name[256];
    cl_uint compute_units;
    cl_ulong global_mem;
};
struct platform_entry {
    char name[256], version[256];
    cl_uint ndev;
    struct device_entry dev[16];
};

/* At most 16 platforms of 16 devices each; returns how many platforms were found. */
static int find_devices(struct platform_entry *plat, int max)
{
    cl_uint nplat = 0;
    if (clGetPlatformIDs(0, NULL, &nplat) != CL_SUCCESS || nplat == 0)
        return 0;
    cl_platform_id ids[16];
    if (nplat > (cl_uint)max)
        nplat = (cl_uint)max;
    if (clGetPlatformIDs(nplat, ids, NULL) != CL_SUCCESS)
        return 0;
    /* a query that fails shows as "?" (a number as 0): the list goes on */
    for (cl_uint p = 0; p < nplat; ++p) {
        struct platform_entry *e = &plat[p];
        memset(e, 0, sizeof *e);
        if (cl_platform_string(ids[p], CL_PLATFORM_NAME, e->name, sizeof e->name) != CL_SUCCESS)
            snprintf(e->name, sizeof e->name, "?");
        if (cl_platform_string(ids[p], CL_PLATFORM_VERSION, e->version, sizeof e->version) != CL_SUCCESS)
            snprintf(e->version, sizeof e->version, "?");
        cl_device_id devs[16];
        if (clGetDeviceIDs(ids[p], CL_DEVICE_TYPE_ALL, 16, devs, &e->ndev) != CL_SUCCESS)
            e->ndev = 0;
        if (e->ndev > 16)
            e->ndev = 16;
        for (cl_uint d = 0; d < e->ndev; ++d) {
            if (cl_device_string(devs[d], CL_DEVICE_NAME, e->dev[d].name, sizeof e->dev[d].name) != CL_SUCCESS)
                snprintf(e->dev[d].name, sizeof e->dev[d].name, "?");
            cl_device_value(devs[d], CL_DEVICE_MAX_COMPUTE_UNITS, &e->dev[d].compute_units, sizeof e->dev[d].compute_units);
            cl_device_value(devs[d], CL_DEVICE_GLOBAL_MEM_SIZE, &e->dev[d].global_mem, sizeof e->dev[d].global_mem);
        }
    }
    return (int)nplat;
}

static void print_text(const struct platform_entry *plat, int nplat)
{
    printf("Models (f(c, n), c = cos x; x = psi for the Phong family, theta_h for the Blinn family):\n");
    for (int i = 0; i < models_count(); ++i) {
        const struct model_info *m = models_at(i);
        printf("\n  %-9s %s\n", m->id, m->description);
        printf("            f = %s\n", m->formula);
        printf("            reference: %s; lobe angle: %s; family: %s%s\n", m->reference_id,
               m->lobe == LOBE_PSI ? "psi = angle(R, V)" : "theta_h = angle(N, H)", model_family_name(m->family),
               m->in_default_set ? "" : "; not in the default set");
        if (m->root)
            printf("            zero past its root: %s\n", m->root);
        for (int p = 0; p < m->nparams; ++p)
            printf("            parameter %s in [%g, %g]%s, default %g: %s (e.g. %s:%s=%g)\n", m->params[p].name,
                   m->params[p].min, m->params[p].max, m->params[p].integer ? " integer" : "", m->params[p].def,
                   m->params[p].meaning, m->id, m->params[p].name, m->params[p].def);
    }
    printf("\nOpenCL platforms and devices:\n");
    if (nplat == 0)
        printf("  none found (install pocl-opencl-icd for the CPU driver)\n");
    for (int p = 0; p < nplat; ++p) {
        printf("  platform %d: %s (%s)\n", p, plat[p].name, plat[p].version);
        for (cl_uint d = 0; d < plat[p].ndev; ++d)
            printf("    device %u: %s, %u compute units, %.1f GiB\n", d, plat[p].dev[d].name,
                   plat[p].dev[d].compute_units, (double)plat[p].dev[d].global_mem / 1073741824.0);
    }
}

static int write_json(const char *path, const struct platform_entry *plat, int nplat, char *err, size_t errlen)
{
    struct jw w;
    jw_init(&w);
    jw_obj_begin(&w);
    jw_kv_str(&w, "schema", LIST_SCHEMA);
    jw_kv_str(&w, "brdfbench_version", BRDF_VERSION);
    jw_kv_str(&w, "git_revision", brdf_git_revision);
    jw_kv_arr(&w, "models");
    for (int i = 0; i < models_count(); ++i) {
        const struct model_info *m = models_at(i);
        jw_obj_begin(&w);
        jw_kv_str(&w, "id", m->id);
        jw_kv_str(&w, "description", m->description);
        jw_kv_str(&w, "formula", m->formula);
        jw_kv_str(&w, "reference", m->reference_id);
        jw_kv_str(&w, "lobe", m->lobe == LOBE_PSI ? "psi" : "theta_h");
        jw_kv_str(&w, "family", model_family_name(m->family));
        jw_kv_bool(&w, "in_default_set", m->in_default_set);
        jw_key(&w, "root");
        if (m->root)
            jw_str(&w, m->root);
        else
            jw_null(&w);
        #define F(KIND, MEMBER, KEY) JW_FIELD(KIND, struct model_param, MEMBER, KEY)
        static const struct jw_field param[] = {
            F(JWF_TEXTP, name, "name"), F(JWF_NUM, min, "min"), F(JWF_NUM, max, "max"), F(JWF_NUM, def, "default"),
            F(JWF_BOOL, integer, "integer"), F(JWF_TEXTP, meaning, "meaning"),
        };
        #undef F
        jw_kv_records(&w, "parameters", m->params, (size_t)m->nparams, sizeof *m->params, JW_FIELDS(param));
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_kv_arr(&w, "platforms");
    for (int p = 0; p < nplat; ++p) {
        jw_obj_begin(&w);
        jw_kv_int(&w, "index", p);
        jw_kv_str(&w, "name", plat[p].name);
        jw_kv_str(&w, "version", plat[p].version);
        jw_kv_arr(&w, "devices");
        for (cl_uint d = 0; d < plat[p].ndev; ++d) {
            jw_obj_begin(&w);
            jw_kv_int(&w, "index", d);
            jw_kv_str(&w, "name", plat[p].dev[d].name);
            jw_kv_int(&w, "compute_units", plat[p].dev[d].compute_units);
            jw_kv_int(&w, "global_mem_bytes", (long long)plat[p].dev[d].global_mem);
            jw_obj_end(&w);
        }
        jw_arr_end(&w);
        jw_obj_end(&w);
    }
    jw_arr_end(&w);
    jw_obj_end(&w);
    struct cli_output o;
    const char *wp;
    int rc = cli_output_path(&o, path, "list.json", &wp, err, errlen);
    if (!rc && jw_write_file(&w, wp, err, errlen))
        rc = EXIT_RUNTIME;
    int frc = cli_output_finish(&o, !rc, err, errlen);
    jw_free(&w);
    return rc ? rc : frc;
}

int cmd_list(int argc, char **argv)
{
    char err[1024];
    const char *json_path = NULL;
    const struct cli_flag flags[] = {
        CLI_FLAG_JSON(&json_path),
    };
    const struct cli_command cmd = {
        .name = "list",
        .about = "  Lists the models (formula, parameters, reference) and the OpenCL platforms and devices;\n"
                 "  with --json as a JSON document (schema " LIST_SCHEMA ").\n",
        .flags = flags,
        .nflags = (int)(sizeof flags / sizeof flags[0]),
    };
    int prc = cli_parse(&cmd, argc, argv, NULL, err, sizeof err);
    if (prc == CLI_ANSWERED)
        return EXIT_OK;
    if (prc) {
        fprintf(stderr, "brdfbench list: %s\n", err);
        return EXIT_USAGE;
    }
    struct platform_entry plat[16];
    int nplat = find_devices(plat, 16);
    if (!json_path) {
        print_text(plat, nplat);
        return EXIT_OK;
    }
    if (write_json(json_path, plat, nplat, err, sizeof err)) {
        fprintf(stderr, "brdfbench list: %s\n", err);
        return EXIT_RUNTIME;
    }
    return EXIT_OK;
}
