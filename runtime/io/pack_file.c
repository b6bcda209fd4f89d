/* pack_file.c — writing and reading pack files (pack_file.h,
 * docs/pack-format.md). Little-endian, as the GPU data is on every machine
 * this runs on (a big-endian host is refused at compile time). */
#include "pack_file.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envelope.h"
#include "io.h"

_Static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "pack files are little-endian");

enum { HEADER_BYTES = 32, ENTRY_BYTES = 24 };

/* Section ids, in file order. */
enum {
    SEC_SCENE = 1, SEC_SURFACES, SEC_POINTS, SEC_KNOTS, SEC_RECORDS, SEC_VERTICES,
    SEC_INDICES, SEC_HULLS, SEC_COUNT = SEC_HULLS
};
enum { SCENE_BYTES = 96, SURFACE_BYTES = SC_PACK_KEY_BYTES + 16, HULL_BYTES = 72 };

static const char *const section_names[SEC_COUNT + 1] = {
    "", "scene", "surfaces", "points", "knots", "records", "vertices", "indices", "hulls"};
static const uint32_t element_bytes[SEC_COUNT + 1] = {
    0, SCENE_BYTES, SURFACE_BYTES, 16, 4, 16, SC_PACK_VERTEX_BYTES, 4, HULL_BYTES};

static uint64_t fnv1a(const unsigned char *p, size_t n)
{
    uint64_t h = 14695981039346656037u;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 1099511628211u;
    return h;
}

static void put32(unsigned char *p, uint32_t v) { memcpy(p, &v, 4); }
static void put64(unsigned char *p, uint64_t v) { memcpy(p, &v, 8); }
static uint32_t get32(const unsigned char *p) { uint32_t v; memcpy(&v, p, 4); return v; }
static uint64_t get64(const unsigned char *p) { uint64_t v; memcpy(&v, p, 8); return v; }

static size_t align8(size_t n) { return (n + 7) & ~(size_t)7; }

/* The SCENE section's one element. */
static void put_scene(unsigned char *p, const sc_pack *k)
{
    memset(p, 0, SCENE_BYTES);
    put32(p, (uint32_t)k->nrecords);
    put32(p + 4, (uint32_t)k->ntrim_texels);
    put32(p + 8, k->view);
    put32(p + 12, k->termination);
    put32(p + 16, SC_PACK_RECORD_TEXELS);
    memcpy(p + 24, k->raster_origin, 24);
    memcpy(p + 48, k->lo, 24);
    memcpy(p + 72, k->hi, 24);
}

int sc_pack_write(const char *path, const sc_pack *k, sc_error *err)
{
    uint64_t counts[SEC_COUNT + 1] = {
        0, 1, (uint64_t)k->nsurfaces, (uint64_t)k->npoints, (uint64_t)k->nknots,
        (uint64_t)k->nrecords * SC_PACK_RECORD_TEXELS + (uint64_t)k->ntrim_texels,
        (uint64_t)k->nvertices, (uint64_t)k->nindices, (uint64_t)k->nhulls};
    size_t offsets[SEC_COUNT + 1], total = HEADER_BYTES + SEC_COUNT * ENTRY_BYTES;
    for (int s = 1; s <= SEC_COUNT; s++) {
        total = align8(total);
        offsets[s] = total;
        total += (size_t)counts[s] * element_bytes[s];
    }
    total = align8(total);
    unsigned char *buf = calloc(total, 1);
    if (!buf)
        return sc_fail(err, path, 0, "out of memory (%zu bytes)", total);
    memcpy(buf, SC_PACK_MAGIC, 8);
    put32(buf + 8, SC_PACK_VERSION);
    put32(buf + 12, SEC_COUNT);
    put64(buf + 16, total);
    for (int s = 1; s <= SEC_COUNT; s++) {
        unsigned char *e = buf + HEADER_BYTES + (s - 1) * ENTRY_BYTES;
        put32(e, (uint32_t)s);
        put32(e + 4, element_bytes[s]);
        put64(e + 8, counts[s]);
        put64(e + 16, offsets[s]);
    }
    put_scene(buf + offsets[SEC_SCENE], k);
    for (int i = 0; i < k->nsurfaces; i++) {
        unsigned char *p = buf + offsets[SEC_SURFACES] + (size_t)i * SURFACE_BYTES;
        memcpy(p, k->keys[i], SC_PACK_KEY_BYTES);
        memcpy(p + SC_PACK_KEY_BYTES, k->colours + 4 * i, 16);
    }
    /* Empty arrays may be NULL, which memcpy must not see even for 0 bytes. */
    const void *arrays[SEC_COUNT + 1] = {
        [SEC_POINTS] = k->points, [SEC_KNOTS] = k->knots, [SEC_RECORDS] = k->records,
        [SEC_VERTICES] = k->vertices, [SEC_INDICES] = k->indices};
    for (int sec = SEC_POINTS; sec <= SEC_INDICES; sec++)
        if (counts[sec])
            memcpy(buf + offsets[sec], arrays[sec], (size_t)counts[sec] * element_bytes[sec]);
    for (int i = 0; i < k->nhulls; i++) {
        unsigned char *p = buf + offsets[SEC_HULLS] + (size_t)i * HULL_BYTES;
        const sc_pack_hull *h = &k->hulls[i];
        int32_t ints[6] = {h->surface, h->patch, h->first_vertex, h->vertex_count,
                           h->first_index, h->index_count};
        memcpy(p, ints, 24);
        memcpy(p + 24, h->lo, 24);
        memcpy(p + 48, h->hi, 24);
    }
    put64(buf + 24, fnv1a(buf + HEADER_BYTES, total - HEADER_BYTES));
    sc_out_file out;
    int status = sc_out_open(&out, path, err);
    if (status == SC_OK) {
        fwrite(buf, 1, total, out.f);
        status = sc_out_commit(&out, err);
    }
    free(buf);
    return status;
}

void sc_pack_free(sc_pack *k)
{
    free(k->keys);
    free(k->colours);
    free(k->points);
    free(k->knots);
    free(k->records);
    free(k->vertices);
    free(k->indices);
    free(k->hulls);
    memset(k, 0, sizeof *k);
}

/* A copy of section s (count elements), or NULL for none or when memory
 * runs out. */
static void *section_copy(const unsigned char *data, uint64_t offset, uint64_t count,
                          uint32_t size)
{
    if (!count)
        return NULL;
    void *p = sc_try_alloc((size_t)count, size);
    if (p)
        memcpy(p, data + offset, (size_t)count * size);
    return p;
}

static int bad(sc_error *err, const char *name, const char *fmt, const char *a, uint64_t x,
               uint64_t y)
{
    char what[256];
    snprintf(what, sizeof what, fmt, a, (unsigned long long)x, (unsigned long long)y);
    return sc_fail(err, name, 0, "%s", what);
}

int sc_pack_parse(const unsigned char *data, size_t size, const char *name, sc_pack *k,
                  sc_error *err)
{
    memset(k, 0, sizeof *k);
    if (size < 8 || memcmp(data, SC_PACK_MAGIC, 8))
        return sc_fail(err, name, 0, "not a splinecast pack (no \"%s\" magic): write one with "
                                     "`splinecast pack`", SC_PACK_MAGIC);
    if (size < HEADER_BYTES)
        return bad(err, name, "%struncated: %llu bytes, the header alone has %llu", "", size,
                   HEADER_BYTES);
    uint32_t version = get32(data + 8), nsections = get32(data + 12);
    uint64_t total = get64(data + 16);
    if (version != SC_PACK_VERSION)
        return bad(err, name, "%spack version %llu; this library reads version %llu (pack the "
                              "scene again with this version's `splinecast pack`)",
                   "", version, SC_PACK_VERSION);
    if (total != size)
        return bad(err, name, total > size ? "%struncated: the header says %llu bytes, the file "
                                             "has %llu"
                                           : "%sthe header says %llu bytes, the file has %llu",
                   "", total, size);
    if (get64(data + 24) != fnv1a(data + HEADER_BYTES, size - HEADER_BYTES))
        return sc_fail(err, name, 0, "checksum mismatch: the file is damaged");
    if (nsections != SEC_COUNT || HEADER_BYTES + (uint64_t)nsections * ENTRY_BYTES > size)
        return bad(err, name, "%s%llu sections, expected %llu", "", nsections, SEC_COUNT);
    uint64_t counts[SEC_COUNT + 1] = {0}, offsets[SEC_COUNT + 1] = {0};
    for (uint32_t i = 0; i < nsections; i++) {
        const unsigned char *e = data + HEADER_BYTES + i * ENTRY_BYTES;
        uint32_t id = get32(e), elem = get32(e + 4);
        uint64_t count = get64(e + 8), offset = get64(e + 16);
        if (id != i + 1 || elem != element_bytes[id])
            return bad(err, name, "%ssection %llu: unexpected id or element size %llu", "",
                       i + 1, elem);
        /* Within the file, without overflow: count ≤ size / elem first. */
        if (offset > size || count > (size - offset) / elem || count > INT32_MAX)
            return bad(err, name, "section %s: %llu elements at offset %llu do not fit in the "
                                  "file",
                       section_names[id], count, offset);
        counts[id] = count;
        offsets[id] = offset;
    }
    const unsigned char *scene = data + offsets[SEC_SCENE];
    if (counts[SEC_SCENE] != 1 || get32(scene + 16) != SC_PACK_RECORD_TEXELS)
        return sc_fail(err, name, 0, "section scene: malformed");
    k->nrecords = (int)get32(scene);
    k->ntrim_texels = (int)get32(scene + 4);
    k->view = get32(scene + 8);
    k->termination = get32(scene + 12);
    memcpy(k->raster_origin, scene + 24, 24);
    memcpy(k->lo, scene + 48, 24);
    memcpy(k->hi, scene + 72, 24);
    if ((uint64_t)k->nrecords * SC_PACK_RECORD_TEXELS + (uint64_t)k->ntrim_texels !=
        counts[SEC_RECORDS])
        return bad(err, name, "%ssection records: %llu texels, the scene section says %llu", "",
                   counts[SEC_RECORDS],
                   (uint64_t)k->nrecords * SC_PACK_RECORD_TEXELS + (uint64_t)k->ntrim_texels);
    k->nsurfaces = (int)counts[SEC_SURFACES];
    k->npoints = (int)counts[SEC_POINTS];
    k->nknots = (int)counts[SEC_KNOTS];
    k->nvertices = (int)counts[SEC_VERTICES];
    k->nindices = (int)counts[SEC_INDICES];
    k->nhulls = (int)counts[SEC_HULLS];
    k->keys = sc_try_alloc((size_t)(k->nsurfaces ? k->nsurfaces : 1), SC_PACK_KEY_BYTES);
    k->colours = sc_try_alloc((size_t)(k->nsurfaces ? k->nsurfaces : 1), 16);
    if (!k->keys || !k->colours) {
        sc_pack_free(k);
        return sc_fail_oom(err, name, 0, (size_t)k->nsurfaces + 1, SC_PACK_KEY_BYTES + 16,
                           "the pack's surfaces");
    }
    for (int i = 0; i < k->nsurfaces; i++) {
        const unsigned char *p = data + offsets[SEC_SURFACES] + (size_t)i * SURFACE_BYTES;
        memcpy(k->keys[i], p, SC_PACK_KEY_BYTES);
        memcpy(k->colours + 4 * i, p + SC_PACK_KEY_BYTES, 16);
        if (!memchr(k->keys[i], 0, SC_PACK_KEY_BYTES)) {
            sc_pack_free(k);
            return bad(err, name, "%ssurface %llu: its key is not terminated%llu", "",
                       (uint64_t)i, 0);
        }
    }
    k->points = section_copy(data, offsets[SEC_POINTS], counts[SEC_POINTS], 16);
    k->knots = section_copy(data, offsets[SEC_KNOTS], counts[SEC_KNOTS], 4);
    k->records = section_copy(data, offsets[SEC_RECORDS], counts[SEC_RECORDS], 16);
    k->vertices = section_copy(data, offsets[SEC_VERTICES], counts[SEC_VERTICES],
                               SC_PACK_VERTEX_BYTES);
    k->indices = section_copy(data, offsets[SEC_INDICES], counts[SEC_INDICES], 4);
    k->hulls = sc_try_alloc((size_t)(k->nhulls ? k->nhulls : 1), sizeof *k->hulls);
    const void *copies[SEC_COUNT + 1] = {NULL, NULL, NULL, k->points, k->knots, k->records,
                                         k->vertices, k->indices, k->hulls};
    for (int sec = SEC_POINTS; sec <= SEC_HULLS; sec++)
        if ((counts[sec] || sec == SEC_HULLS) && !copies[sec]) {
            char what[64];
            snprintf(what, sizeof what, "section %s", section_names[sec]);
            sc_pack_free(k);
            return sc_fail_oom(err, name, 0, (size_t)counts[sec] + (sec == SEC_HULLS),
                               sec == SEC_HULLS ? sizeof(sc_pack_hull) : element_bytes[sec],
                               what);
        }
    for (int i = 0; i < k->nhulls; i++) {
        const unsigned char *p = data + offsets[SEC_HULLS] + (size_t)i * HULL_BYTES;
        sc_pack_hull *h = &k->hulls[i];
        int32_t ints[6];
        memcpy(ints, p, 24);
        *h = (sc_pack_hull){ints[0], ints[1], ints[2], ints[3], ints[4], ints[5], {0}, {0}};
        memcpy(h->lo, p + 24, 24);
        memcpy(h->hi, p + 48, 24);
        /* What the CPU reads through them must lie inside their arrays. */
        if (h->surface < 0 || h->surface >= k->nsurfaces || h->first_index < 0 ||
            h->index_count < 0 || h->index_count % 3 ||
            (int64_t)h->first_index + h->index_count > k->nindices || h->first_vertex < 0 ||
            h->vertex_count < 0 || (int64_t)h->first_vertex + h->vertex_count > k->nvertices) {
            sc_pack_free(k);
            return bad(err, name, "%shull %llu points outside the surfaces, vertices or indices%llu",
                       "", (uint64_t)i, 0);
        }
    }
    for (int i = 0; i < k->nindices; i++)
        if (k->indices[i] >= (uint32_t)k->nvertices) {
            uint64_t bad_index = k->indices[i];
            sc_pack_free(k);
            return bad(err, name, "%sindex %llu is %llu, past the vertices", "", (uint64_t)i,
                       bad_index);
        }
    return SC_OK;
}

int sc_pack_read(const char *path, sc_pack *out, sc_error *err)
{
    char *data;
    size_t size;
    memset(out, 0, sizeof *out);
    if (sc_read_file_max(path, SC_MAX_FILE_BYTES, 1, &data, &size, err) != SC_OK)
        return SC_FAIL;
    int status = sc_pack_parse((const unsigned char *)data, size, path, out, err);
    free(data);
    return status;
}
