/* gl_data.h — a scene's patch data on the GPU, in the layout the generated
 * programs read (gen/gpu_layout.h): control points, knots, one record per
 * GPU patch and the trim blocks of trimmed surfaces, in three buffer
 * textures. A surface drawn by `bez` programs gives one record per Bézier
 * patch, one drawn by `nurbs` programs one record for the whole surface.
 * Surface transforms are baked in, so object space is world space. The data
 * is uploaded once; replacing one surface rewrites only its ranges. */
#ifndef SC_GL_DATA_H
#define SC_GL_DATA_H

#include "gl_loader.h"
#include "gpu_layout.h"
#include "key.h"
#include "nurbs.h"

/* Where one surface's data sits. */
typedef struct sc_gpu_surface {
    scg_patch_kind kind;
    int first_record, record_count;
    int first_point, point_count;      /* texels of SCG_TEX_POINTS */
    int first_knot, knot_count;        /* texels of SCG_TEX_KNOTS */
    int first_trim, trim_count;        /* texels of its trim block, counted
                                          from the end of the records */
} sc_gpu_surface;

typedef struct sc_gpu_data {
    GLuint buffers[SCG_TEXTURE_COUNT];
    GLuint textures[SCG_TEXTURE_COUNT];
    int nsurfaces;
    sc_gpu_surface *surfaces;
    int nrecords, npoints, nknots, ntrim_texels;
    double *centres;                   /* per record, x y z: the point its
                                          data is relative to (a float value,
                                          as in the record) */
    size_t bytes;                      /* GPU bytes of all three textures */
    size_t bytes_uploaded;             /* by the last upload or update */
    float *staged[SCG_TEXTURE_COUNT];  /* built, not yet sent: between
                                          sc_gpu_data_build_from and
                                          sc_gpu_data_send */
} sc_gpu_data;

/* Uploads every surface of the scene; keys[s], the key surface s is drawn
 * with, says how: its patch kind (`bez` or `nurbs`) and, for trimmed keys,
 * the trim degree its trim block is packed for. A `bez` surface s gets one
 * record per patch of patches[s], its world-space Bézier patches
 * (sc_surface_world_patches), in their order: the renderer builds its hulls
 * from the same lists. */
int sc_gpu_data_upload_from(const sc_gl *gl, const sc_scene *scene,
                            const sc_patch_list *patches, const scg_key *keys,
                            sc_gpu_data *data, sc_error *err);
/* The two halves of sc_gpu_data_upload_from, so that a caller can weigh
 * the bytes (data->bytes, with its own) before anything reaches the GPU:
 * build lays the data out in memory (and checks the layout's limits);
 * send uploads it and frees the staged copy. A GL_OUT_OF_MEMORY names
 * `needed`, the bytes of GPU data of the whole scene (sc_gl_fail_memory);
 * on any failure the data is freed. */
int sc_gpu_data_build_from(const sc_gl *gl, const sc_scene *scene,
                           const sc_patch_list *patches, const scg_key *keys,
                           sc_gpu_data *data, sc_error *err);
int sc_gpu_data_send(const sc_gl *gl, sc_gpu_data *data, size_t needed, sc_error *err);
/* After surface s of the scene changed (patches[s] made again from it):
 * rewrites its ranges alone when its data keeps its size (same degrees,
 * counts, kind and trim pieces), else uploads all; *moved (when not NULL)
 * is then 1: the records of other surfaces may have new numbers. */
int sc_gpu_data_update_surface_from(const sc_gl *gl, sc_gpu_data *data, const sc_scene *scene,
                                    const sc_patch_list *patches, int surface,
                                    const scg_key *keys, int *moved, sc_error *err);
/* The same, decomposing the scene's surfaces themselves. */
int sc_gpu_data_upload(const sc_gl *gl, const sc_scene *scene, const scg_key *keys,
                       sc_gpu_data *data, sc_error *err);
int sc_gpu_data_update_surface(const sc_gl *gl, sc_gpu_data *data, const sc_scene *scene,
                               int surface, const scg_key *keys, int *moved, sc_error *err);
/* Binds the textures to their units (unit = scg_texture value). */
void sc_gpu_data_bind(const sc_gl *gl, const sc_gpu_data *data);
void sc_gpu_data_free(const sc_gl *gl, sc_gpu_data *data);

/* Record of Bézier patch `patch` (sc_patch_list numbering) of
 * surface s: its own record for `bez` surfaces, the surface's for `nurbs`. */
int sc_gpu_data_record(const sc_gpu_data *data, int surface, int patch);
/* The centre of a record (3 doubles). */
const double *sc_gpu_data_record_centre(const sc_gpu_data *data, int record);

#endif
