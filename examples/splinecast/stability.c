/* stability.c — the stability suite's folder, table and measurement
 * (stability.h). The table is the folder's README.md, so that the list a
 * reader sees is the list that runs: rows `| name | file | camera | what |`,
 * the header and separator rows skipped. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "commands.h"
#include "stability.h"

#define SUITE_REL "examples/scenes/stability"

/* The library's error record: the message, and where in which file when
 * the table is at fault. */
static int fail_at(sc_error *err, const char *file, int line, const char *message)
{
    memset(err, 0, sizeof *err);
    snprintf(err->message, sizeof err->message, "%s", message);
    if (file)
        snprintf(err->file, sizeof err->file, "%.*s", (int)sizeof err->file - 1, file);
    err->line = line;
    return SC_FAIL;
}

static int has_table(const char *dir)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/README.md", dir);
    return access(path, R_OK) == 0;
}

int stab_find_suite(const char *given, char *dir, size_t size, sc_error *err)
{
    if (given) {
        if (!has_table(given))
            return fail_at(err, given, 0,
                           "no README.md (the suite's table) in this --suite folder");
        snprintf(dir, size, "%s", given);
        return SC_OK;
    }
    if (has_table(SUITE_REL)) {
        snprintf(dir, size, "%s", SUITE_REL);
        return SC_OK;
    }
    /* The executable lives in a build folder of the checkout (build/,
     * build-asan/, or deeper when installed from a staging tree), so the
     * folders above it are tried in turn. */
    char exe[1024];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        for (int up = 0; up < 4; up++) {
            char *slash = strrchr(exe, '/');
            if (!slash)
                break;
            *slash = '\0';
            char candidate[1100];
            snprintf(candidate, sizeof candidate, "%s/%s", exe[0] ? exe : "/", SUITE_REL);
            if (has_table(candidate)) {
                snprintf(dir, size, "%s", candidate);
                return SC_OK;
            }
        }
    }
    return fail_at(err, NULL, 0,
                   "the stability suite (" SUITE_REL "/README.md) is neither under the working "
                   "directory nor above the executable; give --suite DIR");
}

/* Copies cell `text` (up to the next '|') without its surrounding blanks;
 * returns where the next cell starts, or NULL at the end of the line. */
static const char *cell(const char *text, char *out, size_t size)
{
    const char *end = strpbrk(text, "|\n");
    if (!end || *end == '\n')
        return NULL;
    while (text < end && (*text == ' ' || *text == '\t'))
        text++;
    const char *last = end;
    while (last > text && (last[-1] == ' ' || last[-1] == '\t'))
        last--;
    size_t len = (size_t)(last - text) < size - 1 ? (size_t)(last - text) : size - 1;
    memcpy(out, text, len);
    out[len] = '\0';
    return end + 1;
}

int stab_read_suite(const char *dir, stab_suite *out, sc_error *err)
{
    memset(out, 0, sizeof *out);
    snprintf(out->dir, sizeof out->dir, "%s", dir);
    char path[1100];
    snprintf(path, sizeof path, "%s/README.md", dir);
    FILE *f = fopen(path, "r");
    if (!f)
        return fail_at(err, path, 0, "cannot be read");
    char line[2048];
    int lineno = 0, capacity = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (line[0] != '|')
            continue;
        stab_row row;
        const char *p = cell(line + 1, row.name, sizeof row.name);
        p = p ? cell(p, row.file, sizeof row.file) : NULL;
        p = p ? cell(p, row.camera, sizeof row.camera) : NULL;
        if (!p) {
            fclose(f);
            stab_free_suite(out);
            return fail_at(err, path, lineno, "a table row needs four cells");
        }
        if (!strcmp(row.file, "file") || row.file[0] == '-')
            continue;   /* the header and the separator */
        if (out->count == capacity) {
            capacity = capacity ? 2 * capacity : 16;
            stab_row *grown = realloc(out->rows, (size_t)capacity * sizeof *grown);
            if (!grown) {
                fclose(f);
                stab_free_suite(out);
                return fail_at(err, NULL, 0, "out of memory");
            }
            out->rows = grown;
        }
        out->rows[out->count++] = row;
    }
    fclose(f);
    if (!out->count)
        return fail_at(err, path, 0, "no scene rows in its table");
    return SC_OK;
}

void stab_free_suite(stab_suite *suite)
{
    free(suite->rows);
    suite->rows = NULL;
    suite->count = 0;
}

int stab_load_row(const stab_suite *suite, const stab_row *row, int width, int height,
                  sc_scene_id *scene, sc_camera_desc *cam, sc_error *err)
{
    char path[1300];
    snprintf(path, sizeof path, "%s/%s", suite->dir, row->file);
    *cam = (sc_camera_desc){.width = width, .height = height, .text = row->camera};
    if (sc_check_camera(cam, err) != SC_OK)
        return SC_FAIL;
    return sc_make_scene(&(sc_scene_desc){.path = path}, scene, err);
}

int stab_check_method(sc_scene_id scene, sc_method method, sc_start start,
                      unsigned long *keys_hash, sc_error *err)
{
    sc_keys_desc desc = {.method = method, .start = start};
    int count = 0;
    if (sc_query_scene_keys(scene, &desc, NULL, 0, &count, err) != SC_OK)
        return SC_FAIL;
    sc_key *keys = calloc((size_t)(count ? count : 1), sizeof *keys);
    if (!keys)
        return fail_at(err, NULL, 0, "out of memory");
    int status = sc_query_scene_keys(scene, &desc, keys, count, &count, err);
    unsigned long h = 5381;
    for (int k = 0; k < count && status == SC_OK; k++) {
        status = sc_check_key(keys[k].text, err);
        for (const char *p = keys[k].text; *p; p++)
            h = h * 33 + (unsigned char)*p;
        h = h * 33 + ' ';
    }
    if (keys_hash)
        *keys_hash = h;
    free(keys);
    return status;
}

int stab_measure(sc_context_id ctx, sc_scene_id scene, const sc_renderer_desc *desc,
                 const sc_camera_desc *cam, sc_frame_id ref, int frames, int keep_frame,
                 stab_result *out, sc_error *err)
{
    memset(out, 0, sizeof *out);
    sc_renderer_id r;
    if (sc_make_renderer(ctx, scene, desc, &r, err) != SC_OK)
        return SC_FAIL;
    double *times = calloc((size_t)(frames > 0 ? frames : 1), sizeof *times);
    int status = times ? sc_draw(r, cam, err) : fail_at(err, NULL, 0, "out of memory");
    for (int f = 0; f < frames && status == SC_OK; f++) {
        double t0 = sc_now();
        status = sc_draw(r, cam, err);
        times[f] = 1e3 * (sc_now() - t0);
    }
    if (status == SC_OK && frames > 0)
        out->frame_ms = cli_median(times, frames);
    sc_frame_id frame = {0};
    if (status == SC_OK)
        status = sc_read_frame(r, &frame, err);
    if (status == SC_OK)
        status = sc_compare_frames(ref, frame, &out->cmp, err);
    if (status == SC_OK && keep_frame)
        out->frame = frame;
    else
        sc_destroy_frame(frame);
    free(times);
    sc_destroy_renderer(r);
    return status;
}
