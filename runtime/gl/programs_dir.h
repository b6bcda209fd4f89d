/* programs_dir.h — the programs of a `splinecast gen` folder, found by its
 * manifest (DIR/manifest.tsv: key, stage, file, bytes), so that a program
 * built at build time is loaded at run time without the compiler: no
 * generation, no glslang. */
#ifndef SC_PROGRAMS_DIR_H
#define SC_PROGRAMS_DIR_H

#include <stddef.h>

#include "sc_base.h"

typedef struct sc_programs_dir sc_programs_dir;

/* Reads DIR/manifest.tsv; a missing or malformed manifest fails with
 * manifest.tsv:line. */
int sc_programs_dir_open(const char *dir, sc_programs_dir **out, sc_error *err);
void sc_programs_dir_close(sc_programs_dir *d);
const char *sc_programs_dir_path(const sc_programs_dir *d);

/* Whether the manifest lists key (canonical text). */
int sc_programs_dir_has(const sc_programs_dir *d, const char *key);

/* The two stages of key, read from their files (allocated, NUL-terminated)
 * and checked against the manifest: the sizes it gives and the key each
 * fragment program's header names; a mismatch fails naming the key and
 * the file. vertex_name: the vertex program's file name without .vert. */
int sc_programs_dir_load(const sc_programs_dir *d, const char *key, char vertex_name[64],
                         char **vertex, char **fragment, sc_error *err);

#endif
