/* gl_binary_cache.h — linked programs kept on disk (glGetProgramBinary) so
 * that a second start of a program loads them instead of compiling. One
 * file per key and driver in a folder: DIR/KEY.DRIVER.bin, DRIVER a hash of
 * the vendor, renderer and version strings, which the file also holds
 * whole; it holds as well a hash of the program's GLSL, so that changed
 * sources are compiled again, never served stale. A driver that offers no
 * binary formats (llvmpipe with Mesa's own cache off) gets no files:
 * programs are compiled as before. */
#ifndef SC_GL_BINARY_CACHE_H
#define SC_GL_BINARY_CACHE_H

#include <stdint.h>

#include "gl_loader.h"

typedef struct sc_binary_cache sc_binary_cache;

/* For the current context; NULL (nothing cached) when the driver has no
 * binary formats. */
sc_binary_cache *sc_binary_cache_open(const sc_gl *gl, const char *dir);
void sc_binary_cache_close(sc_binary_cache *bc);

/* FNV-1a over both stages: what a cached binary must have been built from. */
uint64_t sc_binary_cache_source_hash(const char *vertex, const char *fragment);

/* A program linked from the cached binary of key, or 0 when there is none
 * (or the driver refused it: a binary of another build of the driver). */
GLuint sc_binary_cache_load(sc_binary_cache *bc, const char *key, uint64_t source_hash);
/* Asks the driver to keep the binary of a program about to be linked. */
void sc_binary_cache_prepare(sc_binary_cache *bc, GLuint program);
/* Writes the linked program's binary (never half-written); a failure is
 * logged, not returned: the cache only saves time. */
void sc_binary_cache_store(sc_binary_cache *bc, const char *key, uint64_t source_hash,
                           GLuint program);

#endif
