/* peer.h — the tessellation peers the ray caster is charted against
 * (docs/chart.md): GLU's NURBS tessellator, whose triangles the GL draws,
 * and GL 4 hardware tessellation of the same Bézier patches. Both draw into
 * the render targets the ray caster writes (colour, surface id, (u, v, t),
 * point, normal, depth), so that one comparison with the CPU reference
 * measures all three. A peer reads the scene's current control points when
 * it is updated, so a surface changed with sc_update_surface is
 * re-tessellated (GLU) or re-uploaded (tessellation shaders) by the next
 * update. */
#ifndef SC_PEER_H
#define SC_PEER_H

#include "aov.h"
#include "camera.h"
#include "gl_loader.h"
#include "image.h"
#include "scene.h"

typedef enum sc_peer_type {
    SC_PEER_TYPE_GLU,        /* GLU_NURBS_TESSELLATOR, chordal tolerance in pixels */
    SC_PEER_TYPE_TESS,       /* tessellation control + evaluation shaders */
} sc_peer_type;

typedef struct sc_peer_config {
    sc_peer_type type;
    double tolerance_px;     /* chordal error bound in pixels (> 0) */
    int aovs_on_demand;      /* 1: frames write the colour and depth alone
                                unless asked for the AOVs (sc_peer_draw's
                                aovs, sc_peer_read) */
} sc_peer_config;

typedef struct sc_peer_stats {
    double tessellate_ms;    /* last update: GLU's tessellation, or the
                                patches' extraction and bounds */
    double upload_ms;        /* last update: GLU: vertices of transformed
                                surfaces to world space; sending the data,
                                to completion */
    double draw_ms;          /* last draw, to completion */
    long vertices;           /* GLU: vertices of the last tessellation */
    long triangles;          /* GLU: uploaded; tessellation shaders: generated
                                by the last draw */
    size_t gpu_bytes;        /* vertex, index, patch and colour data */
    double compile_ms;       /* compiling and linking the peer's program */
    int skipped_surfaces;    /* tessellation shaders: trimmed surfaces, left
                                out (their trims are not applied) */
    int tessellator_errors;  /* GLU: errors its callback reported */
    int subpatches;          /* tessellation shaders: sub-patches per patch
                                side of the last draw (levels above the
                                driver's maximum are split) */
} sc_peer_stats;

typedef struct sc_peer sc_peer;

/* Needs a current context; the scene must outlive the peer. */
int sc_peer_create(const sc_gl *gl, const sc_scene *scene, const sc_peer_config *config,
                   sc_peer **out, sc_error *err);
void sc_peer_destroy(sc_peer *p);
/* From the scene's current control points to data on the GPU: GLU
 * tessellates for the view (its tolerance is in that view's pixels); the
 * tessellation shaders' data does not depend on the view. */
int sc_peer_update(sc_peer *p, const sc_camera *cam, sc_error *err);
/* Draws the data of the last update for cam and waits for it; with the
 * AOVs when aovs is 1 or the config does not ask for them on demand. */
int sc_peer_draw(sc_peer *p, const sc_camera *cam, int aovs, sc_error *err);
/* The last frame's image (RGBA) and AOVs, as sc_renderer_read: a frame
 * drawn without the AOVs is drawn again with them at its camera first. */
int sc_peer_read(sc_peer *p, sc_image *img, sc_aov *aov, sc_error *err);
void sc_peer_stats_get(const sc_peer *p, sc_peer_stats *stats);

#endif
