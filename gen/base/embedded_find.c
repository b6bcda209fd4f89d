/* embedded_find.c — look-up in a table of embedded files. */
#include <string.h>

#include "embedded.h"

const sc_embedded_file *sc_embedded_find(const sc_embedded_file *table, const char *name)
{
    for (const sc_embedded_file *f = table; f->name; f++)
        if (!strcmp(f->name, name))
            return f;
    return NULL;
}
