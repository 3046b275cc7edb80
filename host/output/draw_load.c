/* draw_load.c - draw.h in the main binary: every draw_* opens the drawing module
 * libbrdfbench-draw.so on first use (draw_module.h says why it is a module) and forwards to it.
 *
 * Where the module is looked for, in order (nothing from the environment, so that the program
 * loads no code its installation does not hold):
 *   1. beside the program (the folder of /proc/self/exe): the build tree;
 *   2. BRDF_DRAW_MODULE_RELDIR relative to that folder (set by CMake: ../lib/brdfbench for an
 *      install to bin/ and lib/): cmake --install and the .deb.
 * A module that is missing, does not load or is of another version makes every draw_* that can
 * fail return -1 with one line saying so (the commands that draw exit 3 with it); the others
 * (colour lookups) answer as for an unknown entry.
 */
#include "draw_module.h"
#include "infile.h"
#include "outdir.h"

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#ifndef BRDF_DRAW_MODULE_RELDIR
#define BRDF_DRAW_MODULE_RELDIR "../lib/brdfbench"
#endif

/* The drawing module, opened once per process (pthread_once): the process's, not a run's. */
static const struct draw_module_api *mod;
static char mod_err[3 * PATH_MAX + 1024]; /* room for the paths it names */
static pthread_once_t mod_once = PTHREAD_ONCE_INIT;

static const struct draw_host_api host_api = {write_file_atomic, infile_open};

/* Opens path and takes its table; 1 when it is the module, 0 with mod_err set otherwise. */
static int try_module(const char *path)
{
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        const char *e = dlerror();
        snprintf(mod_err, sizeof mod_err, "the drawing module %s does not load: %s", path, e ? e : "unknown error");
        return 0;
    }
    /* POSIX's way from the void * of dlsym to a function pointer. */
    draw_module_entry_fn entry;
    void *sym = dlsym(h, DRAW_MODULE_ENTRY);
    memcpy(&entry, &sym, sizeof entry);
    const struct draw_module_api *api = sym ? entry(&host_api) : NULL;
    if (!api || api->abi != DRAW_MODULE_ABI) {
        snprintf(mod_err, sizeof mod_err, "%s is not a drawing module of this brdfbench (interface %d expected)", path,
                 DRAW_MODULE_ABI);
        dlclose(h);
        return 0;
    }
    mod = api; /* kept open until the process ends */
    return 1;
}

static void open_module(void)
{
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0) {
        snprintf(mod_err, sizeof mod_err, "the drawing module %s cannot be looked for: /proc/self/exe is unreadable",
                 DRAW_MODULE_FILE);
        return;
    }
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    if (slash) *slash = '\0';
    char beside[PATH_MAX + 64], installed[PATH_MAX + 128];
    snprintf(beside, sizeof beside, "%s/%s", exe, DRAW_MODULE_FILE);
    snprintf(installed, sizeof installed, "%s/%s/%s", exe, BRDF_DRAW_MODULE_RELDIR, DRAW_MODULE_FILE);
    const char *where[2] = {beside, installed};
    for (int i = 0; i < 2; i++) {
        if (access(where[i], F_OK) == 0) {
            try_module(where[i]); /* found: its own failure is the message */
            return;
        }
    }
    snprintf(mod_err, sizeof mod_err,
             "the drawing module %s (pictures, OpenCV) is not installed: not found in %s nor in %s/%s; "
             "reinstall brdfbench, or build the target brdfbench-draw",
             DRAW_MODULE_FILE, exe, exe, BRDF_DRAW_MODULE_RELDIR);
}

/* The table, or NULL with err set to the one line why not. */
static const struct draw_module_api *module(char *err, size_t errlen)
{
    pthread_once(&mod_once, open_module);
    if (!mod && err && errlen) snprintf(err, errlen, "%s", mod_err);
    return mod;
}

int draw_module_check(char *err, size_t errlen) { return module(err, errlen) ? 0 : -1; }

/* ---- the forwarders, in draw.h's order ------------------------------------------------------- */

int draw_png_rgb8(const char *path, int width, int height, const unsigned char *rgb, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->png_rgb8(path, width, height, rgb, err, errlen) : -1;
}

int draw_error_image(const char *path, int width, int height, const float *abs_err, float vmax, const char *title,
                     char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->error_image(path, width, height, abs_err, vmax, title, err, errlen) : -1;
}

int draw_contact_sheet(const char *path, int width, int height, const unsigned char *ref_rgb,
                       const unsigned char *model_rgb, const float *abs_err, float vmax, const char *title, char *err,
                       size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->contact_sheet(path, width, height, ref_rgb, model_rgb, abs_err, vmax, title, err, errlen) : -1;
}

int draw_signed_error_image(const char *path, int width, int height, const float *signed_err, float vmax,
                            const char *title, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->signed_error_image(path, width, height, signed_err, vmax, title, err, errlen) : -1;
}

int draw_contact_grid(const char *path, int width, int height, const unsigned char *ref_rgb,
                      const unsigned char *model_rgb, const float *abs_err, float vmax, const char *title,
                      const struct draw_grid_labels *labels, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->contact_grid(path, width, height, ref_rgb, model_rgb, abs_err, vmax, title, labels, err, errlen)
             : -1;
}

void draw_colormap_rgb(int cmap, int index, unsigned char rgb[3])
{
    const struct draw_module_api *m = module(NULL, 0);
    if (m)
        m->colormap_rgb(cmap, index, rgb);
    else
        rgb[0] = rgb[1] = rgb[2] = 0; /* what the module answers for an unknown map */
}

int draw_heatmap_figure(const char *path, const char *title, int npanels, const struct draw_heatmap_panel *panels,
                        struct draw_panel_layout *layout, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->heatmap_figure(path, title, npanels, panels, layout, err, errlen) : -1;
}

int draw_heatmap_grid(const char *path, const char *title, int npanels, int ncols,
                      const struct draw_heatmap_panel *panels, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->heatmap_grid(path, title, npanels, ncols, panels, err, errlen) : -1;
}

int draw_colour_index(const char *name)
{
    const struct draw_module_api *m = module(NULL, 0);
    return m ? m->colour_index(name) : DRAW_COLOUR_UNKNOWN;
}

int draw_line_plot(const char *path, const struct draw_line_plot *plot, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->line_plot(path, plot, err, errlen) : -1;
}

int draw_bar_chart(const char *path, const struct draw_bar_chart *chart, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->bar_chart(path, chart, err, errlen) : -1;
}

int draw_scatter_plot(const char *path, const struct draw_scatter *plot, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->scatter_plot(path, plot, err, errlen) : -1;
}

int draw_scatter_plot_plain(const char *path, const struct draw_scatter *plot, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->scatter_plot_plain(path, plot, err, errlen) : -1;
}

void draw_verdict_rgb(int verdict, unsigned char rgb[3])
{
    const struct draw_module_api *m = module(NULL, 0);
    if (m)
        m->verdict_rgb(verdict, rgb);
    else
        rgb[0] = rgb[1] = rgb[2] = 0;
}

int draw_verdict_chart(const char *path, const struct draw_verdict_chart *c, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->verdict_chart(path, c, err, errlen) : -1;
}

int draw_stamp_png(const char *path, const char *text, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->stamp_png(path, text, err, errlen) : -1;
}

int draw_read_rgb8(const char *path, int *width, int *height, unsigned char **rgb, char *err, size_t errlen)
{
    const struct draw_module_api *m = module(err, errlen);
    return m ? m->read_rgb8(path, width, height, rgb, err, errlen) : -1;
}
