/* geometry.h - triangle meshes for the image passes: a Wavefront OBJ reader, a reader for
 * POV-Ray bicubic_patch blocks (the Utah teapot of Debian's povray-examples), the Bezier
 * patch tessellator with analytic normals, and angle-weighted smooth vertex normals.
 *
 * Readers return 0 on success, 2 when the file is malformed (the message names the file,
 * the line and the problem) and 3 when the file cannot be read (I/O or memory). */
#ifndef BRDFBENCH_GEOMETRY_H
#define BRDFBENCH_GEOMETRY_H

#include <stddef.h>
#include <stdint.h>

/* Small double 3-vector helpers shared by the geometry, the rasteriser and the shading
 * reference. */
static inline void vec3_sub(const double *a, const double *b, double *o)
{
    o[0] = a[0] - b[0];
    o[1] = a[1] - b[1];
    o[2] = a[2] - b[2];
}
static inline void vec3_cross(const double *a, const double *b, double *o)
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}
static inline double vec3_dot(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
/* Scales a to unit length (a zero vector stays zero); returns the former length. */
double vec3_normalize(double *a);

struct mesh {
    size_t nverts;
    size_t ntris;
    float *pos;    /* 3 * nverts, x y z */
    float *nrm;    /* 3 * nverts, unit length once normals are set */
    uint32_t *tri; /* 3 * ntris vertex indices */
};

void mesh_free(struct mesh *m);

/* Reads the vertices ("v") and faces ("f", polygons fanned into triangles) of an OBJ file.
 * Texture coordinates and normals in the file are checked for syntax but not used: normals
 * are computed by mesh_smooth_normals so that every mesh is shaded the same way. */
int obj_read(const char *path, struct mesh *out, char *err, size_t errlen);
/* The same on text already in memory; name is used in messages. */
int obj_parse(const char *text, size_t len, const char *name, struct mesh *out, char *err,
              size_t errlen);

/* Angle-weighted vertex normals (each face adds its unit normal times the corner angle):
 * unlike area weighting the result does not depend on how a face was split into
 * triangles, e.g. every corner of a triangulated cube gets normalize(+-1, +-1, +-1).
 * Vertices touched only by degenerate triangles get (0, 0, 1). Returns 0, or 3 (memory). */
int mesh_smooth_normals(struct mesh *m, char *err, size_t errlen);

/* Axis-aligned bounds of the vertices. */
void mesh_bounds(const struct mesh *m, double lo[3], double hi[3]);

/* A bicubic Bezier patch: cp[4 * i + j] is the control point of row i, column j, in the
 * order POV-Ray lists them (four rows of four points). */
struct bezier_patch {
    double cp[16][3];
};

/* Reads every `bicubic_patch { ... <x, y, z> x16 ... }` block of a POV-Ray scene file.
 * Everything between the patches is skipped; inside a patch, keywords and their values
 * before the control points are skipped, the 16 points must be there. */
int patches_read(const char *path, struct bezier_patch **out, size_t *count, char *err,
                 size_t errlen);
int patches_parse(const char *text, size_t len, const char *name, struct bezier_patch **out,
                  size_t *count, char *err, size_t errlen);

/* Point and unit normal at (u, v) in [0,1]^2; u runs along a row (column index j), v
 * across the rows (row index i), as in POV-Ray; the normal is dP/du x dP/dv normalised
 * (outward on the teapot of povray-examples). Where that cross product
 * vanishes (a patch side collapsed to a point, like the teapot's lid knob and bottom
 * centre) the normal is taken a small step inside the patch. */
void patch_eval(const struct bezier_patch *p, double u, double v, double pos[3], double nrm[3]);

/* Tessellates every patch into density x density quads (two triangles each), with
 * (density + 1)^2 vertices per patch carrying the analytic normals. Triangles wind so that
 * their geometric normal agrees with the analytic one. density in [1, 512]. Returns 0,
 * 2 (density out of range) or 3 (memory / size overflow). */
int patches_tessellate(const struct bezier_patch *patches, size_t count, int density,
                       struct mesh *out, char *err, size_t errlen);

#endif
