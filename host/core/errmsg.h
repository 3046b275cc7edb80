/* errmsg.h - the one-line message an engine or parser hands back in (err, errlen). */
#ifndef BRDF_ERRMSG_H
#define BRDF_ERRMSG_H

#include <stddef.h>

/* printf into err (at most errlen bytes, always terminated); nothing when err is NULL or
 * errlen is 0. */
void set_err(char *err, size_t errlen, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

#endif
