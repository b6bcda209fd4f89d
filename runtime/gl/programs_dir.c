/* programs_dir.c — loading generated programs from a `splinecast gen`
 * folder by its manifest (programs_dir.h). The folder is input like any
 * file: names with a '/' are refused (nothing outside the folder is read),
 * files are read with a size cap, and a file that is not what the
 * manifest says fails naming the key. */
#include "programs_dir.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io.h"
#include "key.h"

/* A program's GLSL is tens of kilobytes; a manifest one row per stage. */
enum { MAX_GLSL_BYTES = 16 << 20, MAX_MANIFEST_BYTES = 16 << 20, MAX_NAME = 160 };

typedef struct row {
    char key[SCG_KEY_MAX];
    char frag[MAX_NAME], vert[MAX_NAME];
    size_t frag_bytes, vert_bytes;
} row;

struct sc_programs_dir {
    char path[1024];
    int count;
    row *rows;
};

static row *find(const sc_programs_dir *d, const char *key)
{
    for (int i = 0; i < d->count; i++)
        if (!strcmp(d->rows[i].key, key))
            return &d->rows[i];
    return NULL;
}

int sc_programs_dir_open(const char *dir, sc_programs_dir **out, sc_error *err)
{
    *out = NULL;
    char path[1100];
    if (strlen(dir) >= 1024)
        return sc_fail(err, NULL, 0, "programs folder name too long (at most 1023 characters)");
    snprintf(path, sizeof path, "%s/manifest.tsv", dir);
    char *text;
    size_t size;
    if (sc_read_file_max(path, MAX_MANIFEST_BYTES, 1, &text, &size, err) != SC_OK)
        return SC_FAIL;
    if (sc_check_text(text, size, path, err) != SC_OK) {
        free(text);
        return SC_FAIL;
    }
    sc_programs_dir *d = sc_alloc(1, sizeof *d);
    snprintf(d->path, sizeof d->path, "%s", dir);
    int line = 0, cap = 0, status = SC_OK;
    for (char *p = text, *next; p && *p && status == SC_OK; p = next) {
        next = strchr(p, '\n');
        if (next)
            *next++ = 0;
        line++;
        if (line == 1) {
            if (strcmp(p, "key\tstage\tfile\tbytes"))
                status = sc_fail(err, path, line, "not a manifest of `splinecast gen` (its "
                                                  "first line is \"key<TAB>stage<TAB>file<TAB>bytes\")");
            continue;
        }
        char key[SCG_KEY_MAX + 1], stage[8], file[MAX_NAME + 1];
        unsigned long bytes;
        char extra;
        if (sscanf(p, "%128[^\t]\t%7[^\t]\t%160[^\t]\t%lu%c", key, stage, file, &bytes, &extra) != 4 ||
            strlen(key) >= SCG_KEY_MAX || strlen(file) >= MAX_NAME ||
            (strcmp(stage, "frag") && strcmp(stage, "vert"))) {
            status = sc_fail(err, path, line, "expected KEY<TAB>frag|vert<TAB>FILE<TAB>BYTES");
            break;
        }
        if (strchr(file, '/')) {
            status = sc_fail(err, path, line, "file %s is not in the folder", file);
            break;
        }
        row *r = find(d, key);
        if (!r) {
            if (d->count == cap) {
                cap = cap ? 2 * cap : 16;
                d->rows = sc_realloc(d->rows, (size_t)cap, sizeof *d->rows);
            }
            r = &d->rows[d->count++];
            memset(r, 0, sizeof *r);
            snprintf(r->key, sizeof r->key, "%s", key);
        }
        int is_frag = !strcmp(stage, "frag");
        snprintf(is_frag ? r->frag : r->vert, MAX_NAME, "%s", file);
        *(is_frag ? &r->frag_bytes : &r->vert_bytes) = bytes;
    }
    free(text);
    for (int i = 0; i < d->count && status == SC_OK; i++)
        if (!d->rows[i].frag[0] || !d->rows[i].vert[0])
            status = sc_fail(err, path, 0, "key %s has no %s row", d->rows[i].key,
                             d->rows[i].frag[0] ? "vert" : "frag");
    if (status != SC_OK) {
        sc_programs_dir_close(d);
        return SC_FAIL;
    }
    *out = d;
    return SC_OK;
}

void sc_programs_dir_close(sc_programs_dir *d)
{
    if (!d)
        return;
    free(d->rows);
    free(d);
}

const char *sc_programs_dir_path(const sc_programs_dir *d) { return d->path; }

int sc_programs_dir_has(const sc_programs_dir *d, const char *key) { return find(d, key) != NULL; }

/* Names the key in a failure already filled in. */
static int with_key(sc_error *err, const char *key)
{
    if (err)
        snprintf(err->key, sizeof err->key, "%s", key);
    return SC_FAIL;
}

/* One stage's file, its size checked against the manifest's. */
static int read_stage(const sc_programs_dir *d, const char *key, const char *file, size_t bytes,
                      char **text, sc_error *err)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", d->path, file);
    size_t size;
    if (sc_read_file_max(path, MAX_GLSL_BYTES, 1, text, &size, err) != SC_OK)
        return with_key(err, key);
    if (size != bytes) {
        free(*text);
        *text = NULL;
        sc_fail(err, NULL, 0, "%s has %zu bytes where the manifest says %zu: it changed "
                              "after `splinecast gen` wrote it", path, size, bytes);
        return with_key(err, key);
    }
    return SC_OK;
}

int sc_programs_dir_load(const sc_programs_dir *d, const char *key, char vertex_name[64],
                         char **vertex, char **fragment, sc_error *err)
{
    *vertex = *fragment = NULL;
    const row *r = find(d, key);
    if (!r) {
        sc_fail(err, NULL, 0, "not in %s/manifest.tsv: generate it at build time "
                              "(splinecast gen --key KEY -o %s, or --scene with the options "
                              "the renderer is made with), or let the runtime generate what "
                              "is missing (sc_context_desc.generate_missing)",
                d->path, d->path);
        return with_key(err, key);
    }
    if (read_stage(d, key, r->frag, r->frag_bytes, fragment, err) != SC_OK ||
        read_stage(d, key, r->vert, r->vert_bytes, vertex, err) != SC_OK) {
        free(*fragment);
        *fragment = NULL;
        return SC_FAIL;
    }
    /* The fragment program names its key in its header (emitter.md). */
    char want[SCG_KEY_MAX + 16];
    snprintf(want, sizeof want, "\n// key: %s\n", key);
    if (!strstr(*fragment, want)) {
        free(*fragment);
        free(*vertex);
        *fragment = *vertex = NULL;
        sc_fail(err, NULL, 0, "%s/%s is not the program of this key (its header names another)",
                d->path, r->frag);
        return with_key(err, key);
    }
    size_t n = strlen(r->vert);
    if (n > 5 && !strcmp(r->vert + n - 5, ".vert"))
        n -= 5;
    snprintf(vertex_name, 64, "%.*s", (int)n, r->vert);
    return SC_OK;
}
