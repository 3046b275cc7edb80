/* cmd_list.c - `brdfbench list`: the model registry and the OpenCL platforms and devices. */
#include "cli.h"
#include "clsession.h"
#include "commands.h"
#include "exitcodes.h"
#include "models.h"

#include <stdio.h>
#include <string.h>

static void list_devices(void)
{
    cl_uint nplat = 0;
    cl_int e = clGetPlatformIDs(0, NULL, &nplat);
    printf("\nOpenCL platforms and devices:\n");
    if (e != CL_SUCCESS || nplat == 0) {
        printf("  none found (install pocl-opencl-icd for the CPU driver)\n");
        return;
    }
    cl_platform_id plats[16];
    if (nplat > 16)
        nplat = 16;
    clGetPlatformIDs(nplat, plats, NULL);
    for (cl_uint p = 0; p < nplat; ++p) {
        char name[256] = "", version[256] = "";
        clGetPlatformInfo(plats[p], CL_PLATFORM_NAME, sizeof name, name, NULL);
        clGetPlatformInfo(plats[p], CL_PLATFORM_VERSION, sizeof version, version, NULL);
        printf("  platform %u: %s (%s)\n", p, name, version);
        cl_uint ndev = 0;
        cl_device_id devs[16];
        if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 16, devs, &ndev) != CL_SUCCESS)
            ndev = 0;
        if (ndev > 16)
            ndev = 16;
        for (cl_uint d = 0; d < ndev; ++d) {
            char dname[256] = "";
            cl_uint cu = 0;
            cl_ulong mem = 0;
            clGetDeviceInfo(devs[d], CL_DEVICE_NAME, sizeof dname, dname, NULL);
            clGetDeviceInfo(devs[d], CL_DEVICE_MAX_COMPUTE_UNITS, sizeof cu, &cu, NULL);
            clGetDeviceInfo(devs[d], CL_DEVICE_GLOBAL_MEM_SIZE, sizeof mem, &mem, NULL);
            printf("    device %u: %s, %u compute units, %.1f GiB\n", d, dname, cu, (double)mem / 1073741824.0);
        }
    }
}

int cmd_list(int argc, char **argv)
{
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--help") == 0) {
            printf("usage: brdfbench list\n  Lists the models (formula, parameters, reference) and the OpenCL devices.\n");
            return EXIT_OK;
        }
        fprintf(stderr, "brdfbench list: unknown option '%s' (accepted: --help)\n", argv[i]);
        return EXIT_USAGE;
    }
    printf("Models (f(c, n), c = cos x; x = psi for the Phong family, theta_h for the Blinn family):\n");
    for (int i = 0; i < models_count(); ++i) {
        const struct model_info *m = models_at(i);
        printf("\n  %-9s %s\n", m->id, m->description);
        printf("            f = %s\n", m->formula);
        printf("            reference: %s; lobe angle: %s; family: %s%s\n", m->reference_id,
               m->lobe == LOBE_PSI ? "psi = angle(R, V)" : "theta_h = angle(N, H)", m->family,
               m->in_default_set ? "" : "; not in the default set");
        if (m->root)
            printf("            zero past its root: %s\n", m->root);
        for (int p = 0; p < m->nparams; ++p)
            printf("            parameter %s in [%g, %g]%s, default %g: %s (e.g. %s:%s=%g)\n", m->params[p].name,
                   m->params[p].min, m->params[p].max, m->params[p].integer ? " integer" : "", m->params[p].def,
                   m->params[p].meaning, m->id, m->params[p].name, m->params[p].def);
    }
    list_devices();
    return EXIT_OK;
}
