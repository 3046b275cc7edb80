/* hemisphere_pictures.h - the hemisphere sweep's pictures (accuracy --pictures). */
#ifndef BRDF_HEMISPHERE_PICTURES_H
#define BRDF_HEMISPHERE_PICTURES_H

#include <stddef.h>

#include "hemisphere.h"

/* For each result, in dir: hemisphere_heatmap_LABEL.png (delta and Delta over theta_h, theta_d
 * at the phi_d and parameter value of its largest Delta), hemisphere_max_rel_vs_p_LABEL.png and
 * hemisphere_max_abs_vs_p_LABEL.png. *drawn counts the pictures. 0, or EXIT_RUNTIME with err. */
int hemisphere_draw(const struct hemi_result *res, int count, const char *dir, int *drawn, char *err, size_t errlen);

#endif
