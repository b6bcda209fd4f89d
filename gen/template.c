/* template.c — slot filling for the embedded GLSL templates (template.h)
 * and the text buffer the emitter prints into. */
#include "template.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


static void text_reserve(scg_text *t, size_t extra)
{
    if (t->len + extra + 1 <= t->cap)
        return;
    size_t cap = t->cap ? t->cap : 256;
    while (cap < t->len + extra + 1)
        cap *= 2;
    t->data = sc_realloc(t->data, cap, 1);
    t->cap = cap;
}

void scg_text_append_n(scg_text *t, const char *s, size_t n)
{
    text_reserve(t, n);
    memcpy(t->data + t->len, s, n);
    t->len += n;
    t->data[t->len] = 0;
}

void scg_text_append(scg_text *t, const char *s) { scg_text_append_n(t, s, strlen(s)); }

void scg_text_printf(scg_text *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n <= 0)
        return;
    text_reserve(t, (size_t)n);
    va_start(ap, fmt);
    vsnprintf(t->data + t->len, (size_t)n + 1, fmt, ap);
    va_end(ap);
    t->len += (size_t)n;
}

const char *scg_text_str(const scg_text *t) { return t->data ? t->data : ""; }

void scg_text_free(scg_text *t)
{
    free(t->data);
    *t = (scg_text){0};
}

const char *scg_template_get(const char *name, sc_error *err)
{
    const sc_embedded_file *f = sc_embedded_find(scg_embedded_templates, name);
    if (!f) {
        sc_fail(err, NULL, 0, "no embedded template '%s' (is it in templates/?)", name);
        return NULL;
    }
    return (const char *)f->data;
}

/* Length of s without one trailing newline. */
static size_t without_final_newline(const char *s)
{
    size_t n = strlen(s);
    return n && s[n - 1] == '\n' ? n - 1 : n;
}

/* Appends text with `indent` before every non-empty line; every line,
 * the last included, ends with a newline, so text that ends in a newline
 * (after the one dropped) ends in a blank line. Empty text appends
 * nothing. */
static void append_indented(scg_text *out, const char *text, size_t len, const char *indent,
                            size_t indent_len)
{
    if (len == 0)
        return;
    const char *end = text + len;
    for (;;) {
        const char *nl = memchr(text, '\n', (size_t)(end - text));
        const char *line_end = nl ? nl : end;
        if (line_end > text)
            scg_text_append_n(out, indent, indent_len);
        scg_text_append_n(out, text, (size_t)(line_end - text));
        scg_text_append(out, "\n");
        if (!nl)
            return;
        text = nl + 1;
    }
}

static int find_slot(const scg_slot *slots, int nslots, const char *name, size_t len)
{
    for (int i = 0; i < nslots; i++)
        if (strlen(slots[i].name) == len && !memcmp(slots[i].name, name, len))
            return i;
    return -1;
}

/* Parses "{{NAME}}" at s; returns the slot index and sets *after past it. */
static int parse_slot(const char *s, const char *line_end, const scg_slot *slots, int nslots,
                      const char *template_name, int line_no, const char **after, sc_error *err)
{
    const char *name = s + 2, *p = name;
    while (p < line_end && (isupper((unsigned char)*p) || isdigit((unsigned char)*p) || *p == '_'))
        p++;
    if (p == name || p + 1 >= line_end || p[0] != '}' || p[1] != '}') {
        sc_fail(err, template_name, line_no, "malformed slot (want {{NAME}} in capitals)");
        return -1;
    }
    int slot = find_slot(slots, nslots, name, (size_t)(p - name));
    if (slot < 0) {
        sc_fail(err, template_name, line_no, "slot {{%.*s}} is not filled by the emitter",
                (int)(p - name), name);
        return -1;
    }
    *after = p + 2;
    return slot;
}

int scg_template_fill(scg_text *out, const char *template_name, const char *template_text,
                      const scg_slot *slots, int nslots, sc_error *err)
{
    char *used = sc_alloc((size_t)(nslots > 0 ? nslots : 1), 1);
    int status = SC_OK, line_no = 0;
    const char *s = template_text;
    while (*s && status == SC_OK) {
        line_no++;
        const char *nl = strchr(s, '\n');
        const char *line_end = nl ? nl : s + strlen(s);
        const char *body = s;
        while (body < line_end && (*body == ' ' || *body == '\t'))
            body++;
        const char *after = NULL;
        if (line_end - body >= 4 && body[0] == '{' && body[1] == '{') {
            int slot = parse_slot(body, line_end, slots, nslots, template_name, line_no, &after,
                                  err);
            if (slot < 0) {
                status = SC_FAIL;
                break;
            }
            const char *rest = after;
            while (rest < line_end && (*rest == ' ' || *rest == '\t'))
                rest++;
            if (rest == line_end) {
                used[slot] = 1;
                append_indented(out, slots[slot].text, without_final_newline(slots[slot].text), s,
                                (size_t)(body - s));
                s = nl ? nl + 1 : line_end;
                continue;
            }
        }
        /* Slots inside a line are replaced in place. */
        const char *p = s;
        while (p < line_end) {
            const char *open = strstr(p, "{{");
            if (!open || open >= line_end) {
                scg_text_append_n(out, p, (size_t)(line_end - p));
                break;
            }
            scg_text_append_n(out, p, (size_t)(open - p));
            int slot = parse_slot(open, line_end, slots, nslots, template_name, line_no, &after,
                                  err);
            if (slot < 0) {
                status = SC_FAIL;
                break;
            }
            used[slot] = 1;
            scg_text_append_n(out, slots[slot].text, without_final_newline(slots[slot].text));
            p = after;
        }
        if (nl)
            scg_text_append(out, "\n");
        s = nl ? nl + 1 : line_end;
    }
    for (int i = 0; i < nslots && status == SC_OK; i++)
        if (!used[i])
            status = sc_fail(err, template_name, 0, "template has no slot {{%s}}", slots[i].name);
    free(used);
    return status;
}

int scg_template_expand(scg_text *out, const char *template_name, const scg_slot *slots,
                        int nslots, sc_error *err)
{
    const char *text = scg_template_get(template_name, err);
    if (!text)
        return SC_FAIL;
    return scg_template_fill(out, template_name, text, slots, nslots, err);
}
