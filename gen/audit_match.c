/* audit_match.c — pairing the shaders of two audits when an option changed
 * (`audit --compare --match FIELDS`): keys are compared with the chosen
 * fields left out, so that, say, every Newton program of one audit meets
 * the Broyden program of the same patch in the other. */
#include <stdlib.h>
#include <string.h>

#include "audit.h"

/* The fields of a key's canonical text in order (key.h), by the names
 * --match takes. */
static const char *const field_names[] = {"shape", "rational", "eval", "trim", "method",
                                          "start", "iters", "tol", "ert", "out"};
enum { FIELD_COUNT = sizeof field_names / sizeof field_names[0] };

int scg_audit_match_fields(const char *list, unsigned *ignore, sc_error *err)
{
    *ignore = 0;
    const char *p = list;
    while (*p) {
        size_t n = strcspn(p, ",");
        int found = -1;
        for (int f = 0; f < FIELD_COUNT; f++)
            if (strlen(field_names[f]) == n && !strncmp(p, field_names[f], n))
                found = f;
        if (found < 0)
            return sc_fail(err, NULL, 0, "--match: unknown key field '%.*s' (fields: shape, "
                           "rational, eval, trim, method, start, iters, tol, ert, out)",
                           (int)n, p);
        *ignore |= 1u << found;
        p += n;
        if (*p == ',')
            p++;
    }
    if (!*ignore)
        return sc_fail(err, NULL, 0, "--match wants a list of key fields, e.g. method,iters");
    return SC_OK;
}

/* The key with the ignored fields emptied; a name that is not a key
 * (vertex programs) stays whole. */
static void masked(const char *key, unsigned ignore, char *out, size_t size)
{
    int fields = 1;
    for (const char *c = key; *c; c++)
        fields += *c == '-';
    if (fields != FIELD_COUNT || !ignore) {
        snprintf(out, size, "%s", key);
        return;
    }
    size_t len = 0;
    const char *p = key;
    for (int f = 0; f < FIELD_COUNT; f++) {
        size_t n = strcspn(p, "-");
        if (!(ignore & (1u << f)) && len + n + 2 < size) {
            memcpy(out + len, p, n);
            len += n;
        }
        if (len + 1 < size)
            out[len++] = '-';
        p += n + (p[n] == '-');
    }
    out[len ? len - 1 : 0] = 0;
}

int scg_audit_pair(const scg_audit_line *old_lines, int old_count,
                   const scg_audit_line *new_lines, int new_count, unsigned ignore,
                   int *old_of_new, sc_error *err)
{
    char a[256], b[256];
    for (int i = 0; i < new_count; i++) {
        old_of_new[i] = -1;
        masked(new_lines[i].key, ignore, a, sizeof a);
        for (int j = 0; j < old_count; j++) {
            if (old_lines[j].stage != new_lines[i].stage)
                continue;
            masked(old_lines[j].key, ignore, b, sizeof b);
            if (strcmp(a, b))
                continue;
            if (old_of_new[i] >= 0)
                return sc_fail(err, NULL, 0, "--match: %s and %s of the old audit both match "
                               "%s: leave fewer fields out", old_lines[old_of_new[i]].key,
                               old_lines[j].key, new_lines[i].key);
            old_of_new[i] = j;
        }
        for (int k = 0; k < i && old_of_new[i] >= 0; k++)
            if (old_of_new[k] == old_of_new[i])
                return sc_fail(err, NULL, 0, "--match: %s and %s of the new audit both match "
                               "%s: leave fewer fields out", new_lines[k].key, new_lines[i].key,
                               old_lines[old_of_new[i]].key);
    }
    return SC_OK;
}
