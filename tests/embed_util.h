/* embed_util.h — the example programs of docs/api.md built the way a user
 * builds them: against a copy of the library installed by `make install`
 * (once per test run, into a staging folder) through pkg-config. */
#ifndef SC_TEST_EMBED_UTIL_H
#define SC_TEST_EMBED_UTIL_H

#include <stddef.h>

/* Builds examples/NAME.c against the installed copy into exe; 0 when
 * built, else nonzero after a failed check. */
int test_build_example(const char *name, char *exe, size_t size);

#endif
