/* raster.h - the G-buffer of the image passes (world position, unit normal and shininess
 * per pixel) and the host code that fills it: a perspective camera, a triangle rasteriser
 * with a depth buffer and perspective-correct interpolation, and the analytic sphere grid.
 *
 * The G-buffer is made on the host, once per scene and resolution: it is outside every
 * timed shading launch, it is the same input for the device shading and the double
 * reference (so their difference is the shading's alone), and a plain C rasteriser is
 * deterministic and testable on its own. Its layout is what the shading kernel reads:
 * planes of floats (structure of arrays), so that a work-item loads 16 neighbouring
 * pixels of one quantity with one vector load. */
#ifndef BRDFBENCH_RASTER_H
#define BRDFBENCH_RASTER_H

#include <stddef.h>

#include "geometry.h"

/* enum gbuffer_plane: the planes, in the order kernels/shade.cl reads them */
#include "shade_shared.h"

/* Every plane's length is a multiple of this many pixels; the padding is background. */
#define GBUFFER_ALIGN 1024

struct gbuffer {
    int width, height;
    size_t npix;               /* width * height */
    size_t stride;             /* floats per plane: npix rounded up to GBUFFER_ALIGN */
    float *data;               /* GB_NPLANES * stride floats, plane k at data + k * stride */
    size_t foreground;         /* pixels covered by a surface (shininess > 0) */
};

static inline float *gbuffer_plane(const struct gbuffer *g, int k)
{
    return g->data + (size_t)k * g->stride;
}

/* Bytes of one G-buffer of width x height (with padding); 0 on overflow. */
size_t gbuffer_bytes(long width, long height);
/* Allocates a cleared (all background) G-buffer. Returns 0, or 3 (memory/overflow). */
int gbuffer_alloc(struct gbuffer *g, int width, int height, char *err, size_t errlen);
void gbuffer_free(struct gbuffer *g);

struct camera {
    double eye[3], target[3], up[3];
    double fov_y_deg;          /* vertical field of view */
};

/* Unit direction of the primary ray through the centre of pixel (x, y) (y = 0 at the top). */
void camera_ray(const struct camera *cam, int width, int height, double x, double y,
                double dir[3]);

/* A camera looking at the centre of the mesh's bounding box from direction `from` (need
 * not be unit), at the nearest distance where every vertex lies within the central `fill`
 * share (0..1] of the frame's width and height. */
void camera_fit_mesh(struct camera *cam, const struct mesh *m, const double from[3],
                     const double up[3], double fov_y_deg, double aspect, double fill);

/* Rasterises the mesh (vertex normals interpolated perspective-correctly and normalised)
 * with shininess `shininess` on every covered pixel. Surfaces are two-sided: on a
 * triangle seen from its back the normal is flipped towards the viewer, since open
 * surfaces (the teapot's patches) show both sides. Triangles reaching behind the camera's
 * near plane are skipped (the scenes are framed so that none does). Returns 0 or 3. */
int raster_mesh(struct gbuffer *g, const struct mesh *m, const struct camera *cam,
                float shininess, char *err, size_t errlen);

/* The sphere grid: rows x cols cells filling the frame, a sphere in every cell, column j
 * with shininess col_shininess[j]; positions and normals by exact ray-sphere intersection.
 * cam receives the camera used. Row r occupies pixel rows [r*H/rows, (r+1)*H/rows). */
struct sphere_grid {
    int rows, cols;
    double radius;             /* world units; cells are 1 high */
    double cell_w;             /* cell width in world units */
};
void sphere_grid_layout(int width, int height, int rows, int cols, struct sphere_grid *sg,
                        struct camera *cam);
/* Centre of the sphere of cell (row, col). */
void sphere_grid_centre(const struct sphere_grid *sg, int row, int col, double c[3]);
int raster_spheres(struct gbuffer *g, int rows, int cols, const double *col_shininess,
                   struct camera *cam, char *err, size_t errlen);

#endif
