/* pack_file.h — a scene's GPU data in one file (docs/pack-format.md):
 * what a renderer uploads — the patch records and trim blocks, the hull
 * vertices and indices, each surface's variant key and colour — written at
 * build time by `splinecast pack` and read at run time without the scene,
 * its readers or the preparation. The format has a magic, a version and a
 * checksum; reading it is bounded like every reader (docs/limits.md): the
 * file is read whole under SC_MAX_FILE_BYTES and every array is a section
 * of it, so nothing is allocated beyond the file's own size. */
#ifndef SC_PACK_FILE_H
#define SC_PACK_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "sc_base.h"

#define SC_PACK_MAGIC "SPLCPACK"
enum {
    SC_PACK_VERSION = 1,
    SC_PACK_KEY_BYTES = 128,     /* a key's text, NUL-padded (SC_KEY_SIZE) */
    SC_PACK_VERTEX_BYTES = 52,   /* one hull vertex as the GPU reads it */
    SC_PACK_RECORD_TEXELS = 4,   /* texels per patch record (gpu_layout.h) */
};

typedef struct sc_pack_hull {
    int32_t surface, patch;
    int32_t first_vertex, vertex_count;
    int32_t first_index, index_count;
    double lo[3], hi[3];         /* the hull's bounding box */
} sc_pack_hull;

typedef struct sc_pack {
    int nsurfaces;
    char (*keys)[SC_PACK_KEY_BYTES];
    float *colours;              /* 4 per surface: linear RGB, 1 */
    int npoints, nknots;         /* texels of sc_points (4 floats), sc_knots (1) */
    int nrecords, ntrim_texels;  /* sc_records: the records, then the trim blocks */
    float *points, *knots, *records;
    int nvertices;
    unsigned char *vertices;     /* SC_PACK_VERTEX_BYTES each */
    int nindices;
    uint32_t *indices;
    int nhulls;
    sc_pack_hull *hulls;
    uint32_t view;               /* the sc_show the keys' outputs are for */
    uint32_t termination;        /* the sc_ray_termination they were made with */
    double raster_origin[3];     /* what vertices' raster positions are relative to */
    double lo[3], hi[3];         /* the scene's box (the default view frames it) */
} sc_pack;

/* Written to a temporary file and renamed: never half-written. */
int sc_pack_write(const char *path, const sc_pack *pack, sc_error *err);
/* A bad magic, another version, a wrong checksum, a truncated file or a
 * section that does not fit fail with the file's name and what is wrong;
 * indices and hulls that point outside their arrays too. */
int sc_pack_read(const char *path, sc_pack *out, sc_error *err);
int sc_pack_parse(const unsigned char *data, size_t size, const char *name, sc_pack *out,
                  sc_error *err);
void sc_pack_free(sc_pack *pack);

#endif
