/* aov.c — the AOV file (aov.h, docs/aov-format.md): one text header line
 * with magic, size, camera and channel list, then each channel as a plane of
 * little-endian 32-bit values. The camera is stored with %.17g so that a
 * file compares equal to the camera it was rendered with. */
#include "aov.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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

void sc_aov_alloc(sc_aov *aov, const sc_camera *cam, int has_iters)
{
    memset(aov, 0, sizeof *aov);
    aov->width = cam->width;
    aov->height = cam->height;
    aov->camera = *cam;
    aov->has_iters = has_iters;
    size_t n = (size_t)cam->width * (size_t)cam->height;
    aov->surface = sc_alloc(n, sizeof(int32_t));
    for (size_t i = 0; i < n; i++)
        aov->surface[i] = -1;
    aov->uv = sc_alloc(n * 2, sizeof(float));
    aov->t = sc_alloc(n, sizeof(float));
    aov->point = sc_alloc(n * 3, sizeof(float));
    aov->normal = sc_alloc(n * 3, sizeof(float));
    aov->iters = has_iters ? sc_alloc(n, sizeof(float)) : NULL;
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
    *strchr(header, '\n') = 0;
    int width, height, used = 0;
    char cam_text[600], list[AOV_MAX_HEADER];
    if (strncmp(header, AOV_MAGIC " ", sizeof AOV_MAGIC) != 0) {
        fclose(f);
        return sc_fail(err, path, 1, "not an AOV file (expected magic " AOV_MAGIC ")");
    }
    if (sscanf(header, AOV_MAGIC " %d %d camera=%599s channels=%2047s%n", &width, &height,
               cam_text, list, &used) != 4 || header[used] != 0) {
        fclose(f);
        return sc_fail(err, path, 1,
                       "bad header: expected '" AOV_MAGIC " W H camera=... channels=...'");
    }
    if (width <= 0 || height <= 0 || (long long)width * height > (1LL << 28)) {
        fclose(f);
        return sc_fail(err, path, 1, "bad image size %dx%d", width, height);
    }
    sc_camera cam = {.width = width, .height = height};
    sc_error cam_err = {0};
    if (sc_camera_parse(cam_text, &cam, &cam_err) != SC_OK) {
        fclose(f);
        return sc_fail(err, path, 1, "%s", cam_err.message);
    }

    /* First pass over the list: which channels, in which order. */
    int order[32], comps[32], nitems = 0, seen[CH_COUNT] = {0};
    for (char *save = NULL, *item = strtok_r(list, ",", &save); item;
         item = strtok_r(NULL, ",", &save)) {
        char name[64];
        int is_int, components;
        if (nitems == 32 || !parse_channel(item, name, sizeof name, &is_int, &components)) {
            fclose(f);
            return sc_fail(err, path, 1, "bad channel '%s' (expected NAME:i32 or NAME:f32xN)",
                           item);
        }
        int ch = -1;
        for (int c = 0; c < CH_COUNT; c++)
            if (!strcmp(name, known_channels[c].name))
                ch = c;
        if (ch >= 0 && (is_int != known_channels[ch].is_int ||
                        components != known_channels[ch].components || seen[ch])) {
            fclose(f);
            return sc_fail(err, path, 1, "channel '%s' has the wrong type or appears twice",
                           item);
        }
        if (ch >= 0)
            seen[ch] = 1;
        order[nitems] = ch; /* -1: unknown, skipped */
        comps[nitems++] = components;
    }
    for (int c = 0; c < CH_ITERS; c++)
        if (!seen[c]) {
            fclose(f);
            return sc_fail(err, path, 1, "channel '%s' is missing", known_channels[c].name);
        }

    sc_aov_alloc(aov, &cam, seen[CH_ITERS]);
    size_t npix = (size_t)width * (size_t)height;
    unsigned char *buf = sc_alloc(npix * 16, 4);
    for (int k = 0; k < nitems; k++) {
        size_t count = npix * (size_t)comps[k];
        if (fread(buf, 4, count, f) != count) {
            free(buf);
            fclose(f);
            sc_aov_free(aov);
            return sc_fail(err, path, 0, "truncated: channel %d of %d is incomplete", k + 1,
                           nitems);
        }
        if (order[k] >= 0)
            get_le32(channel_data(aov, order[k]), buf, count);
    }
    free(buf);
    int extra = fgetc(f) != EOF;
    fclose(f);
    if (extra) {
        sc_aov_free(aov);
        return sc_fail(err, path, 0, "unexpected bytes after the last channel");
    }
    return SC_OK;
}
