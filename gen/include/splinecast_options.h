/* splinecast_options.h — the options' one vocabulary: the enums a program
 * passes in splinecast.h's desc structs, which are also the values the
 * runtime works with and, where the compiler needs them (start, trim
 * method), the fields of a variant key. They live under gen/base so that
 * every layer (gen/, the runtime's folders, the public header) sees the same
 * types without a translation between them; splinecast.h includes this
 * header and `make install` installs it beside it. Zero means default in
 * every enum a desc carries. */
#ifndef SPLINECAST_OPTIONS_H
#define SPLINECAST_OPTIONS_H

#ifdef __cplusplus
extern "C" {
#endif

/* Limits of the options' numbers: desc fields outside them are refused. */
#define SC_MAX_TRIM_ITERS 64       /* clipping iterations per trim crossing */
#define SC_MAX_HULL_DIVISIONS 64   /* uniform hulls: sub-patches per side */
#define SC_MAX_ITERS 64            /* Newton iterations */
#define SC_MAX_DEGREE 16           /* highest surface degree a program draws */

/* How a ray meets a patch (keys: newton, broyden, bclip, subdiv, hybrid;
 * docs/variant-key.md, docs/compiler.md). */
typedef enum sc_method {
    SC_METHOD_DEFAULT = 0, /* SC_DEFAULT_METHOD: hybrid */
    SC_METHOD_NEWTON,      /* Newton iteration on the ray's two planes */
    SC_METHOD_BROYDEN,     /* Broyden's method: the Jacobian of the first
                              evaluation, then rank-one updates */
    SC_METHOD_BCLIP,       /* Bézier clipping of the sub-patch against the
                              ray's two planes (Nishita et al.) */
    SC_METHOD_SUBDIV,      /* object-space subdivision of the sub-patch
                              (Dammertz & Keller) with a stack of intervals */
    SC_METHOD_HYBRID       /* Newton, restarted from the middles of the
                              sub-patch and its quarters in the same hull
                              where its point is not a converged, kept
                              crossing inside the sub-patch */
} sc_method;

/* Where Newton's method starts (keys: mid, cp, view, secure). */
typedef enum sc_start {
    SC_START_DEFAULT = 0,  /* cpmap */
    SC_START_MID,          /* Newton starts at the middle of the sub-patch */
    SC_START_CPMAP,        /* at the control-point parameters interpolated
                              over the hull */
    SC_START_VIEW,         /* view-dependent: a Newton solve of the ray
                              through each hull vertex in the vertex stage,
                              from the vertex's control-point parameters,
                              interpolated over the hull (seed 000 §4.4) */
    SC_START_SECURE        /* triangular patches (tri keys) only: the four
                              secure starts of seed 004 on the univariate
                              quartic along the projected ray (0, its
                              inflection points, 1), iterated together */
} sc_start;

/* How an unrolled Bézier program evaluates the patch in its iteration
 * (keys: dc, bern, pow). NURBS keys evaluate by de Boor and the generic
 * program by its loops, whatever this says. */
typedef enum sc_eval {
    SC_EVAL_DEFAULT = 0,   /* pow where both degrees are at most
                              SC_DEFAULT_POW_MAX_DEGREE, dc above */
    SC_EVAL_DC,            /* de Casteljau */
    SC_EVAL_BERN,          /* Bernstein basis sums */
    SC_EVAL_POW            /* the power basis by Horner's rule, its
                              coefficients computed once a pixel; the hit
                              point by de Casteljau. Keys of a degree above
                              SC_MAX_POW_DEGREE take dc */
} sc_eval;

/* The power form's rounding error grows about as 2^degree each way: on
 * random patches (tests/test_kernels.c) it stays below 0.5 % of the
 * tolerance up to degree 4 and reaches half of it at 7, where Newton also
 * fails 2.5x as often as with dc (docs/compiler.md, "The power form"). */
#define SC_DEFAULT_POW_MAX_DEGREE 4
#define SC_MAX_POW_DEGREE 6

/* How trimmed surfaces are trimmed (keys: fastNiC, clipNiC, leftNiC, trim0). */
typedef enum sc_trim_method {
    SC_TRIM_DEFAULT = 0,   /* fast */
    SC_TRIM_FAST,          /* a uniform grid: only the pieces in the pixel's cell */
    SC_TRIM_CLIP,          /* every piece, two-sided Bézier clipping */
    SC_TRIM_LEFT,          /* every piece, left-only Bézier clipping */
    SC_TRIM_NONE           /* trim loops ignored: the keys of untrimmed
                              surfaces (trim0), as ignore_trims asks */
} sc_trim_method;

/* Early ray termination (default: manual). */
typedef enum sc_ray_termination {
    SC_TERMINATION_DEFAULT = 0,
    SC_TERMINATION_NONE,        /* every hull fragment runs the intersection */
    SC_TERMINATION_CONSERVATIVE,/* depth written with depth_greater, so that
                                   a GPU may keep early depth testing */
    SC_TERMINATION_MANUAL,      /* the intersection is skipped behind the
                                   nearest hit so far, and whole hulls behind
                                   it are culled between batches */
    SC_TERMINATION_MANUAL_BOTH, /* also a hit behind it is dropped before
                                   trimming and shading */
    SC_TERMINATION_PEEL,        /* depth peeling of the hulls' entries: each
                                   layer a depth pre-pass, then the
                                   intersection only where the depth test
                                   finds this layer's hull in front (ert4),
                                   while a pixel's hit lies behind a hull
                                   entry; decided on the GPU, no read-back */
    SC_TERMINATION_LISTS        /* candidate lists per pixel for every hull
                                   (ert5): tiles of pixels drawn per program,
                                   each pixel running its hulls nearest box first
                                   until a hit lies in front of the next box;
                                   hulls that hold the eye or cross the near
                                   plane are drawn as hulls (ert0). The
                                   manual modes list only small hulls
                                   (sc_renderer_desc.list_below_px) */
} sc_ray_termination;

/* What the image shows. shade, uv, iters and hull come from the programs;
 * normal, depth and reflect are drawn from the AOVs. */
typedef enum sc_show {
    SC_SHOW_SHADE = 0,         /* shaded colour (default) */
    SC_SHOW_UV,                /* (u, v) as colour */
    SC_SHOW_ITERS,             /* iteration count */
    SC_SHOW_NORMAL,            /* normal as colour */
    SC_SHOW_DEPTH,             /* distance as grey */
    SC_SHOW_HULL,              /* each proxy hull in a colour of its own: the
                                  surface inside it lit, the rest of its face
                                  dim (early termination off; the AOVs hold
                                  only the hits no nearer hull face hides) */
    SC_SHOW_REFLECT            /* reflection lines: stripes at infinity seen
                                  in the exact normal, from the AOVs */
} sc_show;

/* How patches are cut into sub-patches, each bounded by a proxy hull. */
typedef enum sc_hull_split {
    SC_SPLIT_DEFAULT = 0,      /* adaptive */
    SC_SPLIT_ADAPTIVE,         /* until the control mesh is flat within
                                  hull_tolerance */
    SC_SPLIT_UNIFORM           /* hull_divisions × hull_divisions per patch */
} sc_hull_split;

/* The quartic spline a terrain's heights become (seed 004, section IV;
 * docs/splines.md). */
typedef enum sc_terrain_scheme {
    SC_SCHEME_DEFAULT = 0,         /* c2 */
    SC_SCHEME_C0,                  /* interpolates at every quartic domain point */
    SC_SCHEME_C1,                  /* local C1 quasi-interpolant */
    SC_SCHEME_C2,                  /* the quartic C2 box spline */
    SC_SCHEME_LINEAR               /* piecewise linear, degree-elevated */
} sc_terrain_scheme;

/* The order hulls are drawn in each frame (default: hybrid; for terrains
 * the Manhattan sets of seed 004, section VII, unless an order is given). */
typedef enum sc_hull_order {
    SC_HULL_ORDER_DEFAULT = 0,
    SC_HULL_ORDER_FRONT_TO_BACK,   /* strictly by nearest hull depth */
    SC_HULL_ORDER_BY_PROGRAM,      /* grouped by program, front to back in one */
    SC_HULL_ORDER_HYBRID           /* depth buckets, by program in a bucket */
} sc_hull_order;

/* What the zeros of early ray termination, the draw order and batch_hulls
 * mean, chosen by measurement (docs/speed.md, `splinecast bench --ert,
 * --order, --batch`). The renderer and the keys of a scene share the termination,
 * so that `info`, `gen --scene` and `make shaders` name the programs
 * `render` compiles. */
#define SC_DEFAULT_TERMINATION SC_TERMINATION_MANUAL
#define SC_RENDER_DEFAULT_ORDER SC_HULL_ORDER_HYBRID
#define SC_RENDER_DEFAULT_BATCH_HULLS 32
/* What a zero list_below_px means: hulls up to 8 pixels wide and high go
 * through candidate lists (docs/speed.md, "Candidate lists": the 100,352-
 * patch grid 3.1-3.7x faster, the tea set as exact). SC_LISTS_OFF lists
 * none. */
#define SC_RENDER_DEFAULT_LIST_BELOW_PX 8
#define SC_LISTS_OFF (-1)

/* What SC_METHOD_DEFAULT means: the hybrid, which on the tea set and
 * PRO20359-L1 closes Newton's holes and fails no pixel Newton gets right,
 * for 1.10x Newton's frame on the teapot at 1024² (docs/compiler.md,
 * "Methods"). */
#define SC_DEFAULT_METHOD SC_METHOD_HYBRID

/* Where the GL context comes from. */
typedef enum sc_backend {
    SC_BACKEND_DEFAULT = 0,    /* EGL, falling back to OSMesa */
    SC_BACKEND_EGL,            /* EGL; falls back to OSMesa with a warning */
    SC_BACKEND_OSMESA
} sc_backend;

#ifdef __cplusplus
}
#endif

#endif
