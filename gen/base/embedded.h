/* embedded.h — files compiled into the library by the Makefile
 * (gen/base/embed.sh), so that it needs no data directory: the GLSL
 * templates (the compiler's table) and the default scene (the runtime's
 * table). Each file's bytes are followed by a NUL. */
#ifndef SC_EMBEDDED_H
#define SC_EMBEDDED_H

#include <stddef.h>

typedef struct sc_embedded_file {
    const char *name;              /* base name, e.g. "raycast.frag" */
    const unsigned char *data;
    size_t size;
} sc_embedded_file;

/* The file with this base name in `table` (terminated by an entry with name
 * NULL), or NULL. */
const sc_embedded_file *sc_embedded_find(const sc_embedded_file *table, const char *name);

#endif
