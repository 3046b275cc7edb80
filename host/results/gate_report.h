/* gate_report.h - the writing side of gate.h: one line per gate and the summary, JUnit XML
 * and the JSON result (schema GATE_RESULT_SCHEMA), and the check of their paths. */
#ifndef BRDF_GATE_REPORT_H
#define BRDF_GATE_REPORT_H

#include <stdio.h>

#include "gate.h"

/* One line per gate and a summary. */
void gate_set_print(FILE *f, const struct gate_set *g);
/* JUnit XML (one testsuite, one testcase per gate) and the JSON result. Both are written
 * atomically; an existing device file (e.g. /dev/stdout) is written in place. 0 or -1. */
int gate_set_write_junit(const struct gate_set *g, const char *path, const struct cl_session *s,
                         char *err, size_t errlen);
int gate_set_write_json(const struct gate_set *g, const char *path, const struct cl_session *s,
                        char *err, size_t errlen);

#endif
