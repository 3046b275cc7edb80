/* field.h - error fields for the heatmaps: delta(x, n) over the epicentre and Delta(x, n)
 * over the attenuation zone of one model against its reference, evaluated on the device
 * (kernels/field.cl) on a grid normalised per n, checked against the double host
 * reference on a sample of cells, and stored as JSON so the pictures can be redrawn.
 *
 * Grid (rows = n, log-spaced from n_min to n_max; cols along the normalised x axis):
 *   epicentre:   x = t x_e(n),          t = col/(cols-1)            (axis: x / x_e(n), 0..1)
 *   attenuation: x = x_e(n) u_max^t,    u_max = (pi/2) / x_e(n_max) (axis: x / x_e(n), log 1..u_max)
 * Attenuation cells with x > pi/2 are NaN: the zone ends earlier for small n. */
#ifndef BRDF_FIELD_H
#define BRDF_FIELD_H

#include "schemas.h"
#include <stddef.h>

#include "clsession.h"
#include "models.h"

#define FIELD_DEFAULT_ROWS 121
#define FIELD_DEFAULT_COLS 181
#define FIELD_MAX_CELLS 4000000L

struct field_grid {
    int rows, cols;
    double n_min, n_max;
};

/* The largest finite value of a field and its cell. value is NAN when there is none. */
struct field_peak {
    double value, n, x;
    int row, col;
};

struct field_result {
    struct model_spec model, reference;
    struct field_grid grid;
    double u_max;              /* attenuation axis end, (pi/2) / x_e(n_max) */
    double *n;                 /* rows values of n, as the device saw them (float) */
    float *epi_rel;            /* rows*cols, row-major, row 0 = n_min */
    float *att_abs;            /* rows*cols, NaN past pi/2 */
    struct field_peak epi_peak, att_peak;
    /* Largest |device - double host| over the sampled cells (same nominal x and n). */
    double check_rel_diff, check_abs_diff;
    int check_cells;
    double device_seconds;
    /* A field file of a model this process does not know (a user model of the run that made it):
       model.info points here, made from the file's label, formula and lobe (field_read_json). */
    struct model_info *standin;
};

struct field_ctx {
    struct cl_session *s;
    cl_program program;
    cl_kernel kernel;
    char build_options[256];        /* a user model's build of field.cl uses them too (programs.h) */
};

/* Checks rows/cols (2..10000, product <= FIELD_MAX_CELLS) and 0 < n_min < n_max <= 1e6.
 * Returns 0 or EXIT_USAGE with a message. */
int field_grid_check(const struct field_grid *g, char *err, size_t errlen);
/* x of a cell (radians) in each zone, in double. */
double field_epi_x(const struct field_result *r, int row, int col);
double field_att_x(const struct field_result *r, int row, int col);
/* The n of a row, log-spaced (before rounding to float). */
double field_row_n(const struct field_grid *g, int row);

int field_open(struct field_ctx *f, struct cl_session *s, const char *build_options);
void field_close(struct field_ctx *f);
/* Evaluates the field of m against its reference. Returns 0 or an exit code (3). */
int field_run(struct field_ctx *f, const struct model_spec *m, const struct field_grid *g, struct field_result *out);
void field_result_free(struct field_result *r);
/* Finds the peaks of both fields (also used after reading a file back). */
void field_find_peaks(struct field_result *r);

#endif
