/*
 * merl.cl - a measured BRDF (the MERL table, Matusik et al. 2003) evaluated on the device.
 *
 * The table is a float buffer in the file's layout (red, green, blue blocks of 1,458,000 cells,
 * each phi_d_i + 180 (theta_d_i + 90 theta_h_i)), already scaled to sr^-1; a negative value
 * marks a cell that was not measured and is passed through as it is. One work-item per
 * direction pair: L and V in tangent space (N = z) as xyz triples. The conversion to
 * Rusinkiewicz's half/difference angles and the index mapping are brdf_merl_half_diff and
 * brdf_merl_index3 of brdf_models.h, which the host's double lookup (host/core/merl.c) uses too.
 * Output: the three channels and the flat cell index, for the host's check.
 */
#define REAL float
#define RSCALAR float
#include "brdf_models.h"

__kernel void merl_lookup(__global const float *table, __global const float *l, __global const float *v,
                          uint count, __global float *rgb, __global int *cell)
{
    uint i = get_global_id(0);
    if (i >= count)
        return;
    float th, td, pd;
    brdf_merl_half_diff(l[3 * i], l[3 * i + 1], l[3 * i + 2], v[3 * i], v[3 * i + 1], v[3 * i + 2], &th, &td, &pd);
    int ih, id, ip;
    int idx = brdf_merl_index3(th, td, pd, &ih, &id, &ip);
    rgb[3 * i] = table[idx];
    rgb[3 * i + 1] = table[BRDF_MERL_CELLS + idx];
    rgb[3 * i + 2] = table[2 * BRDF_MERL_CELLS + idx];
    cell[i] = idx;
}
