/* gl_binary_cache.c — program binaries on disk (gl_binary_cache.h). A file:
 *   "SCPB" u32 version, u32 format (GL enum), u32 driver string bytes,
 *   u64 source hash, u64 binary bytes, the driver string, the binary;
 * little-endian as the host writes it (the driver's binary is for this
 * machine anyway). A file that does not match in any field is ignored
 * and, once the program is compiled, replaced. */
#include "gl_binary_cache.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io.h"

enum { BINARY_VERSION = 1, MAX_BINARY_BYTES = 64 << 20 };

struct sc_binary_cache {
    const sc_gl *gl;
    char dir[1024];
    char driver[768];        /* vendor | renderer | version */
    uint64_t driver_hash;
};

typedef struct file_header {
    char magic[4];
    uint32_t version, format, driver_bytes;
    uint64_t source_hash, binary_bytes;
} file_header;

static uint64_t fnv1a(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++)
        h = (h ^ p[i]) * 1099511628211u;
    return h;
}

static const uint64_t FNV_BASIS = 14695981039346656037u;

uint64_t sc_binary_cache_source_hash(const char *vertex, const char *fragment)
{
    uint64_t h = fnv1a(FNV_BASIS, vertex, strlen(vertex) + 1);
    return fnv1a(h, fragment, strlen(fragment) + 1);
}

sc_binary_cache *sc_binary_cache_open(const sc_gl *gl, const char *dir)
{
    GLint formats = 0;
    gl->GetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
    if (formats <= 0) {
        sc_log(SC_LOG_INFO, "program binaries: the driver offers no binary formats; "
                            "programs are compiled at every start");
        return NULL;
    }
    if (strlen(dir) >= 1024) {
        sc_log(SC_LOG_WARN, "program binaries: folder name too long; not cached");
        return NULL;
    }
    sc_binary_cache *bc = sc_alloc(1, sizeof *bc);
    bc->gl = gl;
    snprintf(bc->dir, sizeof bc->dir, "%s", dir);
    snprintf(bc->driver, sizeof bc->driver, "%s | %s | %s",
             (const char *)gl->GetString(GL_VENDOR), (const char *)gl->GetString(GL_RENDERER),
             (const char *)gl->GetString(GL_VERSION));
    bc->driver_hash = fnv1a(FNV_BASIS, bc->driver, strlen(bc->driver));
    return bc;
}

void sc_binary_cache_close(sc_binary_cache *bc) { free(bc); }

static void file_name(const sc_binary_cache *bc, const char *key, char *path, size_t size)
{
    snprintf(path, size, "%s/%s.%016llx.bin", bc->dir, key, (unsigned long long)bc->driver_hash);
}

GLuint sc_binary_cache_load(sc_binary_cache *bc, const char *key, uint64_t source_hash)
{
    if (!bc)
        return 0;
    char path[1400];
    file_name(bc, key, path, sizeof path);
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    file_header h;
    GLuint program = 0;
    size_t driver_bytes = strlen(bc->driver);
    char *data = NULL;
    if (fread(&h, sizeof h, 1, f) == 1 && !memcmp(h.magic, "SCPB", 4) &&
        h.version == BINARY_VERSION && h.source_hash == source_hash &&
        h.driver_bytes == driver_bytes && h.binary_bytes > 0 &&
        h.binary_bytes <= MAX_BINARY_BYTES) {
        data = malloc(driver_bytes + (size_t)h.binary_bytes);
        if (data && fread(data, 1, driver_bytes + (size_t)h.binary_bytes, f) ==
                        driver_bytes + (size_t)h.binary_bytes &&
            !memcmp(data, bc->driver, driver_bytes)) {
            const sc_gl *gl = bc->gl;
            program = gl->CreateProgram();
            gl->ProgramBinary(program, h.format, data + driver_bytes, (GLsizei)h.binary_bytes);
            GLint ok = 0;
            gl->GetProgramiv(program, GL_LINK_STATUS, &ok);
            if (!ok) {
                gl->DeleteProgram(program);
                program = 0;
                sc_log(SC_LOG_INFO, "program binaries: %s refused by the driver; compiling", path);
            }
        }
    }
    free(data);
    fclose(f);
    return program;
}

void sc_binary_cache_prepare(sc_binary_cache *bc, GLuint program)
{
    if (bc)
        bc->gl->ProgramParameteri(program, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
}

void sc_binary_cache_store(sc_binary_cache *bc, const char *key, uint64_t source_hash,
                           GLuint program)
{
    if (!bc)
        return;
    const sc_gl *gl = bc->gl;
    GLint length = 0;
    gl->GetProgramiv(program, GL_PROGRAM_BINARY_LENGTH, &length);
    if (length <= 0 || length > MAX_BINARY_BYTES)
        return;
    char *binary = malloc((size_t)length);
    GLenum format = 0;
    GLsizei got = 0;
    if (!binary)
        return;
    gl->GetProgramBinary(program, length, &got, &format, binary);
    char path[1400];
    file_name(bc, key, path, sizeof path);
    sc_error err = {0};
    sc_out_file out;
    /* The folder itself is made on first use; its parent must exist. */
    if (mkdir(bc->dir, 0777) != 0 && errno != EEXIST)
        sc_fail(&err, NULL, 0, "cannot make the folder (%s)", strerror(errno));
    else if (got > 0 && sc_out_open(&out, path, &err) == SC_OK) {
        file_header h = {.magic = {'S', 'C', 'P', 'B'},
                         .version = BINARY_VERSION,
                         .format = format,
                         .driver_bytes = (uint32_t)strlen(bc->driver),
                         .source_hash = source_hash,
                         .binary_bytes = (uint64_t)got};
        fwrite(&h, sizeof h, 1, out.f);
        fwrite(bc->driver, 1, h.driver_bytes, out.f);
        fwrite(binary, 1, (size_t)got, out.f);
        sc_out_commit(&out, &err);
    }
    if (err.message[0])
        sc_log(SC_LOG_WARN, "program binaries: %s not written: %s", path, err.message);
    free(binary);
}
