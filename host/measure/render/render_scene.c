/* render_scene.c - the scenes (spheres, teapot, bunny): reading them, their G-buffers and light,
 * and the rows of the spheres' image each model owns. */
#define _XOPEN_SOURCE 700
#include "render_internal.h"
#include "errmsg.h"
#include "exitcodes.h"
#include "geometry.h"
#include "raster.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* World direction towards the light (upper left, in front), for every scene. */
static const double light_dir_world[3] = {-0.45, 0.6, 0.66};
/* Where the mesh cameras look from (right, above, in front), and their field of view. */
static const double mesh_view_from[3] = {0.35, 0.45, 1.0};
static const double world_up[3] = {0.0, 1.0, 0.0};
#define MESH_FOV_DEG 30.0
#define MESH_FILL 0.92

/* ------------------------------------------------------------------ scenes */

int scene_load(int kind, const struct render_options *o, struct scene_data *sd, char *err,
               size_t errlen)
{
    memset(sd, 0, sizeof *sd);
    sd->kind = kind;
    if (kind == RENDER_SPHERES) {
        snprintf(sd->source, sizeof sd->source, "analytic spheres");
        return 0;
    }
    const char *path = kind == RENDER_TEAPOT ? o->teapot_path : o->bunny_path;
    const char *def = kind == RENDER_TEAPOT ? RENDER_TEAPOT_PATH : RENDER_BUNNY_PATH;
    const char *pkg = kind == RENDER_TEAPOT ? RENDER_TEAPOT_PACKAGE : RENDER_BUNNY_PACKAGE;
    snprintf(sd->source, sizeof sd->source, "%s", path);
    if (access(path, R_OK) != 0) {
        int is_default = strcmp(path, def) == 0;
        if (is_default)
            set_err(err, errlen,
                    "%s scene: %s is missing: it comes with Debian's %s package (apt-get install "
                    "%s; where an image excludes /usr/share/doc from installs, take the file out "
                    "of the package: apt-get download %s && dpkg-deb -x %s_*.deb DIR; "
                    "scripts/setup.sh does both)",
                    render_scene_names[kind], path, pkg, pkg, pkg, pkg);
        else
            set_err(err, errlen, "%s scene: cannot read %s: %s", render_scene_names[kind], path,
                    strerror(errno));
        return is_default ? EXIT_RUNTIME : EXIT_USAGE;
    }
    int rc;
    if (kind == RENDER_TEAPOT) {
        struct bezier_patch *p = NULL;
        rc = patches_read(path, &p, &sd->patches, err, errlen);
        if (rc == 0)
            rc = patches_tessellate(p, sd->patches, o->tess, &sd->mesh, err, errlen);
        free(p);
        if (rc == 0) {
            /* the file's teapot stands on z = 0 with z up; the scenes are y-up: a rotation
               of -90 degrees about x, (x, y, z) -> (x, z, -y) */
            for (size_t v = 0; v < sd->mesh.nverts; v++) {
                float *q = sd->mesh.pos + 3 * v, *n = sd->mesh.nrm + 3 * v, t;
                t = q[1];
                q[1] = q[2];
                q[2] = -t;
                t = n[1];
                n[1] = n[2];
                n[2] = -t;
            }
        }
    } else {
        rc = obj_read(path, &sd->mesh, err, errlen);
        if (rc == 0)
            rc = mesh_smooth_normals(&sd->mesh, err, errlen);
    }
    if (rc)
        mesh_free(&sd->mesh);
    return rc;
}

/* G-buffer and light of a scene at a size. */
int scene_gbuffer(const struct scene_data *sd, const struct render_options *o, int w, int h,
                  struct gbuffer *g, struct render_light *lt, char *err, size_t errlen)
{
    int rc = gbuffer_alloc(g, w, h, err, errlen);
    if (rc)
        return rc;
    struct camera cam;
    if (sd->kind == RENDER_SPHERES) {
        rc = raster_spheres(g, o->nmodels, o->ncols, o->sphere_n, &cam, err, errlen);
    } else {
        camera_fit_mesh(&cam, &sd->mesh, mesh_view_from, world_up, MESH_FOV_DEG,
                        (double)w / h, MESH_FILL);
        rc = raster_mesh(g, &sd->mesh, &cam, (float)o->mesh_n, err, errlen);
    }
    if (rc) {
        gbuffer_free(g);
        return rc;
    }
    double dir[3] = {light_dir_world[0], light_dir_world[1], light_dir_world[2]};
    vec3_normalize(dir);
    double d[3] = {cam.eye[0] - cam.target[0], cam.eye[1] - cam.target[1],
                   cam.eye[2] - cam.target[2]};
    double dist = sqrt(vec3_dot(d, d));
    for (int c = 0; c < 3; c++)
        lt->eye[c] = cam.eye[c];
    lt->point = o->point_light;
    if (o->point_light) {
        /* at the camera's distance from the scene's centre, E = 1 at the centre */
        for (int c = 0; c < 3; c++)
            lt->light[c] = cam.target[c] + dist * dir[c];
        lt->intensity = dist * dist;
    } else {
        for (int c = 0; c < 3; c++)
            lt->light[c] = dir[c];
        lt->intensity = 1.0;
    }
    return 0;
}

/* Rows [y0, y1) of the frame a model's figures cover: its band of the sphere grid (the rows
   raster_spheres gives to grid row `row`), or the whole frame. */
void model_region(const struct scene_data *sd, const struct render_options *o, int h,
                  int row, int *y0, int *y1)
{
    if (sd->kind != RENDER_SPHERES) {
        *y0 = 0;
        *y1 = h;
        return;
    }
    int a = -1, b = h;
    for (int y = 0; y < h; y++) {
        int r = (int)((long)y * o->nmodels / h);
        if (r == row && a < 0)
            a = y;
        if (r > row) {
            b = y;
            break;
        }
    }
    *y0 = a < 0 ? 0 : a;
    *y1 = b;
}
