/* report_claims.h - the claims page (claims.md, and report.md's "Claims of the papers") as a
 * function of rows: claims.json's rows (one per claim: its id, kind, source, the claim, what
 * was claimed and measured, the tolerance, the verdict, the note and the method), q_sweep.json's
 * context (the Q sweep's grid, for the closing "Grids:" line) and, when the claims run measured
 * the physically based models' cost, physical.json's rows (their section at the page's end).
 * reproduce writes claims.md by calling it on the rows it builds in memory; report.md calls it
 * on the same rows read back from the run folder, so the two agree by construction.
 *
 * The rows' layout (what the writers put in them and the upgrade functions of the previous
 * schemas rebuild):
 * - claims: context "claim grid" ("n step 1, 4096 samples per zone") and, when the page carries
 *   the physically based models' section, "physically based models" = "physical.json"; a row
 *   per claim, key id, attributes kind ("claim" or "check") and source, metrics claimed and
 *   measured (unit 1, direction neither; left out where the claim or the measurement is not a
 *   single number, as claims.json's null with its reason: compare would read a null as a
 *   figure that failed), texts claim,
 *   claimed_text, measured_text, tolerance, verdict ("reproduced", "within noise",
 *   "not reproduced"), note, method.
 * - q_sweep: context "Q grid" ("Q = 0.01..0.99 step 0.01, n in [2, 1000] step 1, 1024 samples
 *   per zone").
 * - physical: context n, reps and check_points; document text lookup_note (when measured
 *   materials were timed); a row per timed model (key model; attributes evaluates,
 *   physically_based; metrics evaluations_per_s, ratio_to_fq2, ratio_to_phong, ratio_to_pow,
 *   check_max_abs_of_peak, and albedo_normal_incidence, he_terms_mean, he_terms_max where the
 *   model has them; texts vs_fq2, vs_phong (compare's verdicts) and check_status), then a row per
 *   angle of He's terms table (keys table "He terms", theta "30 deg"; metrics
 *   terms_mirror@RATIO and terms_off@RATIO per sigma0/lambda ratio). */
#ifndef BRDF_REPORT_CLAIMS_H
#define BRDF_REPORT_CLAIMS_H

#include "mdbuf.h"
#include "rdoc.h"

/* The claims context line that says the page carries physical.json's section. */
#define REPORT_CLAIMS_PHYSICAL_CTX "physically based models"

/* claims.md: the summary, the claims and harness checks tables, the grids line and, when
 * physical is not NULL, the physically based models' section. q_sweep may be NULL (its grid
 * then reads "?"). Returns 0, or 3 when out of memory (b->failed). */
int report_claims_page(struct md_buf *b, const struct rdoc *claims, const struct rdoc *q_sweep,
                       const struct rdoc *physical);

/* The physically based models' section: cost, He's terms, albedo (physical.json's rows). */
void report_physical_section(struct md_buf *b, const struct rdoc *physical);

#endif
