/* shaderlang_internal.h - inside the shader-language translator (shaderlang.h is its interface):
 * the tokens, the syntax tree, the translation state and the functions its stages share.
 * shaderlang_error.c: failures and the arena; shaderlang_lex.c: the lexer; shaderlang_parse.c:
 * the parser; shaderlang_check.c: types, values, built-ins; shaderlang_emit.c: expressions and
 * statements emitted as C; shaderlang.c: the program and the three builds; shaderlang_brdf.c:
 * BRDF Explorer .brdf files. */
#ifndef BRDF_SHADERLANG_INTERNAL_H
#define BRDF_SHADERLANG_INTERNAL_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include "mdbuf.h"

#define SL_NAME_MAX 48       /* as USERMODEL_NAME_MAX */
#define SL_MAX_PARAMS 2      /* as MODEL_MAX_PARAMS */
#define SL_MAX_ARGS 16       /* arguments of a call; values of a constructor (a mat4 has 16) */
#define SL_MAX_UNROLL 256    /* iterations of one unrolled for loop */
#define SL_MAX_WHILE 32      /* iterations of a while or do loop (unrolled, lane by lane) */
#define SL_MAX_UNROLL_TOTAL 8192 /* loop bodies emitted in all (nested loops multiply) */
#define SL_MAX_OUTPUT ((size_t)4 << 20) /* bytes of translated text (loops unrolled, helpers inlined) */
#define SL_MAX_INLINE 16     /* nested calls of helper functions */
#define SL_MAX_ARRAY 256     /* elements of an array */
#define SL_MAX_MACRO_DEPTH 16
#define SL_MAX_NESTING 200   /* parentheses, operators and statements inside each other */
#define SL_MAX_DEFINES 16    /* -D on the command line; define: lines of a header */
#define SL_DEFINE_MAX 120    /* "NAME VALUE" of one define */

/* ---- memory: one arena per translation ------------------------------------------------ */

struct arena_block {
    struct arena_block *next;
    size_t used, cap;
    max_align_t data[];
};

enum tok_kind { K_EOF, K_ID, K_INT, K_FLT, K_OP };

struct tok {
    int k;
    int line, col;
    const char *p;
    int len;
};

struct tokv {
    struct tok *v;
    int n, cap;
};

struct macro {
    const char *name;
    int len;
    struct tokv body;
    int active;
    struct macro *next;
};

enum base { B_VOID, B_BOOL, B_INT, B_FLOAT, B_STRUCT };
struct sdef;
struct type {
    int b;
    int n; /* components: 1 to 4 (vectors of float only) */
    const struct sdef *st; /* B_STRUCT: its definition */
    int half;              /* B_FLOAT: 0 float (highp), 1 binary16 (half, min16float, mediump:
                              each operation's result goes through RHALF), 2 a literal or an int
                              made float, which takes the other operand's precision */
};

#define SL_MAX_FIELDS 16
/* struct NAME { TYPE field; ... }; */
struct sdef {
    const struct tok *name;
    int nfields;
    const struct tok *fname[SL_MAX_FIELDS];
    struct type fty[SL_MAX_FIELDS];
    int is_matrix;         /* 1: GLSL's matN (fields are columns), 2: HLSL's floatNxN (rows) */
    struct sdef *next;
};

enum expr_kind { E_FLT, E_INT, E_BOOL, E_VAR, E_UN, E_BIN, E_TER, E_CALL, E_SWZ, E_IDX, E_ARR };
struct expr {
    int k;
    const struct tok *t;   /* where it is, for messages; the name of a variable or a call */
    int op;
    struct expr *a, *b, *c;
    struct expr **args;
    int nargs;
    int swz[4], nswz;      /* nswz 0: a name that is no swizzle (a struct's field) */
    const struct tok *field;
    int is_cast;
    int has_ctor;          /* an initialiser list: a constructor of ctor */
    struct type ctor;
};

enum stmt_kind { S_DECL, S_ASSIGN, S_IF, S_BLOCK, S_RET, S_FOR, S_EMPTY, S_CALL, S_WHILE, S_DO, S_BREAK, S_CONTINUE,
                 S_SWITCH, S_CASE };
struct stmt {
    int k;
    const struct tok *t;
    struct type ty;        /* S_DECL */
    int is_const;
    const struct tok *name;
    int is_array;          /* S_DECL of NAME[LEN] (arr_len NULL: the initialiser's count) */
    struct expr *arr_len;
    struct expr *e;        /* init, rhs, condition, returned value */
    struct expr *lhs;
    int op;
    struct stmt *s1, *s2, *s3; /* then/else; for: init, step, body */
    struct stmt **items;   /* S_BLOCK */
    int n, cap;
};

enum param_mode { PM_IN, PM_OUT, PM_INOUT };
struct func {
    const struct tok *name;
    struct type ret;
    int nparams;
    struct type pty[SL_MAX_ARGS];
    const struct tok *pname[SL_MAX_ARGS];
    int pmode[SL_MAX_ARGS];  /* PM_IN, PM_OUT, PM_INOUT */
    struct expr *parr[SL_MAX_ARGS]; /* an array parameter TYPE NAME[LEN]: its length (else NULL) */
    struct stmt *body;
    const struct tok *close;
    struct func *next;
};

/* A loop or a switch being emitted: the lanes that left it by break and, for a loop, those that
 * skip the rest of this iteration by continue, as flags made at the first break or continue (an
 * int where the condition is the same in every lane, else a REAL mask). Every statement inside
 * runs under all of them (effective, shaderlang_emit.c), the enclosing loops' too. */
struct loopctx {
    struct loopctx *up;
    int is_switch;
    const char *brk_int, *brk_real;    /* 1 while the lane has not broken out */
    const char *cont_int, *cont_real;  /* 1 while the lane has not continued (reset each iteration) */
};

struct val;
struct sym {
    const char *name;
    int len;
    struct type t;
    const char *c[4];     /* the C names of its components */
    int is_const;
    int has_value;        /* a constant int: its value */
    long value;
    int arr_n;            /* an array: its length and its elements (each a sym of type t) */
    struct sym **elem;
    struct sym **fields;  /* a struct: one sym per field */
    struct val *fvals;    /* and their values (sl_sym_val) */
    struct sym *next;
};

struct scope {
    struct sym *syms;
    struct scope *up;
    int function_level;   /* implicit declarations go here */
};

struct fnctx {
    struct type ret;
    const char *ret_c[4];  /* NULL until needed (the model function), else declared */
    const char *live;      /* condition "this lane has not returned yet", NULL before any early return */
    const char *live_var;
    int is_model;
    int returned;          /* the model function has returned (a plain return was written) */
    struct sym *ret_sym;   /* a struct returned: where it is kept */
};

/* The C names given out (c_name), in an open-addressing hash table: a name's lookup does not
 * grow with the number of declarations, so unrolled loops translate in linear time. A base
 * keeps the next suffix to try (u__x, u__x_2, ...). */
struct name_slot {
    const char *s;
    unsigned hash;
    int next_suffix;
};
struct name_table {
    struct name_slot *v;
    size_t n, cap;
};

/* The user's text as the preprocessor read it, for the columns of what it wrote (shaderlang_pp.c). */
struct sl_pp {
    const char *src;
    size_t src_len;
    size_t *line_start;
    int nlines;
    int first_line;            /* the user's line of src's first line */
    int cur_line, cursor;      /* where sl_pp_column looks next */
};

struct sl {
    jmp_buf fail;
    char *err;
    size_t errlen;
    const char *origin;
    const char *src;           /* the text being translated */
    struct arena_block *arena;
    struct tokv toks;
    int pos;
    struct macro *macros;
    int allow_implicit;        /* the body form: assigning an undeclared name declares it */
    int shader_only;           /* the text used something OpenCL C has not */
    int unknown_name;          /* the failure was an unknown name */
    int statement_form;
    struct md_buf out;
    int line_next;             /* the line number the next output line has */
    int stmt_line;
    int ntemp;
    struct name_table used;    /* C names given out */
    struct name_table bases;   /* user names declared, with their next suffix */
    long unrolled;             /* loop bodies emitted by unrolling, all loops together */
    double started;            /* wall clock at the start, for the deadline */
    int fail_code;             /* EXIT_USAGE, or EXIT_RUNTIME past the deadline */
    struct sl_pp pp;
    int pp_active;             /* the lexer reads the preprocessor's output: columns through sl_pp_column */
    int line_delta;            /* #line N: the user's numbering minus the text's */
    struct scope *scope, *globals;
    struct func *funcs;
    struct sdef *structs;
    const struct func *inlining[SL_MAX_INLINE];
    int ninline;
    struct fnctx *fn;
    const char *cur_pred;      /* the predicate of the statement being emitted (out parameters' write-back) */
    struct sym **loop_syms;    /* inside a while/do loop: the float variables it writes */
    int nloop_syms, loop_syms_cap;
    int depth;                 /* of the parser's recursion */
    int default_half;          /* `precision mediump float;` (or lowp) was written: float is binary16 */
    struct loopctx *loops;     /* the innermost loop or switch being emitted (NULL: none) */
};


struct val {
    struct type t;
    const char *c[4];
    int uniform;   /* the same in every lane (literals, ints, uniform booleans) */
    struct val *f; /* a struct: its fields' values */
};

struct builtin;

/* What the program's header comment says (sl_read_header). */
struct header {
    int present;
    size_t end;                 /* bytes of the text the header comment takes */
    char name[SL_NAME_MAX + 1];
    char function[SL_NAME_MAX + 1];
    int nparams;
    char params[SL_MAX_PARAMS][SL_NAME_MAX + 1];
    int integer[SL_MAX_PARAMS];
    char reference[SL_NAME_MAX + 1];
    char lobe[16];
    char description[200];
    int ndefines;               /* define: NAME[=VALUE] lines, as "NAME VALUE" */
    char defines[SL_MAX_DEFINES][SL_DEFINE_MAX + 1];
    char define_error[300];     /* a define: line that is not one, for the translation to report */
    int define_line;
    /* A .brdf file: the header written for it, code lexed before and after the user's text
       (no position of their own), and the line the user's text starts on. */
    const char *header_text, *prelude, *epilogue;
    int first_line;
};

#define FAIL(S, t, ...) sl_fail_at((S), (t) ? (t)->line : 0, (t) ? (t)->col : 0, __VA_ARGS__)

/* ---- failures (a message with its line and column, longjmp to the entry point) and the arena ---- */
/* (shaderlang_error.c) */
/* "origin:line:col: message" into err ("origin:line: ..." when col < 0, "origin: ..." without
 * a line). */
void sl_vformat_at(char *err, size_t errlen, const char *origin, int line, int col, const char *fmt, va_list ap);
void sl_fail_at(struct sl *S, int line, int col, const char *fmt, ...) __attribute__((format(printf, 4, 5), noreturn));
void *sl_arena_alloc(struct sl *S, size_t n);
const char *sl_sfmt(struct sl *S, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
const char *sl_tok_str(struct sl *S, const struct tok *t);
int sl_tok_is(const struct tok *t, const char *s);

/* ---- the lexer (shaderlang_lex.c) ---- */
void sl_tokv_push(struct sl *S, struct tokv *v, struct tok t);
void sl_lex_span(struct sl *S, const char *p, const char *end, int line, int col, struct tokv *into);

/* ---- the preprocessor (shaderlang_pp.c) ---- */
/* The text preprocessed by glslang (kept in the arena, *outlen its length) when it has
 * directives the lexer does not read or there are defines; NULL when it needs none. */
const char *sl_preprocess(struct sl *S, const char *text, size_t len, int first_line, const struct header *h,
                          size_t *outlen);
int sl_pp_column(struct sl *S, const struct tok *t, int out_line);
/* A GLSL or HLSL file (by its name) parsed by glslang, the languages' reference compiler, with
 * the same defines: its first error, at the user's line (and the column of the token it names). */
void sl_validate(struct sl *S, const char *text, size_t len, int first_line, const struct header *h);
int sl_define_text(const char *arg, char *out, size_t outlen, char *err, size_t errlen, const char *what);

/* ---- the parser (shaderlang_parse.c) ---- */
const struct tok *sl_peek(struct sl *S);
int sl_type_of_name(const struct tok *t, struct type *ty, int *shader_only);
/* The struct a name defines, or NULL. */
const struct sdef *sl_find_struct(struct sl *S, const struct tok *t);
int sl_same_type(struct type a, struct type b);
struct stmt *sl_new_stmt(struct sl *S, int k, const struct tok *t);
struct stmt *sl_parse_program(struct sl *S, struct stmt *globals);

/* ---- type checks, values and temporaries, the built-in functions (shaderlang_check.c) ---- */
const char *sl_type_name(struct sl *S, struct type t);
void sl_out_line(struct sl *S, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
const char *sl_temp_real(struct sl *S, const char *expr);
const char *sl_temp_cond(struct sl *S, const char *cond, int uniform);
struct val sl_temp_val(struct sl *S, struct val v);
const char *sl_float_literal(struct sl *S, const struct tok *t);
struct val sl_to_float(struct sl *S, struct val v, const struct tok *where);
struct val sl_convert(struct sl *S, struct val v, struct type t, const struct tok *where, const char *what);
struct sym *sl_lookup(struct sl *S, const struct tok *t);
void sl_push_scope(struct sl *S, int function_level);
struct sym *sl_declare(struct sl *S, struct scope *sc, const struct tok *name, struct type t);
struct val sl_sym_val(struct sym *s);
struct sym *sl_declare_array(struct sl *S, struct scope *sc, const struct tok *name, struct type t, int n);
const char *sl_op_text(int op);
struct val sl_arith(struct sl *S, int op, struct val a, struct val b, const struct tok *where);
/* The precision of an operation of a and b (struct type's half): float when either is,
 * binary16 when either is and the other is too or a literal, else a literal's. */
int sl_half_of(int a, int b);
/* v (a float value) rounded to binary16: each component through RHALF, v.t.half 1. */
struct val sl_round_half(struct sl *S, struct val v);
/* The built-in function a call names, or NULL. */
const struct builtin *sl_find_builtin(const struct tok *t);
struct val sl_call_builtin(struct sl *S, const struct builtin *bi, struct expr *e);

/* ---- square matrices, structs of vectors (shaderlang_matrix.c) ---- */
const struct sdef *sl_matrix_def(int n, int rows);
int sl_is_matrix(struct type t);
int sl_matrix_of_name(const char *w, int *n, int *rows);
struct val sl_matrix_transpose(struct sl *S, struct val a, const struct tok *where);
struct val sl_matrix_mul(struct sl *S, struct val a, struct val b, const struct tok *where);
struct val sl_matrix_arith(struct sl *S, int op, struct val a, struct val b, const struct tok *where);
struct val sl_matrix_construct(struct sl *S, struct type t, struct val *parts, int nparts, const struct tok *where);

/* ---- constructors, calls, expressions and statements, emitted as C (shaderlang_emit.c) ---- */
struct func *sl_find_func(struct sl *S, const struct tok *t);
struct val sl_ev(struct sl *S, struct expr *e);
int sl_stmt_returns(const struct stmt *s);
void sl_emit_block(struct sl *S, struct stmt *b, const char *pred, int new_scope);

/* ---- the program (shaderlang.c) ---- */
void sl_read_header(const char *text, size_t len, struct header *h);
int sl_valid_identifier(const char *s);
void sl_full_function_open(struct md_buf *w, int nparams);
int sl_translate(struct sl *S, const char *text, size_t len, const struct header *h, const char *name,
                 char **out, size_t *outlen);
void sl_free(struct sl *S);
/* Fails with exit 3 once the translation has run past the launch deadline (clsession.h). */
void sl_check_deadline(struct sl *S);
int sl_uses_word(const char *text, size_t len, const char *w);

#endif
