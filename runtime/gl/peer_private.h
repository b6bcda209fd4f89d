/* peer_private.h — what the peers' files share: the peer's state
 * (peer.c: the entry points; peer_common.c: targets, programs, frame
 * set-up and read-back; peer_glu.c: GLU's tessellation; peer_tess.c: the
 * tessellation shaders' patches). */
#ifndef SC_PEER_PRIVATE_H
#define SC_PEER_PRIVATE_H

#include "gl_target.h"
#include "peer.h"

struct sc_peer {
    const sc_gl *gl;
    const sc_scene *scene;
    sc_peer_config config;
    sc_peer_stats stats;
    sc_gl_target target;
    sc_camera camera;         /* of the last draw */
    GLuint program;           /* the frame's: one of the two below */
    GLuint aov_program;       /* writes the colour and the AOVs */
    GLuint colour_program;    /* writes the colour alone */
    int frame_aovs;           /* the last frame wrote the AOVs */
    GLuint vertex_array, vertex_buffer, index_buffer;
    GLuint colour_buffer, colour_texture;   /* linear RGB per surface */
    GLuint query;             /* primitives generated (tessellation shaders) */
    size_t data_bytes;        /* on the GPU besides the colours */
    long index_count;         /* GLU: indices; tessellation shaders: patches */
    void *kind;               /* peer_glu.c's or peer_tess.c's state */
};

/* The GLSL every peer's fragment stage runs: the AOVs and the headlight
 * colour of the ray caster's programs (shader_contract.h); and the same
 * without the AOVs, for the frames that write colour and depth alone. */
extern const char *const sc_peer_fragment_glsl;
extern const char *const sc_peer_colour_fragment_glsl;

/* Compiles and links the stages given (NULL: absent); err has the log. */
int sc_peer_link(const sc_gl *gl, const char *const sources[4], GLuint *program, sc_error *err);
/* The peer's two programs from the stages before the fragment stage
 * (vertex, tessellation control and evaluation; NULL: absent), one with
 * each fragment stage above. */
int sc_peer_link_programs(sc_peer *p, const char *const stages[3], sc_error *err);
/* The same for one compute program. */
int sc_peer_link_compute(const sc_gl *gl, const char *source, GLuint *program, sc_error *err);
/* A vertex stage drawing one triangle over the whole viewport (3 vertices,
 * no attributes): the full-screen passes' (peak, deferred shading, depth
 * peeling's resolve and composite). */
extern const char *const sc_fullscreen_vertex_glsl;
/* Frame set-up: the target at the camera's size, cleared as the renderer
 * clears it (aovs 0: a target of the colour and depth alone); the
 * frame's program (with the AOVs or not), its view-projection matrix
 * relative to the eye and the eye set; the colour texture bound. */
int sc_peer_begin(sc_peer *p, const sc_camera *cam, int aovs, float vp[16], sc_error *err);
/* The target's image (RGBA) and AOVs as the last frame left them
 * (sc_peer_read, which first draws a frame without the AOVs again). */
int sc_peer_read_target(sc_peer *p, sc_image *img, sc_aov *aov, sc_error *err);
/* The colours of the scene's surfaces into colour_buffer. */
void sc_peer_upload_colours(sc_peer *p);

/* The kinds' halves of create / update / draw / destroy. */
int sc_peer_glu_create(sc_peer *p, sc_error *err);
int sc_peer_glu_update(sc_peer *p, const sc_camera *cam, sc_error *err);
int sc_peer_glu_draw(sc_peer *p, sc_error *err);
void sc_peer_glu_destroy(sc_peer *p);
int sc_peer_tess_create(sc_peer *p, sc_error *err);
int sc_peer_tess_update(sc_peer *p, sc_error *err);
int sc_peer_tess_draw(sc_peer *p, const sc_camera *cam, const float vp[16], sc_error *err);
void sc_peer_tess_destroy(sc_peer *p);

/* Uniform locations shared by the peers' programs. */
enum {
    PEER_LOC_VP = 0,          /* mat4: view-projection, the eye at the origin */
    PEER_LOC_EYE = 1,         /* vec3: the eye in world space */
    PEER_LOC_FOOTPRINT = 2,   /* float: pixel footprint at distance 1 */
    PEER_LOC_TOLERANCE = 3,   /* float: chordal bound in pixels */
    PEER_LOC_SPLIT = 4,       /* int: sub-patches per patch side */
    PEER_LOC_MAX_LEVEL = 5,   /* float: the driver's highest level */
};

#endif
