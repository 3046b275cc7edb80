/* raster.c - G-buffer allocation, perspective camera, triangle rasteriser and the analytic
 * sphere grid (see raster.h). */
#include "raster.h"
#include "errmsg.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RASTER_PI 3.14159265358979323846

size_t gbuffer_bytes(long width, long height)
{
    if (width <= 0 || height <= 0)
        return 0;
    size_t npix = (size_t)width * (size_t)height;
    if (npix / (size_t)width != (size_t)height || npix > SIZE_MAX / 2)
        return 0;
    size_t stride = (npix + GBUFFER_ALIGN - 1) / GBUFFER_ALIGN * GBUFFER_ALIGN;
    if (stride > SIZE_MAX / (GB_NPLANES * sizeof(float)))
        return 0;
    return stride * GB_NPLANES * sizeof(float);
}

int gbuffer_alloc(struct gbuffer *g, int width, int height, char *err, size_t errlen)
{
    memset(g, 0, sizeof *g);
    size_t bytes = gbuffer_bytes(width, height);
    if (bytes == 0) {
        set_err(err, errlen, "G-buffer %dx%d: size overflow", width, height);
        return 3;
    }
    g->data = calloc(bytes / sizeof(float), sizeof(float));
    if (!g->data) {
        set_err(err, errlen, "G-buffer %dx%d: out of memory (%zu bytes)", width, height, bytes);
        return 3;
    }
    g->width = width;
    g->height = height;
    g->npix = (size_t)width * (size_t)height;
    g->stride = bytes / sizeof(float) / GB_NPLANES;
    return 0;
}

void gbuffer_free(struct gbuffer *g)
{
    if (!g)
        return;
    free(g->data);
    memset(g, 0, sizeof *g);
}

/* Orthonormal camera basis: forward, right, up. */
static void camera_basis(const struct camera *cam, double f[3], double r[3], double u[3])
{
    vec3_sub(cam->target, cam->eye, f);
    vec3_normalize(f);
    vec3_cross(f, cam->up, r);
    vec3_normalize(r);
    vec3_cross(r, f, u);
}

void camera_ray(const struct camera *cam, int width, int height, double x, double y,
                double dir[3])
{
    double f[3], r[3], u[3];
    camera_basis(cam, f, r, u);
    double t = tan(cam->fov_y_deg * RASTER_PI / 360.0);
    double aspect = (double)width / height;
    double sx = (2.0 * (x + 0.5) / width - 1.0) * t * aspect;
    double sy = (1.0 - 2.0 * (y + 0.5) / height) * t;
    for (int c = 0; c < 3; c++)
        dir[c] = f[c] + sx * r[c] + sy * u[c];
    vec3_normalize(dir);
}

void camera_fit_mesh(struct camera *cam, const struct mesh *m, const double from[3],
                     const double up[3], double fov_y_deg, double aspect, double fill)
{
    double lo[3], hi[3], dir[3] = {from[0], from[1], from[2]};
    mesh_bounds(m, lo, hi);
    vec3_normalize(dir);
    for (int c = 0; c < 3; c++) {
        cam->target[c] = 0.5 * (lo[c] + hi[c]);
        cam->eye[c] = cam->target[c] + dir[c]; /* orientation only; distance below */
        cam->up[c] = up[c];
    }
    cam->fov_y_deg = fov_y_deg;
    double f[3], r[3], u[3];
    camera_basis(cam, f, r, u);
    double tan_y = fill * tan(fov_y_deg * RASTER_PI / 360.0), tan_x = tan_y * aspect;
    /* vertex q (relative to the target) has depth dist + q.f and must satisfy
       |q.r| <= tan_x * depth and |q.u| <= tan_y * depth: each gives a least distance */
    double dist = 0.0;
    for (size_t v = 0; v < m->nverts; v++) {
        double q[3];
        for (int c = 0; c < 3; c++)
            q[c] = m->pos[3 * v + c] - cam->target[c];
        double need_x = fabs(vec3_dot(q, r)) / tan_x - vec3_dot(q, f);
        double need_y = fabs(vec3_dot(q, u)) / tan_y - vec3_dot(q, f);
        double need_front = 1e-3 - vec3_dot(q, f); /* stay in front of the camera */
        dist = fmax(dist, fmax(need_front, fmax(need_x, need_y)));
    }
    for (int c = 0; c < 3; c++)
        cam->eye[c] = cam->target[c] + dist * dir[c];
}

/* Pixel pi of the G-buffer: its position, normal (as float) and shininess. */
static void gbuffer_put(struct gbuffer *g, size_t pi, const double pos[3], const double nrm[3], float shininess)
{
    for (int k = 0; k < 3; ++k) {
        gbuffer_plane(g, GB_PX + k)[pi] = (float)pos[k];
        gbuffer_plane(g, GB_NX + k)[pi] = (float)nrm[k];
    }
    gbuffer_plane(g, GB_SHIN)[pi] = shininess;
}

static double edge_fn(const double *a, const double *b, double px, double py)
{
    return (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
}

/* The edge function evaluated with its end points in a fixed order, so that the two
   triangles sharing an edge get exactly opposite values at every pixel centre: a centre
   on the edge is then covered by at least one of them, never lost to rounding. */
static double edge_fn_canonical(const double *a, const double *b, double px, double py)
{
    if (a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]))
        return edge_fn(a, b, px, py);
    return -edge_fn(b, a, px, py);
}

int raster_mesh(struct gbuffer *g, const struct mesh *m, const struct camera *cam,
                float shininess, char *err, size_t errlen)
{
    const int W = g->width, H = g->height;
    /* inverse view depth per pixel: larger is nearer, 0 is empty */
    double *inv_depth = calloc(g->npix, sizeof *inv_depth);
    if (!inv_depth) {
        set_err(err, errlen, "rasteriser: out of memory for the depth buffer");
        return 3;
    }
    double f[3], r[3], u[3];
    camera_basis(cam, f, r, u);
    double t = tan(cam->fov_y_deg * RASTER_PI / 360.0);
    double aspect = (double)W / H;
    double lo[3], hi[3];
    mesh_bounds(m, lo, hi);
    double d[3];
    vec3_sub(hi, lo, d);
    double near_z = 1e-6 * sqrt(vec3_dot(d, d));

    const float *sh = gbuffer_plane(g, GB_SHIN);

    for (size_t ti = 0; ti < m->ntris; ti++) {
        double P[3][3], N[3][3], S[3][2], Z[3];
        int behind = 0;
        for (int k = 0; k < 3; k++) {
            size_t vi = m->tri[3 * ti + k];
            double rel[3];
            for (int c = 0; c < 3; c++) {
                P[k][c] = m->pos[3 * vi + c];
                N[k][c] = m->nrm[3 * vi + c];
            }
            vec3_sub(P[k], cam->eye, rel);
            Z[k] = vec3_dot(rel, f);
            if (!(Z[k] > near_z)) {
                behind = 1;
                break;
            }
            S[k][0] = (vec3_dot(rel, r) / (Z[k] * t * aspect) + 1.0) * 0.5 * W;
            S[k][1] = (1.0 - vec3_dot(rel, u) / (Z[k] * t)) * 0.5 * H;
        }
        if (behind)
            continue;
        double area = edge_fn(S[0], S[1], S[2][0], S[2][1]);
        if (!(fabs(area) > 1e-12))
            continue; /* degenerate or edge-on: covers no pixel centre reliably */
        double e1[3], e2[3], gn[3], toeye[3];
        vec3_sub(P[1], P[0], e1);
        vec3_sub(P[2], P[0], e2);
        vec3_cross(e1, e2, gn);
        vec3_sub(cam->eye, P[0], toeye);
        double flip = vec3_dot(gn, toeye) < 0 ? -1.0 : 1.0;
        vec3_normalize(gn);

        double minx = fmin(S[0][0], fmin(S[1][0], S[2][0]));
        double maxx = fmax(S[0][0], fmax(S[1][0], S[2][0]));
        double miny = fmin(S[0][1], fmin(S[1][1], S[2][1]));
        double maxy = fmax(S[0][1], fmax(S[1][1], S[2][1]));
        /* pixel centres x + 0.5 inside [minx, maxx] */
        long x0 = (long)ceil(minx - 0.5), x1 = (long)floor(maxx - 0.5);
        long y0 = (long)ceil(miny - 0.5), y1 = (long)floor(maxy - 0.5);
        if (x0 < 0)
            x0 = 0;
        if (y0 < 0)
            y0 = 0;
        if (x1 > W - 1)
            x1 = W - 1;
        if (y1 > H - 1)
            y1 = H - 1;
        double inv_area = 1.0 / area;
        for (long y = y0; y <= y1; y++) {
            double cy = y + 0.5;
            for (long x = x0; x <= x1; x++) {
                double cx = x + 0.5;
                double b0 = edge_fn_canonical(S[1], S[2], cx, cy) * inv_area;
                double b1 = edge_fn_canonical(S[2], S[0], cx, cy) * inv_area;
                double b2 = edge_fn_canonical(S[0], S[1], cx, cy) * inv_area;
                /* inclusive on every edge: a centre on a shared edge is covered by both
                   triangles at the same depth, never by neither */
                if (b0 < 0 || b1 < 0 || b2 < 0)
                    continue;
                double w0 = b0 / Z[0], w1 = b1 / Z[1], w2 = b2 / Z[2];
                double iz = w0 + w1 + w2;
                size_t pi = (size_t)y * W + (size_t)x;
                if (!(iz > inv_depth[pi]))
                    continue;
                inv_depth[pi] = iz;
                w0 /= iz;
                w1 /= iz;
                w2 /= iz;
                double pos[3], nrm[3];
                for (int c = 0; c < 3; c++) {
                    pos[c] = w0 * P[0][c] + w1 * P[1][c] + w2 * P[2][c];
                    nrm[c] = flip * (w0 * N[0][c] + w1 * N[1][c] + w2 * N[2][c]);
                }
                double nl = sqrt(vec3_dot(nrm, nrm));
                if (nl > 1e-12) {
                    for (int c = 0; c < 3; c++)
                        nrm[c] /= nl;
                } else { /* opposing vertex normals: fall back to the face's own */
                    for (int c = 0; c < 3; c++)
                        nrm[c] = flip * gn[c];
                }
                gbuffer_put(g, pi, pos, nrm, shininess);
            }
        }
    }
    free(inv_depth);
    g->foreground = 0;
    for (size_t i = 0; i < g->npix; i++)
        g->foreground += sh[i] > 0.0f;
    return 0;
}

void sphere_grid_layout(int width, int height, int rows, int cols, struct sphere_grid *sg,
                        struct camera *cam)
{
    sg->rows = rows;
    sg->cols = cols;
    /* cells are 1 world unit high; their width keeps the pixels square */
    sg->cell_w = ((double)width / cols) / ((double)height / rows);
    /* 0.42 of the cell leaves room for the perspective enlargement (about 3%) */
    sg->radius = 0.42 * (sg->cell_w < 1.0 ? sg->cell_w : 1.0);
    /* a distant camera (mild perspective) whose frame at z = 0 is exactly the grid */
    double dist = 4.0 * rows;
    cam->eye[0] = 0.0;
    cam->eye[1] = 0.0;
    cam->eye[2] = dist;
    cam->target[0] = cam->target[1] = cam->target[2] = 0.0;
    cam->up[0] = 0.0;
    cam->up[1] = 1.0;
    cam->up[2] = 0.0;
    cam->fov_y_deg = 2.0 * atan(0.5 * rows / dist) * 180.0 / RASTER_PI;
}

void sphere_grid_centre(const struct sphere_grid *sg, int row, int col, double c[3])
{
    c[0] = (col + 0.5) * sg->cell_w - 0.5 * sg->cols * sg->cell_w;
    c[1] = 0.5 * sg->rows - (row + 0.5);
    c[2] = 0.0;
}

int raster_spheres(struct gbuffer *g, int rows, int cols, const double *col_shininess,
                   struct camera *cam, char *err, size_t errlen)
{
    if (rows < 1 || cols < 1) {
        set_err(err, errlen, "sphere grid needs at least one row and one column");
        return 3;
    }
    struct sphere_grid sg;
    sphere_grid_layout(g->width, g->height, rows, cols, &sg, cam);
    g->foreground = 0;
    const double r2 = sg.radius * sg.radius;
    for (int y = 0; y < g->height; y++) {
        int row = (int)((long)y * rows / g->height);
        for (int x = 0; x < g->width; x++) {
            int col = (int)((long)x * cols / g->width);
            double dir[3];
            camera_ray(cam, g->width, g->height, x, y, dir);
            double c[3], oc[3];
            sphere_grid_centre(&sg, row, col, c);
            vec3_sub(c, cam->eye, oc);
            double b = vec3_dot(oc, dir);
            double disc = b * b - (vec3_dot(oc, oc) - r2);
            if (disc < 0)
                continue;
            double tt = b - sqrt(disc); /* nearer root: the visible side */
            double pos[3], nrm[3];
            for (int k = 0; k < 3; k++) {
                pos[k] = cam->eye[k] + tt * dir[k];
                nrm[k] = (pos[k] - c[k]) / sg.radius;
            }
            vec3_normalize(nrm);
            size_t pi = (size_t)y * g->width + (size_t)x;
            gbuffer_put(g, pi, pos, nrm, (float)col_shininess[col]);
            g->foreground++;
        }
    }
    return 0;
}
