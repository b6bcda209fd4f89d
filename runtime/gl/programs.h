/* programs.h — runtime specialization: the GL program of a variant key,
 * generated through gen (build, optimise, emit GLSL, validate with glslang),
 * compiled, linked and cached on first use. A scene asks for each of its
 * distinct keys once; asking again returns the cached program. Vertex
 * programs are shared between keys that need the same one. */
#ifndef SC_PROGRAMS_H
#define SC_PROGRAMS_H

#include <stdint.h>

#include "gl_loader.h"
#include "key.h"

/* A cached program; id 0 is no program. */
typedef struct sc_program { uint32_t id; } sc_program;

typedef struct sc_program_cache sc_program_cache;

/* The cache belongs to the context that is current when it is created. */
sc_program_cache *sc_program_cache_create(const sc_gl *gl);
void sc_program_cache_destroy(sc_program_cache *cache);

/* Where programs come from besides the compiler: glsl_dir, a folder of
 * `splinecast gen` (programs_dir.h), whose programs are read instead of
 * generated; a key it lacks fails naming the key unless generate_missing;
 * binary_dir, linked programs kept on disk (gl_binary_cache.h). Either may
 * be NULL. Fails when glsl_dir has no readable manifest. */
int sc_program_cache_set_sources(sc_program_cache *cache, const char *glsl_dir,
                                 int generate_missing, const char *binary_dir, sc_error *err);

/* Whether sc_program_for_key can give the program of `key` without
 * failing for want of it: a gen folder without generate_missing gives only
 * the keys of its manifest. */
int sc_program_cache_offers(const sc_program_cache *cache, const scg_key *key);

/* The program of `key`: from the cache, or generated, validated, compiled
 * and linked now. A failure names the key (err->key) and, for a rejected
 * program, the compiler's message and the GLSL line it points at. */
int sc_program_for_key(sc_program_cache *cache, const scg_key *key, sc_program *out,
                       sc_error *err);

/* The driver half of sc_program_for_key (compile, link, cache) for GLSL
 * given here: a vertex program already compiled under vertex_name is
 * reused. For GLSL from elsewhere, and for tests of what a driver's
 * rejection reports: the key (err->key), the driver's first message and,
 * when it names one, the GLSL line, quoted. */
int sc_program_from_glsl(sc_program_cache *cache, const scg_key *key, const char *vertex_name,
                         const char *vertex, const char *fragment, sc_program *out,
                         sc_error *err);

GLuint sc_program_gl_name(const sc_program_cache *cache, sc_program program);
const scg_key *sc_program_key(const sc_program_cache *cache, sc_program program);
/* Programs in the cache. */
int sc_program_count(const sc_program_cache *cache);
/* Milliseconds spent on one program: generating and validating it (gen,
 * glslang), and compiling and linking it in the driver. */
void sc_program_times(const sc_program_cache *cache, sc_program program, double *gen_ms,
                      double *gl_ms);

#endif
