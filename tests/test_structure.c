/* test_structure.c — the layout rules of docs/README.md that the include
 * paths of the Makefile cannot enforce, checked on the built objects by
 * tests/structure.sh: no call cycle between files, and few long files. */
#include <stdlib.h>

#include "test.h"

TEST(structure_no_cycles_and_few_long_files)
{
    const char *build = getenv("SC_BUILD") ? getenv("SC_BUILD") : "build";
    char cmd[1024];
    /* SC_BUILD is relative to the project root, as `make test` runs. */
    snprintf(cmd, sizeof cmd, "cd '%s' && sh tests/structure.sh '%s' >&2", test_root_dir, build);
    CHECK_INT(system(cmd), 0);
}
