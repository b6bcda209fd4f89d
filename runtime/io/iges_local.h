/* iges_local.h — what the files of the IGES reader share: the reader's
 * state (records, directory entries, the parameter cache, the geometry
 * budget), the free-format parameter accessors that fail with
 * `file:line: entity TYPE (D n): ...`, transformations and colours
 * (iges_params.c), records and sections (iges_sections.c), trim and
 * model-space curves (iges_curves.c), surfaces (iges_surfaces.c), the
 * model-space curves of a loop (iges_faces.c). read_iges.c, the top,
 * builds the faces. */
#ifndef SC_IGES_LOCAL_H
#define SC_IGES_LOCAL_H

#include "envelope.h"
#include "io.h"
#include "nurbs.h"

enum {
    RECORD_COLS = 80,
    SECTION_COL = 72,   /* 0-based column of the section letter */
    GLOBAL_COLS = 72,   /* data columns of G records */
    PARAM_COLS = 64,    /* data columns of P records */
    MAX_NESTING = 64    /* composite curves inside composite curves */
};

enum section { SEC_S, SEC_G, SEC_D, SEC_P, SEC_T, SEC_COUNT };

/* What building a trim loop can end in besides SC_FAIL / SC_OK. */
enum { LOOP_NO_PCURVE = 1, LOOP_UNSUPPORTED = 2, LOOP_OFF_SURFACE = 3 };

typedef struct record {
    const char *text;
    int len;  /* at most 80; missing columns read as blanks */
    int line; /* line in the file, 1-based */
} record;

typedef struct entity {
    int type, pdata, xform, color, nlines, subscript, form;
    char label[9];
    int line;                 /* file line of its first directory record */
    unsigned char busy;       /* on the current conversion path: a revisit is a cycle */
    unsigned char referenced; /* used as the surface of a 142/144/143/141/510/140 */
    unsigned char has_matrix;
    unsigned char in_subfigure; /* a member of a 308: drawn through its 408s */
    unsigned char counting;   /* on the current path of count_pieces */
    int pieces;               /* curves it expands into (count_pieces), 0 until counted */
    double matrix[12];        /* its own matrix, for a 124, once parsed */
} entity;

typedef struct token {
    int start, len;
    int is_string;
} token;

/* The parameters of one entity: columns 1-64 of its P records concatenated
 * and cut into tokens; tok[0] is the entity type, tok[i] the i-th parameter
 * of the specification's tables. */
typedef struct params {
    int entity;
    int first_record;
    char *text;
    token *tok;
    int ntok, cap;
    int borrowed;  /* text and tok belong to the reader's cache */
} params;

/* A parameter record tokenised once, by its first P line, however many
 * entities point at it: `status` is what stopped iges_tokenize, `at` and `n` where. */
typedef struct parsed_record {
    int done, status, at, n;
    params p;
} parsed_record;

/* Curves read from the file: 2D (parameter space, dim 0 or 2: x and y
 * of the transformed points) or 3D (model space, dim 3). */
typedef struct curve_list {
    sc_curve *items;
    int n, cap;
    int dim;
} curve_list;

typedef struct reader {
    const char *name;
    sc_scene *scene;
    sc_error *err;
    record *rec;
    int nrec;
    int sec_first[SEC_COUNT], sec_count[SEC_COUNT];
    char pdelim, rdelim;
    entity *ent;
    int nent;
    parsed_record *parsed;   /* per P record, filled on demand */
    size_t tokenised;        /* characters tokenised so far (bounded, see tokenise_record) */
    sc_budget budget;        /* geometry charged so far (envelope.h) */
    int cur_owner;           /* the face being built (for budget messages) */
    double instance[12];     /* placement of the subfigure instance being drawn */
    long instance_visits;    /* members visited through 408 instances */
    int warned_no_pcurve, warned_unsupported, warned_off_surface, warned_unbounded;
    int unsupported_entity; /* the curve that stopped the last loop */
} reader;


extern const double iges_identity[12];

enum { TOK_END, TOK_CUT, TOK_BAD_STRING, TOK_NO_MEMORY };

int iges_fail_at(reader *r, int line, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
int iges_fail(reader *r, int e, int line, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
int iges_fail_oom(reader *r, int e, size_t bytes, const char *what);
int iges_gather(const reader *r, int first, int n, int cols, char *buf);
int iges_tokenize(const char *t, int n, char pd, char rd, params *p, int *at);
void iges_params_free(params *p);
int iges_line(const reader *r, const params *p, int i);
int iges_parse_real(const char *s, int len, double *out);
int iges_real(reader *r, const params *p, int i, double *out);
int iges_int(reader *r, const params *p, int i, int *out);
int iges_pointer(reader *r, const params *p, int i, int *target);
int iges_need(reader *r, const params *p, long long n);
int iges_count(reader *r, const params *p, int i, int per, int *out);
int iges_params(reader *r, int e, params *p);
void iges_compose(const double a[12], const double b[12], double out[12]);
int iges_xform(reader *r, int e, double m[12]);
int iges_color(reader *r, int e, float rgb[3]);
int iges_check_knots(reader *r, const params *p, int first_param, const double *k,
                             int nk, int degree, const char *what);
int iges_read_knots(reader *r, const params *p, int at, double *k, int nk, int degree,
                            const char *what);
/* A zeroed curve appended to the list; NULL when memory runs out. */
sc_curve *iges_list_push(curve_list *l);
void iges_list_free(curve_list *l);
void iges_put_point(sc_curve *c, int i, const double m[12], double x, double y, double z,
                      double w);
int iges_leading_reals(reader *r, const params *p, int n, double *v);
int iges_charge_curves(reader *r, int e, const curve_list *l, int first);
void iges_reverse_chain(curve_list *l, int first);
int iges_trim_curves(reader *r, int e, const double parent[12], int reversed, curve_list *out,
                       int depth);
void iges_orient_chain(curve_list *l);
int iges_read_128(reader *r, int e, sc_surface *s);

/* A surface entity as read (iges_surfaces.c): `nurbs` is its exact NURBS,
 * or, for the unbounded planes, cylinders and cones, still empty until the
 * trims say how far it reaches (need_bounds; iges_bound_surface). The
 * frame is o + x, y, z (z the axis or normal). */
enum { IGES_BOUND_PLANE = 1, IGES_BOUND_AXIS = 2 };
typedef struct iges_surface {
    int type;
    int need_bounds;
    double o[3], x[3], y[3], z[3];
    double radius, slope;   /* cylinder, cone: radius at o, its change along z */
    sc_surface nurbs;
} iges_surface;

/* 1: read (sf->nurbs set unless need_bounds); 0: a type not converted;
 * SC_FAIL. */
int iges_read_surface(reader *r, int e, iges_surface *sf);
/* Builds sf->nurbs of a need_bounds surface to cover the model-space
 * loops (3D curves in its object space): SC_OK, IGES_NO_BOUNDS when they
 * are empty (or only reach past a cone's apex), SC_FAIL when memory runs
 * out. */
enum { IGES_NO_BOUNDS = 1 };
int iges_bound_surface(iges_surface *sf, const curve_list *loops, int n);
/* 3D curves on a plane surface to its (u, v): exact (affine). SC_FAIL when
 * memory runs out (the curves made so far stay in `out`). */
int iges_plane_curves(const iges_surface *sf, const curve_list *in, curve_list *out);

/* iges_faces.c: the model-space curves of loop entity e (142, 141, 508)
 * in loop order, mapped by to_obj into the surface's object space: SC_OK,
 * LOOP_NO_PCURVE (it has none), LOOP_UNSUPPORTED or SC_FAIL. */
int iges_loop_model(reader *r, int e, const double to_obj[12], curve_list *out);
int iges_invert(const double m[12], double out[12]);

/* iges_sections.c: records, the global section (delimiters), the
 * directory. */
int iges_read_records(reader *r, const char *text, size_t size);
int iges_read_global(reader *r);
int iges_read_directory(reader *r);

void iges_power_to_bezier(const double c[4], double h, double b[4]);

#endif
