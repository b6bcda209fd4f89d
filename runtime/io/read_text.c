/* read_text.c — what every reader shares: whole files into memory, the
 * text check every reader runs before parsing (so that binary junk is
 * refused with a position instead of being half-parsed), and the common
 * end of a read (loop validation, or an empty scene on failure). The
 * dispatcher (read_scene.c) calls the readers, and the readers call these:
 * kept apart so that no two files call each other. */
#include "io.h"

#include <stdlib.h>
#include <string.h>

#include "envelope.h"

int sc_read_file(const char *path, char **data, size_t *size, sc_error *err)
{
    return sc_read_file_max(path, SC_MAX_FILE_BYTES, 0, data, size, err);
}

/* Length of the UTF-8 sequence starting at s (at most `left` bytes), or 0
 * when it is not a valid, shortest-form encoding of a scalar value. */
static size_t utf8_length(const unsigned char *s, size_t left)
{
    size_t len;
    unsigned min;
    unsigned cp;
    if (s[0] >= 0xC2 && s[0] <= 0xDF) {
        len = 2, min = 0x80, cp = s[0] & 0x1Fu;
    } else if (s[0] >= 0xE0 && s[0] <= 0xEF) {
        len = 3, min = 0x800, cp = s[0] & 0x0Fu;
    } else if (s[0] >= 0xF0 && s[0] <= 0xF4) {
        len = 4, min = 0x10000, cp = s[0] & 0x07u;
    } else {
        return 0;
    }
    if (left < len)
        return 0;
    for (size_t i = 1; i < len; i++) {
        if ((s[i] & 0xC0) != 0x80)
            return 0;
        cp = (cp << 6) | (s[i] & 0x3Fu);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
        return 0;
    return len;
}

int sc_check_text(const char *text, size_t size, const char *name, sc_error *err)
{
    const unsigned char *s = (const unsigned char *)text;
    int line = 1;
    for (size_t i = 0; i < size;) {
        unsigned char c = s[i];
        if (c == '\n') {
            line++;
            i++;
        } else if (c >= 0x20 && c < 0x7F) {
            i++;
        } else if (c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            i++;
        } else if (c == 0) {
            return sc_fail(err, name, line, "NUL byte: this is not a text file");
        } else if (c < 0x80) {
            return sc_fail(err, name, line, "control character 0x%02x: this is not a text file", c);
        } else {
            size_t len = utf8_length(s + i, size - i);
            if (!len)
                return sc_fail(err, name, line, "invalid byte 0x%02x (not UTF-8 text)", c);
            i += len;
        }
    }
    return SC_OK;
}

int sc_finish_read(int status, const char *name, sc_scene *scene, sc_error *err)
{
    if (status == SC_OK) {
        snprintf(scene->source, sizeof scene->source, "%s", name);
        status = sc_scene_validate_loops(scene, err);
    }
    if (status != SC_OK) {
        sc_scene_free(scene);
        return SC_FAIL;
    }
    return SC_OK;
}
