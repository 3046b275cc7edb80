/* merl.h - measured BRDFs in the MERL format (Matusik, Pfister, Brand, McMillan 2003): the
 * reader, the half/difference conversion of (L, V, N), the table lookup in double on the host
 * and the same lookup on the device from a float buffer of the same layout.
 *
 * The file: three little-endian int32 dimensions 90 (theta_h), 90 (theta_d), 180 (phi_d), then
 * 3 x 1,458,000 little-endian doubles, the red, green and blue blocks, each in the order
 * phi_d_i + 180 (theta_d_i + 90 theta_h_i); a stored value times its channel's scale
 * (1/1500, 1.15/1500, 1.66/1500) is the BRDF in sr^-1; a negative value marks a cell that was
 * not measured. The index mapping is kernels/brdf_models.h's brdf_merl_index3, shared with the
 * device kernel (kernels/merl.cl).
 *
 * Lookup: the cell holding the direction, no interpolation (docs/measured.md says why). */
#ifndef BRDF_MERL_H
#define BRDF_MERL_H

#include <stddef.h>

#include "clsession.h"

#define MERL_TH 90
#define MERL_TD 90
#define MERL_PD 180
#define MERL_CELLS 1458000L
/* 12 bytes of dimensions and 3 blocks of doubles */
#define MERL_FILE_BYTES (12L + 3L * 8L * MERL_CELLS)

struct merl_material {
    char path[4096];
    char name[256];           /* the file's name without its folder and a ".binary" ending */
    double *value;            /* 3 x MERL_CELLS: red, green, blue blocks, in sr^-1 (scaled) */
    long negative[3];         /* cells of each channel that are negative (not measured) */
    long unmeasured;          /* cells with a negative value in any channel */
};

/* The channel scales to sr^-1. */
extern const double merl_channel_scale[3];

/* Reads a MERL file in one read. Returns 0, or EXIT_USAGE (2) with a one-line message in err
 * that starts with the path: a file that cannot be opened, a short file, dimensions other than
 * 90 90 180, a size that does not match them, a NaN or an infinite value (named by channel and
 * cell), every cell negative; EXIT_RUNTIME when memory runs out. Nothing is kept on failure. */
int merl_read(const char *path, struct merl_material *m, char *err, size_t errlen);
void merl_free(struct merl_material *m);

/* Rusinkiewicz's half/difference angles of unit L, V about unit N (any tangent frame: for an
 * isotropic table phi_h drops out). */
void merl_half_diff(const double L[3], const double V[3], const double N[3], double *theta_h, double *theta_d,
                    double *phi_d);
/* The flat cell index of the angles and its three components (brdf_merl_index3 in double). */
long merl_index(double theta_h, double theta_d, double phi_d, int *ith, int *itd, int *ipd);
/* The angles at a cell's centre: theta_h = ((i + 1/2)/90)^2 pi/2, theta_d = (j + 1/2)/90 pi/2,
 * phi_d = (k + 1/2)/180 pi; merl_index maps them back to (i, j, k). */
void merl_cell_centre(int ith, int itd, int ipd, double *theta_h, double *theta_d, double *phi_d);
/* Unit L and V about N = z with the given half/difference angles (phi_h = 0). */
void merl_dirs(double theta_h, double theta_d, double phi_d, double L[3], double V[3]);

/* The table's value (sr^-1, per channel) for L, V about N: 1 when the cell was measured, 0 when
 * any channel is negative (rgb then holds the stored negative values, scaled). */
int merl_lookup(const struct merl_material *m, const double L[3], const double V[3], const double N[3],
                double rgb[3]);
/* The value of the cell with flat index idx, as merl_lookup. */
int merl_cell(const struct merl_material *m, long idx, double rgb[3]);

/* The device lookup (kernels/merl.cl): count tangent-space direction pairs (L, V as xyz triples,
 * N = z, floats) evaluated from a float copy of the table (3 x MERL_CELLS, scaled); rgb
 * receives 3 floats per pair, index the flat cell index used. Returns 0 or an exit code. */
/* A device buffer of the table in its file's layout (3 x MERL_CELLS floats, scaled), what the
 * kernels that look a material up read (kernels/merl.cl, shade.cl, throughput.cl). Returns 0 or
 * an exit code (a message on stderr). */
int merl_table_buffer(struct cl_session *s, const struct merl_material *m, cl_mem *out);
/* The luminance of the cell holding (L, V) about N (brdf_merl_luminance: 0 where not measured). */
double merl_luminance(const struct merl_material *m, const double L[3], const double V[3], const double N[3]);

int merl_eval_device(struct cl_session *s, const struct merl_material *m, const float *L, const float *V,
                     size_t count, float *rgb, int *index);

#endif
