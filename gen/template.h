/* template.h — GLSL skeletons with named slots, and the growable text buffer
 * the emitter prints into. Templates live in templates/ and are embedded in
 * the library (embedded.h), so generating a program needs no data folder.
 *
 * A slot is written {{NAME}} (capitals, digits, '_'). Filling is strict, so
 * a template and the emitter cannot drift apart silently: every slot in the
 * template must be given, and every slot given must occur in the template.
 * A slot alone on its line takes that line's indentation for every line of
 * its text; an empty slot alone on its line removes the line. */
#ifndef SCG_TEMPLATE_H
#define SCG_TEMPLATE_H

#include <stddef.h>

#include "embedded.h"
#include "sc_base.h"

/* The templates/ folder, embedded by the Makefile. */
extern const sc_embedded_file scg_embedded_templates[];

/* Growable NUL-terminated text. Zero-initialised is an empty buffer. */
typedef struct scg_text {
    char *data;
    size_t len, cap;
} scg_text;

void scg_text_append(scg_text *t, const char *s);
void scg_text_append_n(scg_text *t, const char *s, size_t n);
void scg_text_printf(scg_text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The text so far ("" when nothing was appended; never NULL). */
const char *scg_text_str(const scg_text *t);
void scg_text_free(scg_text *t);

typedef struct scg_slot {
    const char *name;   /* without the braces */
    const char *text;   /* may span lines; a trailing newline is dropped */
} scg_slot;

/* The embedded template with this base name (e.g. "raycast.frag"), or NULL
 * with err filled. */
const char *scg_template_get(const char *name, sc_error *err);

/* Appends `template_text` to out with its slots filled. `template_name`
 * names the template in messages ("raycast.frag line 12: ..."). */
int scg_template_fill(scg_text *out, const char *template_name, const char *template_text,
                      const scg_slot *slots, int nslots, sc_error *err);

/* scg_template_get + scg_template_fill. */
int scg_template_expand(scg_text *out, const char *template_name, const scg_slot *slots,
                        int nslots, sc_error *err);

#endif
