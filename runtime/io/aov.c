/* aov.c — the AOV file (aov.h, docs/aov-format.md): one text header line
 * with magic, size, camera and channel list, then each channel as a plane of
 * little-endian 32-bit values. The camera is stored with %.17g so that a
 * file compares equal to the camera it was rendered with. */
#include "aov.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "envelope.h"

#define AOV_MAGIC "SCAOV1"
#define AOV_MAX_HEADER 2048

/* A channel as the file knows it: name, value kind, components per pixel,
 * and where its data lives in an sc_aov. */
typedef struct channel_desc {
    const char *name;
    int is_int;
    int components;
} channel_desc;

static const channel_desc known_channels[] = {
    {"surface", 1, 1}, {"uv", 0, 2}, {"t", 0, 1}, {"point", 0, 3}, {"normal", 0, 3}, {"iters", 0, 1},
};
enum { CH_SURFACE, CH_UV, CH_T, CH_POINT, CH_NORMAL, CH_ITERS, CH_COUNT };

static void *channel_data(const sc_aov *aov, int ch)
{
    switch (ch) {
    case CH_SURFACE: return aov->surface;
    case CH_UV: return aov->uv;
    case CH_T: return aov->t;
    case CH_POINT: return aov->point;
    case CH_NORMAL: return aov->normal;
    default: return aov->iters;
    }
}

/* The channels for a cam->width × cam->height image, every pixel a miss;
 * SC_FAIL when memory runs out (with the size taken from a file, that is an
 * error to report, not a reason to abort). */
static int aov_try_alloc(sc_aov *aov, const sc_camera *cam, int has_iters)
{
    memset(aov, 0, sizeof *aov);
    aov->width = cam->width;
    aov->height = cam->height;
    aov->camera = *cam;
    aov->has_iters = has_iters;
    size_t n = (size_t)cam->width * (size_t)cam->height;
    aov->surface = sc_try_alloc(n, sizeof(int32_t));
    aov->uv = sc_try_alloc(n * 2, sizeof(float));
    aov->t = sc_try_alloc(n, sizeof(float));
    aov->point = sc_try_alloc(n * 3, sizeof(float));
    aov->normal = sc_try_alloc(n * 3, sizeof(float));
    aov->iters = has_iters ? sc_try_alloc(n, sizeof(float)) : NULL;
    if (!aov->surface || !aov->uv || !aov->t || !aov->point || !aov->normal ||
        (has_iters && !aov->iters)) {
        sc_aov_free(aov);
        return SC_FAIL;
    }
    for (size_t i = 0; i < n; i++)
        aov->surface[i] = -1;
    return SC_OK;
}

void sc_aov_alloc(sc_aov *aov, const sc_camera *cam, int has_iters)
{
    if (aov_try_alloc(aov, cam, has_iters)) {
        sc_log(SC_LOG_ERROR, "out of memory (AOV channels of %d x %d pixels)", cam->width,
               cam->height);
        abort();
    }
}

void sc_aov_free(sc_aov *aov)
{
    free(aov->surface);
    free(aov->uv);
    free(aov->t);
    free(aov->point);
    free(aov->normal);
    free(aov->iters);
    memset(aov, 0, sizeof *aov);
}

/* 32-bit words to and from little-endian bytes, whatever the host order. */
static void put_le32(unsigned char *out, const void *src, size_t count)
{
    const unsigned char *in = src;
    for (size_t i = 0; i < count; i++) {
        uint32_t w;
        memcpy(&w, in + 4 * i, 4);
        out[4 * i + 0] = (unsigned char)(w & 0xff);
        out[4 * i + 1] = (unsigned char)((w >> 8) & 0xff);
        out[4 * i + 2] = (unsigned char)((w >> 16) & 0xff);
        out[4 * i + 3] = (unsigned char)(w >> 24);
    }
}

static void get_le32(void *dst, const unsigned char *in, size_t count)
{
    unsigned char *out = dst;
    for (size_t i = 0; i < count; i++) {
        uint32_t w = (uint32_t)in[4 * i] | (uint32_t)in[4 * i + 1] << 8 |
                     (uint32_t)in[4 * i + 2] << 16 | (uint32_t)in[4 * i + 3] << 24;
        memcpy(out + 4 * i, &w, 4);
    }
}

int sc_aov_write(const char *path, const sc_aov *aov, sc_error *err)
{
    char cam[512], header[AOV_MAX_HEADER], list[256] = "";
    sc_camera_format(&aov->camera, cam, sizeof cam);
    int nch = aov->has_iters ? CH_COUNT : CH_ITERS;
    for (int c = 0; c < nch; c++) {
        const channel_desc *d = &known_channels[c];
        char item[48];
        snprintf(item, sizeof item, "%s%s:%s%s", c ? "," : "", d->name, d->is_int ? "i32" : "f32",
                 d->components == 2 ? "x2" : d->components == 3 ? "x3" : "");
        strncat(list, item, sizeof list - strlen(list) - 1);
    }
    snprintf(header, sizeof header, AOV_MAGIC " %d %d camera=%s channels=%s\n", aov->width,
             aov->height, cam, list);

    sc_out_file out;
    if (sc_out_open(&out, path, err))
        return SC_FAIL;
    int ok = fputs(header, out.f) >= 0;
    size_t npix = (size_t)aov->width * (size_t)aov->height;
    unsigned char *buf = sc_alloc(npix * 3, 4);
    for (int c = 0; c < nch && ok; c++) {
        size_t count = npix * (size_t)known_channels[c].components;
        put_le32(buf, channel_data(aov, c), count);
        ok = fwrite(buf, 4, count, out.f) == count;
    }
    free(buf);
    if (!ok) {
        sc_out_abandon(&out);
        return sc_fail(err, path, 0, "writing the AOV file failed (disk full?)");
    }
    return sc_out_commit(&out, err);
}

/* One "name:TYPE[xN]" item of the channel list. */
static int parse_channel(const char *item, char *name, size_t name_size, int *is_int,
                         int *components)
{
    const char *colon = strchr(item, ':');
    if (!colon || colon == item || (size_t)(colon - item) >= name_size)
        return 0;
    memcpy(name, item, (size_t)(colon - item));
    name[colon - item] = 0;
    const char *type = colon + 1;
    if (!strncmp(type, "i32", 3))
        *is_int = 1;
    else if (!strncmp(type, "f32", 3))
        *is_int = 0;
    else
        return 0;
    type += 3;
    *components = 1;
    if (*type == 'x') {
        char *end;
        long n = strtol(type + 1, &end, 10);
        if (end == type + 1 || *end || n < 1 || n > 16)
            return 0;
        *components = (int)n;
    } else if (*type) {
        return 0;
    }
    return 1;
}

/* Where the channel data comes from: a file or memory. */
typedef struct aov_source {
    FILE *f;
    const unsigned char *mem;
    size_t left;
} aov_source;

static int source_read(aov_source *src, void *buf, size_t n)
{
    if (src->f)
        return fread(buf, 1, n, src->f) == n;
    if (src->left < n)
        return 0;
    memcpy(buf, src->mem, n);
    src->mem += n;
    src->left -= n;
    return 1;
}

/* Reads what follows the header line (NUL-terminated, without its
 * newline): `available` bytes of channel data are there (SIZE_MAX when
 * unknown, for a pipe). The data's size is checked against the header
 * before anything is allocated, so a short file cannot ask for gigabytes. */
static int read_body(const char *path, char *header, aov_source *src, size_t available,
                     sc_aov *aov, sc_error *err)
{
    int width, height, used = 0;
    char cam_text[600], list[AOV_MAX_HEADER];
    if (strncmp(header, AOV_MAGIC " ", sizeof AOV_MAGIC) != 0)
        return sc_fail(err, path, 1, "not an AOV file (expected magic " AOV_MAGIC ")");
    if (sscanf(header, AOV_MAGIC " %d %d camera=%599s channels=%2047s%n", &width, &height,
               cam_text, list, &used) != 4 || header[used] != 0)
        return sc_fail(err, path, 1,
                       "bad header: expected '" AOV_MAGIC " W H camera=... channels=...'");
    if (width <= 0 || height <= 0 || (long long)width * height > SC_MAX_IMAGE_PIXELS)
        return sc_fail(err, path, 1, "bad image size %dx%d (at most %lld pixels; "
                       "docs/limits.md)", width, height, SC_MAX_IMAGE_PIXELS);
    sc_camera cam = {.width = width, .height = height};
    sc_error cam_err = {0};
    if (sc_camera_parse(cam_text, &cam, &cam_err) != SC_OK)
        return sc_fail(err, path, 1, "%s", cam_err.message);

    /* First pass over the list: which channels, in which order. */
    int order[32], comps[32], nitems = 0, seen[CH_COUNT] = {0};
    for (char *save = NULL, *item = strtok_r(list, ",", &save); item;
         item = strtok_r(NULL, ",", &save)) {
        char name[64];
        int is_int, components;
        if (nitems == 32 || !parse_channel(item, name, sizeof name, &is_int, &components))
            return sc_fail(err, path, 1, "bad channel '%s' (expected NAME:i32 or NAME:f32xN)",
                           item);
        int ch = -1;
        for (int c = 0; c < CH_COUNT; c++)
            if (!strcmp(name, known_channels[c].name))
                ch = c;
        if (ch >= 0 && (is_int != known_channels[ch].is_int ||
                        components != known_channels[ch].components || seen[ch]))
            return sc_fail(err, path, 1, "channel '%s' has the wrong type or appears twice",
                           item);
        if (ch >= 0)
            seen[ch] = 1;
        order[nitems] = ch; /* -1: unknown, skipped */
        comps[nitems++] = components;
    }
    for (int c = 0; c < CH_ITERS; c++)
        if (!seen[c])
            return sc_fail(err, path, 1, "channel '%s' is missing", known_channels[c].name);

    size_t npix = (size_t)width * (size_t)height, need = 0;
    for (int k = 0; k < nitems; k++) {
        size_t bytes = npix * (size_t)comps[k] * 4;
        if (available != SIZE_MAX && available - need < bytes)
            return sc_fail(err, path, 0, "truncated: channel %d of %d is incomplete", k + 1,
                           nitems);
        need += bytes;
    }
    if (available != SIZE_MAX && available > need)
        return sc_fail(err, path, 0, "unexpected bytes after the last channel");
    if (aov_try_alloc(aov, &cam, seen[CH_ITERS]))
        return sc_fail(err, path, 1, "out of memory for the channels of %d x %d pixels", width,
                       height);
    /* Through a fixed buffer: the file's words are little-endian. */
    unsigned char buf[1 << 16];
    for (int k = 0; k < nitems; k++) {
        size_t count = npix * (size_t)comps[k];
        unsigned char *dst = order[k] >= 0 ? channel_data(aov, order[k]) : NULL;
        for (size_t done = 0; done < count;) {
            size_t words = count - done < sizeof buf / 4 ? count - done : sizeof buf / 4;
            if (!source_read(src, buf, words * 4)) {
                sc_aov_free(aov);
                return sc_fail(err, path, 0, "truncated: channel %d of %d is incomplete", k + 1,
                               nitems);
            }
            if (dst)
                get_le32(dst + 4 * done, buf, words);
            done += words;
        }
    }
    if (src->f && fgetc(src->f) != EOF) {
        sc_aov_free(aov);
        return sc_fail(err, path, 0, "unexpected bytes after the last channel");
    }
    return SC_OK;
}

int sc_aov_read(const char *path, sc_aov *aov, sc_error *err)
{
    memset(aov, 0, sizeof *aov);
    FILE *f = fopen(path, "rb");
    if (!f)
        return sc_fail(err, path, 0, "cannot open: %s", strerror(errno));
    char header[AOV_MAX_HEADER];
    if (!fgets(header, sizeof header, f) || !strchr(header, '\n')) {
        fclose(f);
        return sc_fail(err, path, 1, "not an AOV file (no header line)");
    }
    size_t header_len = strlen(header);
    *strchr(header, '\n') = 0;
    struct stat st;
    size_t available = SIZE_MAX;
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode))
        available = (unsigned long long)st.st_size >= header_len
                        ? (size_t)st.st_size - header_len : 0;
    aov_source src = {f, NULL, 0};
    int status = read_body(path, header, &src, available, aov, err);
    fclose(f);
    return status;
}

int sc_aov_read_mem(const void *data, size_t size, const char *name, sc_aov *aov, sc_error *err)
{
    memset(aov, 0, sizeof *aov);
    const unsigned char *bytes = data;
    size_t scan = size < AOV_MAX_HEADER - 1 ? size : AOV_MAX_HEADER - 1;
    const unsigned char *nl = memchr(bytes, '\n', scan);
    if (!nl || memchr(bytes, 0, (size_t)(nl - bytes)))
        return sc_fail(err, name, 1, "not an AOV file (no header line)");
    char header[AOV_MAX_HEADER];
    size_t header_len = (size_t)(nl - bytes) + 1;
    memcpy(header, bytes, header_len - 1);
    header[header_len - 1] = 0;
    aov_source src = {NULL, bytes + header_len, size - header_len};
    return read_body(name, header, &src, size - header_len, aov, err);
}
