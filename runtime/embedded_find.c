/* embedded_find.c — look-up in the table of embedded files. */
#include <string.h>

#include "embedded.h"

const sc_embedded_file *sc_embedded_find(const char *name)
{
    for (const sc_embedded_file *f = sc_embedded_files; f->name; f++)
        if (!strcmp(f->name, name))
            return f;
    return NULL;
}
