/* read_obj.h — what the two files of the OBJ reader share: the reader's
 * state (read_obj.c reads statements into it) and the element finishers
 * (read_obj_element.c turns a finished curv2 or surf into scene curves and
 * surfaces). Not part of the io API. */
#ifndef SC_READ_OBJ_H
#define SC_READ_OBJ_H

#include <stdarg.h>

#include "envelope.h"
#include "io.h"

typedef struct obj_vertex {
    double x[4];  /* x y z w as written (Euclidean, weight) or u v w for vp */
    int ncoords;
    int line;
} obj_vertex;

typedef struct obj_vertex_list {
    obj_vertex *v;
    int count, cap;
} obj_vertex_list;

typedef struct obj_material {
    char name[64];
    float kd[3];
} obj_material;

typedef enum obj_cstype { CS_NONE, CS_BEZIER, CS_BSPLINE, CS_UNSUPPORTED } obj_cstype;

typedef enum obj_element_kind { EL_NONE, EL_SURF, EL_CURV2, EL_SPACE_CURVE } obj_element_kind;

/* One `u0 u1 curv2d` of a trim or hole statement, the curve resolved. */
typedef struct obj_trim_ref {
    double t0, t1;
    int curve;
} obj_trim_ref;

typedef struct obj_loop_ref {
    int is_hole;
    int line;
    int nrefs;
    obj_trim_ref *refs;
} obj_loop_ref;

/* The element between its curv2/surf statement and `end`, with the
 * state-setting attributes captured when it began. */
typedef struct obj_element {
    obj_element_kind kind;
    int line;
    obj_cstype cstype;
    int rational;
    int cstype_line;
    char cstype_name[16];
    int deg[2];
    double range[4];           /* s0 s1 t0 t1 of surf */
    int nidx;
    int *idx;                  /* 0-based vertex or parameter-vertex indices */
    int nparm[2];
    double *parm[2];
    int parm_line[2];
    int nloops;
    obj_loop_ref *loops;
} obj_element;

typedef struct obj_reader {
    const char *name;
    sc_error *err;
    sc_scene *scene;
    /* logical lines */
    const char *pos, *end;
    int next_line, line;
    char *buf;
    size_t buf_cap;
    char **tok;
    int ntok, tok_cap;
    /* data */
    obj_vertex_list verts, pverts;
    sc_curve *curves;
    int ncurves;
    obj_material *materials;
    int nmaterials;
    /* state-setting statements */
    obj_cstype cstype;
    int rational;
    int cstype_line;
    char cstype_name[16];
    int deg[2];
    char cur_name[64];
    float cur_color[3];
    obj_element el;
    sc_budget budget; /* geometry charged so far (envelope.h) */
    /* what was skipped */
    int polygons, space_curves, special_curves, special_points, connections, shell_commands;
    int unknown_statements;
} obj_reader;

/* Fails with the reader's file name and a line number. Inline so that both
 * files use it without one calling into the other. */
static inline int fail(obj_reader *r, int line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static inline int fail(obj_reader *r, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int status = sc_vfail(r->err, r->name, line, fmt, ap);
    va_end(ap);
    return status;
}

/* The element in r->el, ended: a curve appended to r->curves, or a surface
 * (with its trim loops) added to the scene. */
int sc_obj_finish_curv2(obj_reader *r);
int sc_obj_finish_surf(obj_reader *r);

#endif
