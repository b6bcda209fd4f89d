/* embedded.h — files compiled into the library by the Makefile (the
 * default teapot scene, the GLSL templates), so that the runtime needs no
 * data directory. Each file's bytes are followed by a NUL. */
#ifndef SC_EMBEDDED_H
#define SC_EMBEDDED_H

#include <stddef.h>

typedef struct sc_embedded_file {
    const char *name;              /* base name, e.g. "teapot32.bpt" */
    const unsigned char *data;
    size_t size;
} sc_embedded_file;

/* Terminated by an entry with name NULL. */
extern const sc_embedded_file sc_embedded_files[];

/* The file with this base name, or NULL. */
const sc_embedded_file *sc_embedded_find(const char *name);

#endif
