/* usermodel_check.h - what a user model's text may not do, and the deadline of its host
 * reference (docs/user-models.md).
 *
 * The text check: a model (a file's text, an expression) may not name brdfbench's own code:
 * every brdf_*, BRDF_* and brdfbench_* identifier but the documented helpers of
 * kernels/brdf_models.h is refused, outside comments and literals and after line
 * continuations are joined; so is token pasting (##), which could build such a name. In a
 * model file, a function or macro that reaches itself is refused too. The wrapper
 * brdf_user_eval and the dispatchers brdf_eval* lead back into the model, and OpenCL C has no
 * recursion: PoCL's compiler crashes on it (SIGSEGV) instead of saying so.
 *
 * The deadline: the host reference is the model's own code in this process, one call per
 * value. usermodel_watch_begin/end mark a call (a counter and the point, plain stores); a
 * watcher thread, started with the first call, reports a call that has not returned after a
 * second (again every 10 s) and ends the run at the launch deadline (clsession_timeout) as a
 * runaway kernel does: one line, the unfinished outputs removed, exit 3.
 */
#ifndef BRDF_USERMODEL_CHECK_H
#define BRDF_USERMODEL_CHECK_H

#include <stddef.h>

#include "usermodel.h"

/* Checks a model's text. what: "PATH" (a model file, text from line 1: messages name
 * PATH:LINE) or "--model NAME" (an expression: messages name the character). Returns 0, or
 * EXIT_USAGE with the message (EXIT_RUNTIME when out of memory). */
int usermodel_check_text(const char *text, size_t len, const char *what, int is_file, char *err, size_t errlen);

/* Checks an OpenCL C model's text (a model file, a --model or gates-file expression) for
 * what a lobe's formula has no use for and what would reach memory outside the model's own
 * variables: pointers ('*' as a dereference or declarator, '&' as address-of, casts to a
 * pointer type, '->'), arrays and subscripts, asm, volatile, sizeof, address spaces, string
 * literals, calls of anything but a math built-in that takes no pointer or the model's own
 * functions and macros, and directives other than #define, #undef, #if..., #pragma, #error
 * (usermodel_code.c says how). Messages name PATH:LINE:COLUMN or "--model NAME:COLUMN".
 * Returns 0, or EXIT_USAGE with the message (EXIT_RUNTIME when out of memory). */
int usermodel_check_code(const char *text, size_t len, const char *what, int is_file, char *err, size_t errlen);

/* A user model's name against every model known so far: two names that give one file name
 * (field_NAME.json and heatmap_NAME.png drop '_': x_y and xy; render's NAME_error.png and
 * NAME_contact.png: fq2_error and fq2) and render's own stems (contact, he_*) are refused.
 * Returns 0, or EXIT_USAGE with a message naming both models. */
int usermodel_check_file_names(const char *name, char *err, size_t errlen);

/* Around one call of a user model's host reference. */
void usermodel_watch_begin(const struct user_model *um, double c, double n);
void usermodel_watch_end(void);

#endif
