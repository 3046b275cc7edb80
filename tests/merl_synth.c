/* merl_synth.c - writes a MERL-format file from an analytic BRDF (tests/merl_synth.h) for the
 * shell tests and the docs' example runs:
 *   merl_synth OUT blinn N KS KD          ks cos(theta_h)^n + kd
 *   merl_synth OUT ggx ALPHA F0 KS KD     kd + ks D F G / (4 N.L N.V), GGX
 *   merl_synth OUT pattern                distinct values per cell
 * followed by at most one defect: short (one byte short), dims360 (dimensions 90 90 360),
 * nan (a NaN in the blue block), neg LO HI (green theta_h cells LO..HI-1 negative). */
#include "merl_synth.h"

int main(int argc, char **argv)
{
    struct syn_material m = { .kind = SYN_PATTERN };
    struct syn_defects d;
    syn_defects_none(&d);
    int a = 3;
    if (argc >= 6 && strcmp(argv[2], "blinn") == 0) {
        m = (struct syn_material){ .kind = SYN_BLINN, .n = atof(argv[3]), .ks = atof(argv[4]), .kd = atof(argv[5]) };
        a = 6;
    } else if (argc >= 7 && strcmp(argv[2], "ggx") == 0) {
        m = (struct syn_material){ .kind = SYN_CT_GGX, .alpha = atof(argv[3]), .f0 = atof(argv[4]),
                                   .ks = atof(argv[5]), .kd = atof(argv[6]) };
        a = 7;
    } else if (argc < 3 || strcmp(argv[2], "pattern") != 0) {
        fprintf(stderr, "usage: merl_synth OUT blinn N KS KD | ggx ALPHA F0 KS KD | pattern [short|dims360|nan|neg LO HI]\n");
        return 2;
    }
    if (a < argc) {
        if (strcmp(argv[a], "short") == 0)
            d.trim = 1;
        else if (strcmp(argv[a], "dims360") == 0)
            d.dims[0] = 90, d.dims[1] = 90, d.dims[2] = 360;
        else if (strcmp(argv[a], "nan") == 0)
            d.nan_cell = 1000;
        else if (strcmp(argv[a], "neg") == 0 && a + 2 < argc)
            d.neg_th_lo = atoi(argv[a + 1]), d.neg_th_hi = atoi(argv[a + 2]);
        else {
            fprintf(stderr, "merl_synth: unknown defect '%s'\n", argv[a]);
            return 2;
        }
    }
    return syn_write(argv[1], &m, &d) ? 3 : 0;
}
