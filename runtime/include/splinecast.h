/* splinecast.h — the public interface of libsplinecast, the only header a
 * program that links the installed library needs. It ray casts trimmed NURBS
 * surfaces on the GPU with GLSL generated for each variant key.
 *
 * The style is sokol_gfx's: objects are typed handles (small structs holding
 * an id; id 0 is never valid, and a destroyed object's id stays invalid),
 * every object is made from a desc struct in which zero means default,
 * there is one logger, and every call that can fail returns SC_OK or SC_FAIL
 * and fills an sc_error. Public functions read verb first (sc_make_scene,
 * sc_query_frame_info, sc_destroy_renderer).
 *
 * Three uses (docs/api.md shows each):
 *   build-time generation   sc_make_scene → sc_query_scene_keys →
 *                           sc_generate_glsl (validated GLSL, audit figures)
 *   runtime specialization  sc_make_context → sc_make_program (generated,
 *                           validated, compiled and cached on first use)
 *   rendering and accuracy  sc_make_renderer → sc_render → sc_save_png /
 *                           sc_save_aov; sc_render_reference (CPU, double
 *                           precision) → sc_compare_frames
 *   changing a surface      sc_update_surface (renderers of the scene
 *                           rewrite that surface's GPU data alone)
 *   the application's GL    sc_make_context(.get_proc_address) →
 *                           sc_draw_gl (its framebuffer, its matrices,
 *                           depth tested against its own geometry)
 *   build time to run time  sc_save_pack (`splinecast pack`) + `splinecast
 *                           gen` → sc_make_renderer(.pack) on a context
 *                           with .programs_dir and .binary_cache_dir
 *
 * Calls are made from one thread: GL contexts belong to the thread that made
 * them, and the handle pools are not locked. */
#ifndef SPLINECAST_H
#define SPLINECAST_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "splinecast_base.h"
#include "splinecast_options.h"   /* the options' enums: sc_start, sc_show, … */

#ifdef __cplusplus
extern "C" {
#endif

#define SPLINECAST_VERSION "1.0.0"

/* ---- handles ---------------------------------------------------------- */

typedef struct sc_scene_id { uint32_t id; } sc_scene_id;       /* a loaded scene */
typedef struct sc_context_id { uint32_t id; } sc_context_id;   /* an offscreen GL context */
typedef struct sc_program_id { uint32_t id; } sc_program_id;   /* a GL program of one key */
typedef struct sc_renderer_id { uint32_t id; } sc_renderer_id; /* a scene prepared for a context */
typedef struct sc_frame_id { uint32_t id; } sc_frame_id;       /* an image and its AOVs, in memory */

/* Destroys every object still alive and frees the pools; the library can be
 * used again afterwards. */
void sc_shutdown(void);

/* ---- scenes ------------------------------------------------------------ */

/* Zero means default: the embedded 32-patch teapot. */
typedef struct sc_scene_desc {
    const char *path;      /* .bpt, .obj (free-form), .igs/.iges or .stp/.step
                              (docs/step.md), by extension;
                              "teapot": the embedded teapot */
    const char *text;      /* instead of path: the file's bytes in memory */
    size_t size;           /* bytes of text */
    const char *name;      /* with text: names it in messages; its extension
                              picks the reader */
    /* A terrain instead of a scene file (docs/splines.md): triangular
     * quartic patches from a grid of heights, drawn with a `tri` key. */
    const char *heights;   /* a PGM (P2/P5, 8/16-bit) or CSV grid of heights;
                              refused with file:line when malformed */
    int franke;            /* instead of heights: Franke's function at N data
                              points on [0,1]² (144, 576, 2304, …) */
    sc_terrain_scheme scheme;  /* the spline (c2) */
    double spacing;        /* heights: distance between samples (the grid
                              spans 1 along its longer side) */
    double height_scale;   /* heights: factor on the heights (a PGM's gray
                              levels are divided by maxval first) (1) */
} sc_scene_desc;

int sc_make_scene(const sc_scene_desc *desc, sc_scene_id *out, sc_error *err);
/* A renderer that uses the scene keeps its data alive until it is destroyed. */
void sc_destroy_scene(sc_scene_id scene);

typedef struct sc_scene_info {
    int surfaces;
    int rational_surfaces;   /* weights not all equal */
    int trimmed_surfaces;
    int max_degree;          /* highest surface degree in either direction */
    int skipped;             /* entities the reader did not turn into geometry */
    int skipped_kinds;       /* kinds of them: sc_query_scene_skipped's range */
    int dropped_loops;       /* trim loops removed by validation */
    double lo[3], hi[3];     /* world-space bounding box of the control points */
    int terrain_patches;     /* a terrain's triangular patches (0 otherwise);
                                its one surface stands for it */
    int projected_loops;     /* trim loops given only in model space (3D
                                curves), projected into parameter space */
    double projection_dev;   /* the largest distance measured between such
                                a loop on its surface and its 3D curves
                                (object units) */
    int offset_surfaces;     /* offset surfaces, fitted rather than exact */
    double offset_dev;       /* the largest distance measured between such a
                                fit and the true offset (object units) */
} sc_scene_info;

int sc_query_scene_info(sc_scene_id scene, sc_scene_info *info, sc_error *err);

/* One kind of entity the reader skipped, counted (`info`'s `skipped` line). */
typedef struct sc_skipped_info {
    char type[32];           /* e.g. "polygon", "iges-406" */
    int count;
    char reason[96];         /* one word or a few joined by '-' */
} sc_skipped_info;

/* Kind `index` (0 to sc_scene_info.skipped_kinds - 1) of what was skipped. */
int sc_query_scene_skipped(sc_scene_id scene, int index, sc_skipped_info *info,
                           sc_error *err);

/* Writes the scene as Wavefront OBJ free-form surfaces (path must end in
 * .obj; trim loops as curv2, transforms baked in) and a .mtl of its colours
 * beside it (the same name ending in .mtl). Never half-written. */
int sc_save_obj(sc_scene_id scene, const char *path, sc_error *err);

/* "c0", "c1", "c2", "linear" (SC_SCHEME_DEFAULT is c2). */
const char *sc_terrain_scheme_name(sc_terrain_scheme scheme);
int sc_parse_terrain_scheme(const char *name, sc_terrain_scheme *out, sc_error *err);

/* The paper's Table I protocol (docs/splines.md): Franke's function
 * sampled at `points` data sites, the scheme's spline built from them,
 * and the error measured at `sites` uniformly distributed points,
 * relative to the largest |f| among the data. Zero means default. */
typedef struct sc_spline_error_desc {
    sc_terrain_scheme scheme;  /* c2 */
    int points;                /* N, required: 144, 576, 2304, … */
    int sites;                 /* 1000000 */
} sc_spline_error_desc;

typedef struct sc_spline_error_info {
    int points, patches;
    double rel_rms, rel_max;
    char line[160];            /* "splines scheme=S points=N patches=P rel_rms=X rel_max=Y" */
} sc_spline_error_info;

int sc_measure_spline_error(const sc_spline_error_desc *desc, sc_spline_error_info *out,
                            sc_error *err);

/* ---- surfaces --------------------------------------------------------- */

/* One surface's control net. */
typedef struct sc_surface_info {
    char name[64];
    int deg_u, deg_v;
    int nu, nv;                /* control points along u and v */
    int rational;
    int trim_loops;
    int trim_curves;           /* curves over all trim loops */
    double u_min, u_max, v_min, v_max;  /* the parameter domain */
} sc_surface_info;

int sc_query_surface_info(sc_scene_id scene, int surface, sc_surface_info *info,
                          sc_error *err);

/* A surface's trim loops as the trimmed programs read them: cut exactly
 * into v-monotone rational Bézier pieces and packed into the surface's
 * trim block (docs/trimming.md), as a renderer packs them. The same for
 * every trim method: the methods differ in how they walk the block. All
 * zero for an untrimmed surface. */
typedef struct sc_surface_trim_info {
    int degree;                /* highest trim-curve degree: the N of the
                                  surface's trimmed key (clipN, fastN, …) */
    int loops;                 /* loops with pieces */
    int pieces;                /* pieces (horizontal ones, in float, left out) */
    int grid_u, grid_v;        /* the block's grid of cells (powers of two) */
    int entries;               /* entries of the cells' piece lists */
    int texels;                /* RGBA float texels of the block */
    size_t bytes;              /* the block's GPU size: 16 per texel */
} sc_surface_trim_info;

/* Packs the surface's trim loops and reports the block. Fails for trim
 * curves the preparation refuses, as sc_make_renderer would. */
int sc_query_surface_trim(sc_scene_id scene, int surface, sc_surface_trim_info *info,
                          sc_error *err);

/* The control points of a surface, nu × nv of them, u fastest: `points`
 * 3 doubles each (x, y, z: Euclidean, in the surface's own coordinates,
 * before its transform), `weights` 1 each. Either may be NULL. */
int sc_query_surface_points(sc_scene_id scene, int surface, double *points, double *weights,
                            int count, sc_error *err);

/* A surface at one parameter pair, in world space (its transform applied). */
typedef struct sc_surface_point {
    double point[3];
    double du[3], dv[3];       /* first partial derivatives */
    double normal[3];          /* unit; the limit normal at collapsed edges */
    int has_normal;            /* 0 where the surface is degenerate: normal
                                  is then zero */
} sc_surface_point;

/* Evaluates a surface at (u, v), which must lie in its domain
 * (sc_surface_info's u_min … v_max). */
int sc_eval_surface(sc_scene_id scene, int surface, double u, double v, sc_surface_point *out,
                    sc_error *err);

/* New control points for one surface: same degrees, counts, knots and
 * trims. Zero means default: NULL points or weights keep the current
 * ones. `count` must be the surface's nu × nv when either is given. */
typedef struct sc_surface_desc {
    int surface;               /* index in the scene */
    int count;                 /* control points given */
    const double *points;      /* 3 per point, as sc_query_surface_points */
    const double *weights;     /* 1 per point, positive */
} sc_surface_desc;

/* Replaces a surface's control points and updates every renderer drawing
 * the scene: each rebuilds that surface's hulls (with the hull tolerance
 * it was made with; without qhull where the old triangles or a small hull
 * of its own do) and rewrites its patch data alone; the hull vertices of
 * all the surfaces updated since the last frame go with the next frame
 * (or sc_query_renderer_info), each once.
 * Refused, changing nothing, when renderers draw the scene and the new
 * weights would make the surface rational or polynomial (a new variant
 * key: make new renderers). The CPU reference and keys queried afterwards
 * see the new surface. */
int sc_update_surface(sc_scene_id scene, const sc_surface_desc *desc, sc_error *err);

/* ---- variant keys and build-time generation ---------------------------- */

/* A variant key in its canonical text form (docs/variant-key.md), e.g.
 * "bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade". */
#define SC_KEY_SIZE 128
typedef struct sc_key { char text[SC_KEY_SIZE]; } sc_key;

/* Outputs of a generated program (bits). */
enum {
    SC_OUTPUT_SHADE = 1 << 0,  /* shaded colour */
    SC_OUTPUT_AOV = 1 << 1,    /* surface id, (u, v), distance, point, normal */
    SC_OUTPUT_ITERS = 1 << 2,  /* iteration-count view */
    SC_OUTPUT_UV = 1 << 3,     /* (u, v) view */
    SC_OUTPUT_HULL = 1 << 4    /* proxy-hull view */
};

/* The options `splinecast gen` and `info` take. Zero means default. */
typedef struct sc_keys_desc {
    int nurbs_direct;          /* 1: whole NURBS surfaces with de Boor (nurbs
                                  keys) instead of extracted Bézier patches */
    int generic_above;         /* degrees above this use the generic program
                                  with runtime loops (default 9) */
    int ignore_trims;          /* 1: trim loops are ignored (trim0) */
    sc_trim_method trim;
    int trim_iters;            /* clipping iterations per crossing (16) */
    int max_iters;             /* Newton iterations (6) */
    double tolerance_px;       /* Newton tolerance in pixel footprints (0.05) */
    sc_start start;
    sc_ray_termination termination; /* what the programs do for early ray
                                  termination (manual: keys say ert1) */
    unsigned outputs;          /* SC_OUTPUT_* bits (SC_OUTPUT_SHADE |
                                  SC_OUTPUT_AOV) */
    int skip_undrawable;       /* 1: a surface no program can draw (a degree
                                  above SC_MAX_DEGREE) gets no key and a
                                  warning through the logger, instead of
                                  failing the call */
    const char *like;          /* a key whose fields the keys take where
                                  the fields above are zero (`gen --like`):
                                  all but those each surface decides (kind,
                                  degrees, rationality, loop where a degree
                                  needs it, trimmed or not and the trim
                                  degree). So: nurbs or Bezier, dc, bern or
                                  pow, the trim method and cap, method,
                                  start, iterations, tolerance, ertN as it
                                  is and outputs. bern or pow with
                                  nurbs_direct fails, naming the field and
                                  the key */
    sc_method method;          /* intersection method (hybrid; like's), as
                                  sc_renderer_desc.method */
    sc_eval eval;              /* evaluation form of the unrolled Bézier
                                  keys (like's), as sc_renderer_desc.eval */
} sc_keys_desc;

/* The distinct keys the scene needs, sorted. *count is always the number of
 * keys; at most `capacity` are written to keys (which may be NULL). With
 * the default outputs these are the keys of frames that write the AOVs; a
 * renderer's shaded frames (SC_AOVS_ON_DEMAND) draw with the same keys
 * less `aov`: ask again with outputs = SC_OUTPUT_SHADE for those (`gen
 * --scene` writes both). */
int sc_query_scene_keys(sc_scene_id scene, const sc_keys_desc *desc, sc_key *keys,
                        int capacity, int *count, sc_error *err);

/* The key one surface is drawn with; fails for a surface no program can
 * draw, saying why. */
int sc_query_surface_key(sc_scene_id scene, int surface, const sc_keys_desc *desc, sc_key *out,
                         sc_error *err);

/* Parses a key and checks that the compiler can build it. */
int sc_check_key(const char *key, sc_error *err);

/* A key made from another. Zero means "as in like". */
typedef struct sc_key_desc {
    const char *like;          /* NULL: the key of a polynomial, untrimmed
                                  bicubic patch under sc_keys_desc's zeros */
    int deg_u, deg_v;          /* 1 … SC_MAX_DEGREE; the generic program's
                                  keys (loop) become unrolled ones (dc) */
    int rational;              /* 1: rational, 2: polynomial */
    int max_iters;             /* 1 … SC_MAX_ITERS */
    int lists;                 /* 1: the key a renderer's candidate lists
                                  draw like's hulls with (ert5, each
                                  candidate started on its control net;
                                  sc_renderer_desc.list_below_px), which a
                                  programs_dir must hold for them */
} sc_key_desc;

/* Parses like (sc_check_key says whether the result can be built), changes
 * what the desc gives and writes the canonical text: with a zero desc,
 * the canonical form of like. like may be out's own text. */
int sc_make_key(const sc_key_desc *desc, sc_key *out, sc_error *err);

/* Prints the key's IR listing after it is built and after every
 * optimisation pass that changed it (`gen --dump-ir`). */
int sc_dump_ir(const char *key, FILE *out, sc_error *err);

/* Floating-point operations of a key's intersection program, counted from
 * its optimised IR (docs/speed.md: float arithmetic, 1 per lane per op, a
 * multiply-add 2; dot, cross, length their multiplies and adds): the
 * program with each instruction once (total), what one iteration costs
 * (per_iter: the hybrid's loop body over its Newton steps a pass, or what
 * one more unrolled iteration adds; 0 where a generic program's runtime
 * loops hide it) and what a run costs besides (fixed). A pixel that ran i
 * iterations did fixed + i * per_iter. */
typedef struct sc_key_flops {
    double total, per_iter, fixed;
} sc_key_flops;

int sc_count_key_flops(const char *key, sc_key_flops *out, sc_error *err);

/* Figures of one generated stage, as a line of `splinecast audit` shows
 * them (docs/audit.md). */
typedef struct sc_shader_audit {
    long inst;                 /* IR instructions after optimisation (0 for
                                  the vertex stage) */
    long spirv_inst;           /* SPIR-V instructions (glslang) */
    long vec4_regs;            /* estimated peak live registers, vec4 units */
    long tex;                  /* texture fetches */
    long bytes;                /* GLSL size */
    int register_bound;        /* M + 2N for orders M >= N (Pabst et al. 4.2);
                                  0 when the degrees are not fixed */
    char line[256];            /* "KEY - FS: N inst, N spirv-inst, …"; the
                                  vertex stage's is named by its vertex
                                  program: "NAME - VS: …" */
} sc_shader_audit;

/* Zero means default, except the key, which is required. */
typedef struct sc_glsl_desc {
    const char *key;
    int audit;                 /* 1: also translate to SPIR-V and fill the
                                  audits (about half as much time again) */
} sc_glsl_desc;

/* A generated, glslang-validated program. */
typedef struct sc_glsl {
    char key[SC_KEY_SIZE];
    char vertex_name[64];      /* keys that share a vertex program share this */
    char *vertex, *fragment;   /* GLSL 4.50 core, NUL-terminated */
    size_t vertex_size, fragment_size;
    sc_shader_audit vertex_audit, fragment_audit;  /* zero unless desc->audit */
    char *ir_kinds;            /* with desc->audit: "KEY - FS by kind: add 12,
                                  mul 30, …", the optimised IR's
                                  instructions by kind; else NULL */
} sc_glsl;

/* Builds, optimises, emits and validates both stages of a key (no GL
 * needed). A rejected program fails with the key and the offending line. */
int sc_generate_glsl(const sc_glsl_desc *desc, sc_glsl *out, sc_error *err);
void sc_free_glsl(sc_glsl *glsl);

/* A saved audit (the lines of `splinecast audit`) in memory; name names it
 * in messages. */
typedef struct sc_audit_text {
    const char *name;
    const char *text;
    size_t size;
} sc_audit_text;

/* Prints to out what got better and worse per metric from one audit to
 * the other, the shaders added and removed, and totals over the shaders
 * both hold (`splinecast audit --compare`, docs/audit.md). A line that is
 * not an audit line, or a shader audited twice, fails with name:line. */
int sc_compare_audits(const sc_audit_text *before, const sc_audit_text *after, FILE *out,
                      sc_error *err);
/* The same, pairing shaders whose keys are equal once the fields that
 * ignore_fields names (comma-separated: shape, rational, eval, trim, method,
 * start, iters, tol, ert, out) are left out, so that an option change can
 * be compared (`audit --compare --match`); NULL pairs equal keys. Fails,
 * naming them, when two shaders of one audit match the same one. */
int sc_compare_audits_matching(const sc_audit_text *before, const sc_audit_text *after,
                               const char *ignore_fields, FILE *out, sc_error *err);

/* ---- GL contexts and runtime specialization ---------------------------- */

typedef struct sc_context_desc {
    sc_backend backend;
    int debug;                 /* a debug context: more driver messages */
    /* Instead of an offscreen context of the library's own: the
     * application's OpenGL 4.5 core context, current when sc_make_context
     * and every later call naming it are made, its functions looked up
     * through this (eglGetProcAddress, glXGetProcAddressARB,
     * glfwGetProcAddress, …). The library never makes it current or
     * destroys it; sc_draw_gl draws into its bound framebuffer. backend and
     * debug are then ignored. */
    void (*(*get_proc_address)(const char *name))(void);
    /* Where the context's programs come from (docs/api.md, "Build time to
     * run time"). programs_dir: a folder `splinecast gen` wrote; a key is
     * read from it by its manifest (no generation, no glslang), and a key
     * the manifest lacks, or a file that is not what the manifest says,
     * fails naming the key, unless generate_missing is 1 (then generated
     * as without a folder). binary_cache_dir: linked programs are kept
     * there (glGetProgramBinary), keyed by key, driver and GLSL, so that a
     * second start loads instead of compiling; nothing is kept when the
     * driver has no binary formats. NULL: none. */
    const char *programs_dir;
    int generate_missing;
    const char *binary_cache_dir;
} sc_context_desc;

/* An offscreen OpenGL 4.5 core context (EGL or OSMesa, loaded at run time),
 * or the application's (get_proc_address). */
int sc_make_context(const sc_context_desc *desc, sc_context_id *out, sc_error *err);
/* Also destroys the context's programs and renderers. */
void sc_destroy_context(sc_context_id ctx);

typedef struct sc_context_info {
    sc_backend backend;        /* the one actually used: EGL or OSMESA
                                  (DEFAULT for an application's context) */
    char description[256];     /* "egl-surfaceless llvmpipe (…)" etc. */
} sc_context_info;

int sc_query_context_info(sc_context_id ctx, sc_context_info *info, sc_error *err);

/* The GL program of a key: from the context's cache, or generated,
 * validated, compiled and linked now. Asking again for the same key returns
 * the same handle; the context's renderers draw with the programs of that
 * cache, so a renderer's keys (sc_query_renderer_keys) give the programs it
 * draws with. Programs live as long as their context. */
int sc_make_program(sc_context_id ctx, const char *key, sc_program_id *out, sc_error *err);

typedef struct sc_program_info {
    char key[SC_KEY_SIZE];
    uint32_t gl_program;       /* the GL program name, for drawing with it */
    double generate_ms;        /* building, emitting and validating the GLSL */
    double compile_ms;         /* compiling and linking in the driver */
} sc_program_info;

int sc_query_program_info(sc_program_id program, sc_program_info *info, sc_error *err);

/* ---- rendering -------------------------------------------------------- */

/* sc_renderer_desc.aovs. SC_AOVS_ON_DEMAND: the shaded view's frames of
 * sc_draw and sc_draw_gl write the colour and depth alone, with programs
 * compiled without the AOVs (manual early termination then takes its
 * nearest distances from the depth buffer); sc_render draws with them, and
 * sc_read_frame and sc_pick after a frame without them draw it again at
 * its camera with them, once (that frame is then the last). The AOVs'
 * programs are compiled when first needed. The other views and deferred
 * shading are drawn from the AOVs: every frame writes them.
 * SC_AOVS_ALWAYS: every frame writes them (for measuring what they cost). */
typedef enum sc_aovs {
    SC_AOVS_ON_DEMAND = 0,
    SC_AOVS_ALWAYS = 1,
} sc_aovs;

/* Zero means default in every field (the defaults of `splinecast render`). */
typedef struct sc_renderer_desc {
    sc_hull_split hull_split;
    int hull_divisions;        /* uniform: sub-patches per side (2) */
    double hull_tolerance;     /* adaptive: flatness as a fraction of the
                                  scene's bounding-box diagonal (0.003) */
    int hull_max_depth;        /* adaptive: most splits of one patch (8) */
    sc_start start;            /* Newton start (cpmap) */
    int max_iters;             /* Newton iterations (6) */
    double tolerance_px;       /* Newton tolerance in pixel footprints (0.05) */
    sc_show show;
    int generic;               /* 1: the generic program for every surface */
    int unroll_max_degree;     /* highest degree drawn unrolled (9) */
    sc_trim_method trim;
    int trim_iters;            /* clipping iterations per crossing (16) */
    sc_ray_termination termination;
    sc_hull_order order;
    int batch_hulls;           /* hulls per batch in the manual termination
                                  modes (a batch sees the hits of those
                                  before it), the first of depth peeling's
                                  doubling batches, and per hybrid bucket
                                  (32) */
    int list_below_px;         /* in the manual termination modes, hulls
                                  whose projection is at most this many
                                  pixels wide and high are drawn through
                                  candidate lists per pixel (ert5
                                  programs) instead of as hulls (8;
                                  SC_LISTS_OFF: none; docs/speed.md,
                                  "Candidate lists") */
    size_t gpu_memory_budget;  /* most bytes of GPU data (patch data, hulls,
                                  colours: sc_renderer_info.gpu_bytes) the
                                  renderer may upload; a scene that needs
                                  more is refused before anything is sent,
                                  with the message a real GL_OUT_OF_MEMORY
                                  gives ("out of GPU memory: the scene needs
                                  N bytes of GPU data (…)"). 0: no budget */
    int own_programs;          /* 1: programs of the renderer's own, compiled
                                  for it and not shared with the context's
                                  cache, so that compile_ms measures
                                  compiling them (benchmarks) */
    sc_method method;          /* intersection method (hybrid). With subdiv,
                                  max_iters is the depth of the subdivision
                                  stack (24), with bclip the number of
                                  clipping steps (32); both ignore start */
    sc_eval eval;              /* how the unrolled Bézier programs evaluate
                                  the patch in their iteration (pow up to
                                  degree 4, dc above) */
    /* Instead of a scene: a file `splinecast pack` (sc_save_pack) wrote,
     * drawn as it is (docs/pack-format.md); the scene handle is then the
     * zero handle. The pack fixed keys, hulls and view when it was
     * written: the fields above that decide them must be zero; order,
     * batch_hulls, gpu_memory_budget and own_programs apply. */
    const char *pack;
    /* An accuracy target (docs/accuracy.md). accuracy_px > 0: every
     * surface gets the fewest iterations and the largest tolerance (and
     * adaptive hulls no coarser than the defaults') that keep its position
     * error within
     * accuracy_px pixel footprints (0.001 … 100) — and its normal error
     * within accuracy_normal_deg degrees (0 … 90; 0: no normal bound) —
     * in the view *accuracy_view (NULL: the scene's default view at 512²);
     * they replace hull_split, hull_tolerance, max_iters and tolerance_px.
     * 0: off. sc_query_renderer_surface says what was chosen. */
    double accuracy_px;
    double accuracy_normal_deg;
    const struct sc_camera_desc *accuracy_view;
    /* Terrains: 1 shades in a full-screen pass after the intersection, from
     * the AOVs and the patches' exact normals (deferred shading, seed 004);
     * the intersection programs then write the AOVs only. Shaded view. */
    int deferred;
    /* 1: each frame's hull draws (the intersection pass) are timed, from a
     * glFinish before them to one after, and by a GL_TIME_ELAPSED query
     * (sc_renderer_info.intersect_ms); the two waits cost a stall, so this
     * is for benchmarks (`bench --peak`). */
    int time_intersection;
    /* Which frames write the AOVs (surface ids, uv, distance, point,
     * normal, iterations) besides the colour and depth. */
    sc_aovs aovs;
    /* CPU threads of each frame's pass over the hulls (the view test and
     * the candidate lists' outlines), which grows with the patch count:
     * 0, one per online processor; at most 8 are used, and one per 1,024
     * hulls. Results do not depend on it. */
    int threads;
} sc_renderer_desc;

/* Writes what a renderer made with desc would upload for the scene —
 * patch records and trim blocks, hull vertices and indices, each surface's
 * key and colour — to a pack file (docs/pack-format.md; never
 * half-written), without a GL context. sc_make_renderer with
 * sc_renderer_desc.pack draws it; the programs it needs are the keys of
 * sc_query_scene_keys with the same options. Terrains are refused. */
int sc_save_pack(sc_scene_id scene, const sc_renderer_desc *desc, const char *path,
                 sc_error *err);

/* Prepares everything that does not depend on the view: hulls, GPU data
 * and one program per distinct key, taken from the context's program cache
 * (built there on first use). */
int sc_make_renderer(sc_context_id ctx, sc_scene_id scene, const sc_renderer_desc *desc,
                     sc_renderer_id *out, sc_error *err);
void sc_destroy_renderer(sc_renderer_id renderer);

/* The distinct keys the renderer draws with, in order of first use; *count
 * and capacity as in sc_query_scene_keys. */
int sc_query_renderer_keys(sc_renderer_id renderer, sc_key *keys, int capacity, int *count,
                           sc_error *err);

typedef struct sc_renderer_info {
    int programs;              /* distinct keys */
    int hulls, triangles;
    size_t gpu_bytes;          /* patch data, hulls, colours */
    size_t uploaded_bytes;     /* sent to the GPU by sc_make_renderer, or for
                                  the sc_update_surface calls since the
                                  frame (or this query) before the last:
                                  patch data, sent by each call, and hull
                                  vertices, sent once for all of them by
                                  the next frame or by this query (and
                                  colours when made) */
    double compile_ms;         /* generating, validating, compiling, linking */
    /* Of the last frame: */
    int draw_calls;
    int program_switches;      /* glUseProgram calls */
    int culled_hulls;          /* hulls not drawn: behind the hits so far at
                                  every pixel they cover (manual modes) */
    int readbacks;             /* reads of the nearest distances so far
                                  (manual modes) */
    double lo[3], hi[3];       /* the box the default view frames: control
                                  points of untrimmed surfaces, the kept
                                  region of trimmed ones (a packed
                                  renderer's: the packed scene's) */
    long long intersections;   /* of the last frame: fragment programs that
                                  ran the intersection, counted on the GPU
                                  by the programs that write the AOVs; -1
                                  after a frame without them (sc_draw's and
                                  sc_draw_gl's under SC_AOVS_ON_DEMAND:
                                  sc_read_frame draws it again with them) */
    /* Of the last frame, with sc_renderer_desc.time_intersection (-1
     * otherwise): the hull draws that run the intersection programs, timed
     * from a glFinish before them to one after, and by a GL_TIME_ELAPSED
     * query around them (on llvmpipe the query covers the binning of the
     * draws, not their rasterization, so it reads low). */
    double intersect_ms, intersect_query_ms;
    size_t uploaded_total_bytes; /* sent to the GPU since sc_make_renderer,
                                  making included: the difference over a
                                  frame is what following the frame's
                                  sc_update_surface calls cost */
    long long qhull_hulls;     /* sub-patches whose hull came from qhull:
                                  every one sc_make_renderer made, and
                                  those of the sc_update_surface calls
                                  since that neither kept their triangles
                                  nor got a small incremental hull (flat
                                  pieces) */
    int peel_layers;           /* of the last frame, depth peeling
                                  (SC_TERMINATION_PEEL): the layers that
                                  found hull entries in front of a pixel's
                                  best hit; 0 when it did not peel */
} sc_renderer_info;

int sc_query_renderer_info(sc_renderer_id renderer, sc_renderer_info *info, sc_error *err);

/* The machine's peak: a full-screen pass of a fragment program made of
 * `chains` independent dependent chains of `length` vec4 multiply-adds
 * each (independent, so that the pipeline stays full), drawn `frames`
 * times after a warm-up draw. Zero means default: 1024×1024, 2 chains of
 * 256 (on llvmpipe, more chains run out of registers and longer ones out
 * of instruction cache: docs/speed.md), 5 frames. FLOPs: pixels × chains
 * × length × 4 lanes × 2. */
typedef struct sc_peak_desc {
    int width, height;
    int chains, length;
    int frames;
} sc_peak_desc;

typedef struct sc_peak_info {
    double flops;              /* of one frame */
    double gpu_ms;             /* median GL_TIME_ELAPSED of the draw (-1: none) */
    double wall_ms;            /* median of draw + glFinish, timed on the CPU */
    double gflops;             /* flops / wall_ms: llvmpipe's GL_TIME_ELAPSED
                                  covers the binning of the draw, not its
                                  rasterization */
} sc_peak_info;

int sc_measure_peak(sc_context_id ctx, const sc_peak_desc *desc, sc_peak_info *out,
                    sc_error *err);

/* How one surface is drawn: its key, its hulls and the settings behind
 * them, chosen by an accuracy target or given in the desc. */
typedef struct sc_renderer_surface_info {
    sc_key key;
    int hulls;                 /* sub-patches (proxy hulls) */
    double hull_tolerance;     /* adaptive flatness, a fraction of the
                                  scene's size (0 for uniform hulls) */
    int max_iters;             /* the key's iterations */
    double tolerance_px;       /* the key's tolerance */
    /* With an accuracy target only (0 otherwise): */
    double footprint;          /* world size of a pixel at the surface's
                                  nearest distance to the eye */
    double radius;             /* smallest radius of curvature found
                                  (HUGE_VAL: flat) */
} sc_renderer_surface_info;

int sc_query_renderer_surface(sc_renderer_id renderer, int surface,
                              sc_renderer_surface_info *info, sc_error *err);

/* A pinhole view. Zero means default: eye and target both zero frame the
 * scene (the control points of untrimmed surfaces, the kept region of
 * trimmed ones), fovy_deg 0 is 30 degrees, width and height 0 are 512.
 * up zero: +z is up unless the view is along z (then +y). */
typedef struct sc_camera_desc {
    double eye[3], target[3];
    double fovy_deg;
    int width, height;
    const char *text;          /* "EX,EY,EZ,TX,TY,TZ,FOVY[,UX,UY,UZ]" instead
                                  of eye, target, fovy_deg (and up) */
    double up[3];              /* the up vector (where the view runs along
                                  it, the zero rule) */
    double from[3];            /* with the default framing: the direction
                                  from the target towards the eye (zero: a
                                  3/4 view from the front left and above,
                                  "above" along up) */
} sc_camera_desc;

/* Checks a view without a scene: its text parses, its size is in range,
 * and eye and target, when given, differ. */
int sc_check_camera(const sc_camera_desc *camera, sc_error *err);

/* Draws one frame with its AOVs, waits for it and reads it back: the image
 * of the view and its AOVs, with iteration counts. */
int sc_render(sc_renderer_id renderer, const sc_camera_desc *camera, sc_frame_id *out,
              sc_error *err);
/* Draws one frame and waits for it, reading nothing back: what a frame
 * costs, for timing. */
int sc_draw(sc_renderer_id renderer, const sc_camera_desc *camera, sc_error *err);
/* The image and AOVs of the renderer's last frame (sc_draw first; a frame
 * drawn without AOVs is drawn again with them: sc_renderer_desc.aovs). */
int sc_read_frame(sc_renderer_id renderer, sc_frame_id *out, sc_error *err);

/* The application's view of one frame (sc_draw_gl): OpenGL's
 * column-major matrices, as glUniformMatrix4fv takes them. */
typedef struct sc_gl_draw_desc {
    float view[16];            /* world to eye (gluLookAt's); required */
    float projection[16];      /* a perspective projection (gluPerspective's,
                                  glFrustum's); required */
} sc_gl_draw_desc;

/* Draws the renderer's scene into the framebuffer bound in the
 * application's context (sc_context_desc.get_proc_address), in its
 * viewport, with its view and projection, writing each hit's depth into its
 * depth buffer through the ordinary depth test (GL_LESS), so that the
 * surfaces and the application's own geometry hide each other where they
 * should, whichever is drawn first. Neither clears nor waits. The GL state
 * it changes is restored (docs/api.md lists it). The colour is linear RGB:
 * enable GL_FRAMEBUFFER_SRGB on an sRGB framebuffer, as for your own lit
 * geometry. Needs glClipControl's and glDepthRange's defaults. */
int sc_draw_gl(sc_renderer_id renderer, const sc_gl_draw_desc *desc, sc_error *err);

typedef struct sc_reference_desc {
    int threads;               /* 0: one per online core */
    /* Called with the fraction of rows done (about every 10 %), from one
     * thread at a time; NULL for silence. */
    void (*progress)(double fraction, void *user);
    void *progress_user;
} sc_reference_desc;

/* The CPU reference of the same view: double-precision object-space
 * subdivision with exact trimming, independent of starting values. */
int sc_render_reference(sc_scene_id scene, const sc_camera_desc *camera,
                        const sc_reference_desc *desc, sc_frame_id *out, sc_error *err);

/* ---- frames ----------------------------------------------------------- */

/* Reads an AOV file (docs/aov-format.md); its colour is a grey shading. */
int sc_load_frame(const char *aov_path, sc_frame_id *out, sc_error *err);
void sc_destroy_frame(sc_frame_id frame);

/* How the CPU reference went. */
typedef struct sc_reference_stats {
    double seconds;            /* wall time of the ray casting */
    long rays, hits;
    long subdivisions;         /* sub-patch splits over all rays */
    long over_budget;          /* rays whose search was cut short: normally 0 */
    int threads;
} sc_reference_stats;

/* Pointers into the frame, valid until it is destroyed. Per pixel, row 0 at
 * the top, index j * width + i. */
typedef struct sc_frame_info {
    int width, height;
    double eye[3], target[3], fovy_deg;
    const uint8_t *rgba;       /* 4 per pixel, sRGB */
    const int32_t *surface;    /* surface index, -1 for a miss */
    const float *uv;           /* 2 per pixel, in the surface's domain */
    const float *t;            /* distance from the eye */
    const float *point;        /* 3 per pixel, world space */
    const float *normal;       /* 3 per pixel, unit, facing the viewer */
    const float *iters;        /* iterations; NULL for reference frames */
    double render_ms;          /* drawing and reading back, or the reference */
    char camera[320];          /* "EX,EY,EZ,TX,TY,TZ,FOVY[,UX,UY,UZ]" with 17 digits:
                                  parses back to the same view */
    sc_reference_stats reference;  /* zero unless from sc_render_reference */
} sc_frame_info;

int sc_query_frame_info(sc_frame_id frame, sc_frame_info *info, sc_error *err);

/* Written to a temporary file and renamed: never half-written. The PNG of
 * a GPU frame is RGBA; that of a reference or loaded frame, which covers
 * every pixel, is RGB. */
int sc_save_png(sc_frame_id frame, const char *path, sc_error *err);
int sc_save_aov(sc_frame_id frame, const char *path, sc_error *err);

/* Accuracy of `test` against `reference` (docs/reference.md): pixel counts
 * and the percentages and errors of `splinecast diff`. */
typedef struct sc_comparison {
    long reference_hits, test_hits, both_hit;
    long holes, false_hits, off;
    double coverage_pct;       /* (holes + false hits) / reference hits × 100
                                  (infinite when only the test hits) */
    double fail_pct;           /* (holes + false hits + off) / reference hits × 100 */
    double pos_median_px, pos_max_px;
    double normal_mean_deg, normal_max_deg;
    double pos_p99_px, normal_p99_deg;  /* 99th percentiles over both_hit */
    int has_iters;
    double iters_mean, iters_max;
    char line[384];            /* "accuracy coverage_pct=… fail_pct=… …" */
} sc_comparison;

/* Fails when the two frames differ in size or camera. */
int sc_compare_frames(sc_frame_id reference, sc_frame_id test, sc_comparison *out,
                      sc_error *err);

/* ---- picking (runtime/api_pick.c, docs/api.md) ------------------------ */

typedef struct sc_pick_result {
    int hit;                   /* 0: nothing under the point */
    int surface;               /* 0-based index, as sc_query_surface_info and
                                  sc_eval_surface take it; -1 for a miss */
    double u, v;               /* in the surface's own knot range:
                                  sc_eval_surface(u, v) gives point */
    double point[3];           /* world space */
    double normal[3];          /* unit, world space, facing the viewer */
    double t;                  /* distance from the eye along the unit ray */
    /* How it was found: */
    int gpu_surface;           /* the frame's surface id at the pixel (-1) */
    double gpu_u, gpu_v;       /* the frame's float (u, v) there */
    int newton_iters;          /* double-precision Newton steps from it */
    int by_reference;          /* 1: the CPU reference traced the ray
                                  (Newton left the surface's kept region:
                                  a silhouette, a trim edge) */
} sc_pick_result;

/* What lies under image point (x, y) of the renderer's last frame
 * (sc_draw first): x a column and y a row from the top left, in pixels,
 * pixel centres at +0.5. The frame's AOVs give the surface and a float
 * (u, v); Newton's method on the ray against the surface's NURBS refines
 * them in double precision. A pixel the frame did not hit is a miss.
 * Fails for a point outside the frame. */
int sc_pick(sc_renderer_id renderer, double x, double y, sc_pick_result *out, sc_error *err);

/* ---- tessellation peers ------------------------------------------------ */

/* What a program would draw instead of ray casting, measured the same way
 * (docs/chart.md): GLU's NURBS tessellator, its triangles drawn by the
 * GL, or GL 4 hardware tessellation of the scene's Bézier patches. Both
 * write the frame a renderer writes (colour, surface id, distance, point,
 * normal), so sc_compare_frames measures them against the reference. */
typedef struct sc_peer_id { uint32_t id; } sc_peer_id;

typedef enum sc_peer_kind {
    SC_PEER_GLU,               /* GLU_NURBS_TESSELLATOR, GLU_PARAMETRIC_ERROR */
    SC_PEER_TESS_SHADER,       /* tessellation control and evaluation shaders;
                                  trimmed surfaces are left out */
} sc_peer_kind;

/* Zero means default. */
typedef struct sc_peer_desc {
    sc_peer_kind kind;         /* GLU */
    double tolerance_px;       /* chordal error bound in pixels of the view
                                  (0.1) */
    sc_aovs aovs;              /* as sc_renderer_desc.aovs: by default a
                                  frame writes the colour and depth alone,
                                  and sc_read_peer_frame draws it again with
                                  the AOVs */
} sc_peer_desc;

int sc_make_peer(sc_context_id ctx, sc_scene_id scene, const sc_peer_desc *desc,
                 sc_peer_id *out, sc_error *err);
void sc_destroy_peer(sc_peer_id peer);
/* From the scene's current control points (after sc_update_surface, the
 * new ones) to data on the GPU: GLU tessellates for this view, the
 * tessellation shaders' patches are extracted and uploaded. */
int sc_update_peer(sc_peer_id peer, const sc_camera_desc *camera, sc_error *err);
/* Draws the data of the last update and waits for it. */
int sc_draw_peer(sc_peer_id peer, const sc_camera_desc *camera, sc_error *err);
/* The image and AOVs of the peer's last frame (no iteration counts); a
 * frame drawn without the AOVs is drawn again with them first. */
int sc_read_peer_frame(sc_peer_id peer, sc_frame_id *out, sc_error *err);

typedef struct sc_peer_info {
    double tessellate_ms;      /* last update: GLU's tessellation, or the
                                  Bézier extraction and error bounds */
    double upload_ms;          /* last update: sending the data */
    double draw_ms;            /* last draw, to completion */
    long vertices;             /* GLU: of the last tessellation */
    long triangles;            /* GLU: uploaded; tessellation shaders:
                                  generated by the last draw */
    size_t gpu_bytes;
    double compile_ms;         /* the peer's GL program */
    int skipped_surfaces;      /* tessellation shaders: trimmed surfaces */
    int tessellator_errors;    /* GLU: errors it reported in the last update */
} sc_peer_info;

int sc_query_peer_info(sc_peer_id peer, sc_peer_info *info, sc_error *err);

#ifdef __cplusplus
}
#endif

#endif
