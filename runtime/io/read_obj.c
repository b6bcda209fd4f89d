/* read_obj.c — the free-form part of Wavefront OBJ (Advanced Visualizer
 * manual, appendix B1): rational and polynomial Bézier and B-spline
 * surfaces (`surf`) with trimming loops and holes built from 2D curves
 * (`curv2`, `trim`, `hole`), names from `o`/`g`, colours from `usemtl` and
 * the Kd of a .mtl beside the file. Polygons, space curves, special curves
 * and points are counted as skipped. Conventions verified against the spec
 * are in docs/formats.md: x y z of `v` are Euclidean with the weight beside
 * them, control points run u fastest, Bézier `parm` values are segment
 * break points ((K / deg) + 1 of them for K + 1 control points).
 *
 * Every surface and curve is brought to the scene model's clamped form on
 * read: its domain ends inserted to multiplicity deg and the control points
 * outside dropped (sc_curve_clamp / sc_surface_clamp), then a surf range
 * smaller than the domain cut out by splitting (one wider is cut to the
 * domain, with a warning).
 *
 * This file reads statements into the reader's state (read_obj.h);
 * read_obj_element.c assembles each finished curv2 and surf. */
#include "io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "read_obj.h"

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

/* ---- logical lines: comments stripped, backslash continuations joined,
 * split into tokens; r->line is the first physical line. ---- */

static int buf_append(obj_reader *r, const char *s, size_t n, size_t *len)
{
    if (*len + n + 2 > r->buf_cap) {
        size_t cap = r->buf_cap;
        while (*len + n + 2 > cap)
            cap = cap ? 2 * cap : 256;
        char *grown = sc_try_realloc(r->buf, cap, 1);
        if (!grown)
            return sc_fail_oom(r->err, r->name, r->line, cap, 1, "a statement");
        r->buf = grown;
        r->buf_cap = cap;
    }
    memcpy(r->buf + *len, s, n);
    *len += n;
    r->buf[(*len)++] = ' ';
    r->buf[*len] = 0;
    return SC_OK;
}

/* 1: a statement was read; 0: the end; -1: out of memory (r->err set). */
static int next_statement(obj_reader *r)
{
    while (r->pos < r->end) {
        r->line = r->next_line;
        size_t len = 0;
        if (r->buf)
            r->buf[0] = 0;
        for (;;) {
            const char *eol = memchr(r->pos, '\n', (size_t)(r->end - r->pos));
            if (!eol)
                eol = r->end;
            const char *stop = memchr(r->pos, '#', (size_t)(eol - r->pos));
            if (!stop)
                stop = eol;
            while (stop > r->pos && is_space(stop[-1]))
                stop--;
            int more = stop > r->pos && stop[-1] == '\\';
            if (more)
                stop--;
            if (buf_append(r, r->pos, (size_t)(stop - r->pos), &len))
                return -1;
            r->pos = eol < r->end ? eol + 1 : r->end;
            r->next_line++;
            if (!more || r->pos >= r->end)
                break;
        }
        r->ntok = 0;
        for (char *p = r->buf; *p;) {
            while (*p && is_space(*p))
                p++;
            if (!*p)
                break;
            if (r->ntok == r->tok_cap) {
                int cap = r->tok_cap ? 2 * r->tok_cap : 32;
                char **grown = sc_try_realloc(r->tok, (size_t)cap, sizeof *r->tok);
                if (!grown)
                    return sc_fail_oom(r->err, r->name, r->line, (size_t)cap, sizeof *r->tok,
                                       "the words of a statement"), -1;
                r->tok = grown;
                r->tok_cap = cap;
            }
            r->tok[r->ntok++] = p;
            while (*p && !is_space(*p))
                p++;
            if (*p)
                *p++ = 0;
        }
        if (r->ntok)
            return 1;
    }
    return 0;
}

/* ---- numbers ---- */

static int parse_double(obj_reader *r, const char *tok, const char *what, double *out)
{
    char *endp;
    double v = strtod(tok, &endp);
    if (endp == tok || *endp)
        return fail(r, r->line, "%s: expected a number, found '%.40s'", what, tok);
    if (!isfinite(v))
        return fail(r, r->line, "%s: '%.40s' is not a finite number", what, tok);
    *out = v;
    return SC_OK;
}

static int parse_int(obj_reader *r, const char *tok, const char *what, long lo, long hi, long *out)
{
    char *endp;
    long v = strtol(tok, &endp, 10);
    if (endp == tok || *endp)
        return fail(r, r->line, "%s: expected a whole number, found '%.40s'", what, tok);
    if (v < lo || v > hi)
        return fail(r, r->line, "%s %ld is out of range (%ld to %ld)", what, v, lo, hi);
    *out = v;
    return SC_OK;
}

/* OBJ reference numbers: 1-based, or negative counting back from the last
 * one defined so far. `tok` may carry /vt/vn suffixes, which are ignored. */
static int parse_ref(obj_reader *r, const char *tok, int count, const char *what, int *out)
{
    char *endp;
    long v = strtol(tok, &endp, 10);
    if (endp == tok || (*endp && *endp != '/'))
        return fail(r, r->line, "expected a %s reference number, found '%.40s'", what, tok);
    long index = v > 0 ? v - 1 : count + v;
    if (v == 0 || index < 0 || index >= count)
        return fail(r, r->line, "%s reference %ld is out of range (%d defined so far)", what, v,
                    count);
    *out = (int)index;
    return SC_OK;
}

/* ---- vertex data ---- */

static int add_vertex(obj_reader *r, obj_vertex_list *list, int min, int max, const char *what)
{
    int n = r->ntok - 1;
    /* Some writers append an RGB colour to `v`: x y z r g b. */
    int colour_extension = list == &r->verts && n == 6;
    if ((n < min || n > max) && !colour_extension)
        return fail(r, r->line, "%s needs %d to %d numbers, has %d", what, min, max, n);
    if (sc_budget_charge(&r->budget, sizeof *list->v, what, r->name, r->line, r->err))
        return SC_FAIL;
    if (list->count == list->cap) {
        int cap = list->cap ? 2 * list->cap : 64;
        obj_vertex *grown = sc_try_realloc(list->v, (size_t)cap, sizeof *list->v);
        if (!grown)
            return sc_fail_oom(r->err, r->name, r->line, (size_t)cap, sizeof *list->v,
                               "the vertex list");
        list->v = grown;
        list->cap = cap;
    }
    obj_vertex *v = &list->v[list->count];
    v->x[0] = v->x[1] = v->x[2] = 0;
    v->x[3] = 1;
    for (int i = 0; i < n; i++) {
        double x;
        if (parse_double(r, r->tok[1 + i], what, &x))
            return SC_FAIL;
        if (i < 4)
            v->x[i] = x;
    }
    if (colour_extension)
        v->x[3] = 1, n = 3;
    if (list == &r->pverts && n < 3)
        v->x[2] = 1;   /* the weight of a vp sits in the third place */
    v->ncoords = n;
    v->line = r->line;
    list->count++;
    return SC_OK;
}

/* ---- materials ---- */

static const obj_material *find_material(const obj_reader *r, const char *name)
{
    for (int i = r->nmaterials - 1; i >= 0; i--)
        if (!strcmp(r->materials[i].name, name))
            return &r->materials[i];
    return NULL;
}

static void parse_mtl(obj_reader *r, const char *text, size_t size, const char *path)
{
    obj_material *cur = NULL;
    int line = 0;
    for (const char *p = text, *end = text + size; p < end;) {
        const char *eol = memchr(p, '\n', (size_t)(end - p));
        if (!eol)
            eol = end;
        line++;
        char buf[512];
        size_t n = (size_t)(eol - p) < sizeof buf - 1 ? (size_t)(eol - p) : sizeof buf - 1;
        memcpy(buf, p, n);
        buf[n] = 0;
        p = eol < end ? eol + 1 : end;
        char *hash = strchr(buf, '#');
        if (hash)
            *hash = 0;
        char *save, *key = strtok_r(buf, " \t\r\f\v", &save);
        if (!key)
            continue;
        if (!strcmp(key, "newmtl")) {
            char *name = strtok_r(NULL, " \t\r\f\v", &save);
            if (!name) {
                sc_log(SC_LOG_WARN, "%s:%d: newmtl without a name (ignored)", path, line);
                cur = NULL;
                continue;
            }
            obj_material *grown = sc_try_realloc(r->materials, (size_t)r->nmaterials + 1,
                                                 sizeof *r->materials);
            if (!grown) {
                sc_log(SC_LOG_WARN, "%s:%d: out of memory for the materials (the rest of the "
                       "library ignored)", path, line);
                return;
            }
            r->materials = grown;
            cur = &r->materials[r->nmaterials++];
            snprintf(cur->name, sizeof cur->name, "%s", name);
            cur->kd[0] = cur->kd[1] = cur->kd[2] = 0.8f;
        } else if (!strcmp(key, "Kd") && cur) {
            double kd[3];
            int k = 0;
            char *t;
            while (k < 3 && (t = strtok_r(NULL, " \t\r\f\v", &save))) {
                char *endp;
                kd[k] = strtod(t, &endp);
                if (endp == t || *endp || !isfinite(kd[k]))
                    break;
                k++;
            }
            if (k == 1)
                kd[1] = kd[2] = kd[0];
            if (k == 1 || k == 3) {
                for (int i = 0; i < 3; i++) /* the scene's colours are in [0, 1] */
                    cur->kd[i] = (float)fmin(fmax(kd[i], 0.0), 1.0);
            } else {
                sc_log(SC_LOG_WARN, "%s:%d: Kd is not an RGB colour (ignored)", path, line);
            }
        }
    }
}

static void load_mtllib(obj_reader *r)
{
    const char *slash = strrchr(r->name, '/');
    for (int i = 1; i < r->ntok; i++) {
        char path[1024];
        if (r->tok[i][0] == '/' || !slash)
            snprintf(path, sizeof path, "%s", r->tok[i]);
        else
            snprintf(path, sizeof path, "%.*s/%s", (int)(slash - r->name), r->name, r->tok[i]);
        char *data;
        size_t size;
        sc_error e;
        /* Only colours come from it: a device or a huge file is refused. */
        if (sc_read_file_max(path, SC_MAX_MTL_BYTES, 1, &data, &size, &e)) {
            sc_log(SC_LOG_WARN, "%s:%d: material library %s: %s (default colours used)", r->name,
                   r->line, path, e.message);
            continue;
        }
        if (sc_check_text(data, size, path, &e)) {
            char text[1024];
            sc_log(SC_LOG_WARN, "%s (material library ignored)", sc_error_text(&e, text, sizeof text));
        } else {
            parse_mtl(r, data, size, path);
        }
        free(data);
    }
}

static void element_clear(obj_element *el)
{
    free(el->idx);
    free(el->parm[0]);
    free(el->parm[1]);
    for (int l = 0; l < el->nloops; l++)
        free(el->loops[l].refs);
    free(el->loops);
    memset(el, 0, sizeof *el);
}

static const char *element_name(obj_element_kind kind)
{
    return kind == EL_SURF ? "surf" : kind == EL_CURV2 ? "curv2" : "curv";
}

/* ---- statements ---- */

static int begin_element(obj_reader *r, obj_element_kind kind)
{
    obj_element *el = &r->el;
    el->kind = kind;
    el->line = r->line;
    el->cstype = r->cstype;
    el->rational = r->rational;
    el->cstype_line = r->cstype_line;
    memcpy(el->cstype_name, r->cstype_name, sizeof el->cstype_name);
    el->deg[0] = r->deg[0];
    el->deg[1] = r->deg[1];
    if (kind == EL_SPACE_CURVE) {
        r->space_curves++;
        return SC_OK;
    }
    int first = 1;
    if (kind == EL_SURF) {
        if (r->ntok < 6)
            return fail(r, r->line, "surf needs s0 s1 t0 t1 and control points");
        for (int i = 0; i < 4; i++)
            if (parse_double(r, r->tok[1 + i], "surf parameter range", &el->range[i]))
                return SC_FAIL;
        if (!(el->range[0] < el->range[1]) || !(el->range[2] < el->range[3]))
            return fail(r, r->line, "surf parameter range [%.17g, %.17g] x [%.17g, %.17g] is empty",
                        el->range[0], el->range[1], el->range[2], el->range[3]);
        first = 5;
    } else if (r->ntok < 3) {
        return fail(r, r->line, "curv2 needs at least two control points");
    }
    el->nidx = r->ntok - first;
    if (!(el->idx = sc_try_alloc((size_t)el->nidx, sizeof(int))))
        return sc_fail_oom(r->err, r->name, r->line, (size_t)el->nidx, sizeof(int),
                           "the control point list");
    obj_vertex_list *list = kind == EL_SURF ? &r->verts : &r->pverts;
    for (int i = 0; i < el->nidx; i++)
        if (parse_ref(r, r->tok[first + i], list->count,
                      kind == EL_SURF ? "vertex" : "parameter vertex", &el->idx[i]))
            return SC_FAIL;
    return SC_OK;
}

static int statement_parm(obj_reader *r)
{
    obj_element *el = &r->el;
    if (r->ntok < 4)
        return fail(r, r->line, "parm needs a direction (u or v) and at least two values");
    int dir = !strcmp(r->tok[1], "u") ? 0 : !strcmp(r->tok[1], "v") ? 1 : -1;
    if (dir < 0)
        return fail(r, r->line, "parm direction '%.20s' (must be u or v)", r->tok[1]);
    if (dir == 1 && el->kind == EL_CURV2)
        return fail(r, r->line, "parm v in a curv2 body (2D curves have only u)");
    if (el->kind == EL_SPACE_CURVE)
        return SC_OK;
    int n = r->ntok - 2;
    double *v = sc_try_alloc((size_t)n, sizeof(double));
    if (!v)
        return sc_fail_oom(r->err, r->name, r->line, (size_t)n, sizeof(double), "parm values");
    for (int i = 0; i < n; i++)
        if (parse_double(r, r->tok[2 + i], "parm value", &v[i])) {
            free(v);
            return SC_FAIL;
        }
    free(el->parm[dir]);   /* the last parm of a direction counts (spec) */
    el->parm[dir] = v;
    el->nparm[dir] = n;
    el->parm_line[dir] = r->line;
    return SC_OK;
}

static int statement_loop(obj_reader *r, int is_hole)
{
    obj_element *el = &r->el;
    const char *what = is_hole ? "hole" : "trim";
    if (el->kind != EL_SURF)
        return fail(r, r->line, "%s inside a %s body (only surfaces are trimmed)", what,
                    element_name(el->kind));
    int n = r->ntok - 1;
    if (n < 3 || n % 3)
        return fail(r, r->line, "%s needs groups of three: u0 u1 curv2d (has %d values)", what, n);
    if (n / 3 > SC_MAX_LOOP_PIECES)
        return fail(r, r->line, "%s has %d curves: more than the %d a loop may have "
                    "(docs/limits.md)", what, n / 3, SC_MAX_LOOP_PIECES);
    obj_loop_ref *grown = sc_try_realloc(el->loops, (size_t)el->nloops + 1, sizeof *el->loops);
    if (!grown)
        return sc_fail_oom(r->err, r->name, r->line, (size_t)el->nloops + 1, sizeof *el->loops,
                           "the loops of a surf");
    el->loops = grown;
    obj_loop_ref *loop = &el->loops[el->nloops++];
    loop->is_hole = is_hole;
    loop->line = r->line;
    loop->nrefs = n / 3;
    if (!(loop->refs = sc_try_alloc((size_t)loop->nrefs, sizeof *loop->refs)))
        return sc_fail_oom(r->err, r->name, r->line, (size_t)loop->nrefs, sizeof *loop->refs,
                           what);
    for (int i = 0; i < loop->nrefs; i++) {
        obj_trim_ref *ref = &loop->refs[i];
        if (parse_double(r, r->tok[1 + 3 * i], what, &ref->t0) ||
            parse_double(r, r->tok[2 + 3 * i], what, &ref->t1))
            return SC_FAIL;
        const char *tok = r->tok[3 + 3 * i];
        char *endp;
        long v = strtol(tok, &endp, 10);
        if (endp == tok || *endp)
            return fail(r, r->line, "%s: expected a curve number, found '%.40s'", what, tok);
        long index = v > 0 ? v - 1 : r->ncurves + v;
        if (v == 0 || index < 0 || index >= r->ncurves)
            return fail(r, r->line, "%s refers to curve %ld, which is not defined (%d curv2 "
                        "defined so far)", what, v, r->ncurves);
        ref->curve = (int)index;
    }
    return SC_OK;
}

static int statement_cstype(obj_reader *r)
{
    int i = 1, rational = 0;
    if (i < r->ntok && !strcmp(r->tok[i], "rat")) {
        rational = 1;
        i++;
    }
    if (i != r->ntok - 1)
        return fail(r, r->line, "cstype needs one type: [rat] bezier|bspline");
    const char *type = r->tok[i];
    obj_cstype cs;
    if (!strcmp(type, "bezier"))
        cs = CS_BEZIER;
    else if (!strcmp(type, "bspline"))
        cs = CS_BSPLINE;
    else if (!strcmp(type, "bmatrix") || !strcmp(type, "cardinal") || !strcmp(type, "taylor"))
        cs = CS_UNSUPPORTED;
    else
        return fail(r, r->line, "unknown cstype '%.20s' (bezier, bspline, bmatrix, cardinal or "
                    "taylor)", type);
    r->cstype = cs;
    r->rational = rational;
    r->cstype_line = r->line;
    snprintf(r->cstype_name, sizeof r->cstype_name, "%s", type);
    return SC_OK;
}

static int statement_deg(obj_reader *r)
{
    if (r->ntok < 2 || r->ntok > 3)
        return fail(r, r->line, "deg needs one or two degrees: deg DU [DV]");
    long d[2] = {0, 0};
    for (int i = 0; i + 1 < r->ntok; i++)
        if (parse_int(r, r->tok[1 + i], "degree", 1, SC_READ_MAX_DEGREE, &d[i]))
            return SC_FAIL;
    r->deg[0] = (int)d[0];
    r->deg[1] = (int)d[1];
    return SC_OK;
}

static void statement_name(obj_reader *r)
{
    /* o takes the rest of the line; g the first of its group names. */
    size_t len = 0;
    r->cur_name[0] = 0;
    int last = !strcmp(r->tok[0], "g") ? 1 : r->ntok - 1;
    for (int i = 1; i <= last && i < r->ntok; i++) {
        int n = snprintf(r->cur_name + len, sizeof r->cur_name - len, "%s%s", i > 1 ? " " : "",
                         r->tok[i]);
        if (n < 0 || (size_t)n >= sizeof r->cur_name - len)
            break;
        len += (size_t)n;
    }
}

static void statement_usemtl(obj_reader *r)
{
    static const float white[3] = {0.8f, 0.8f, 0.8f};
    const obj_material *m = r->ntok > 1 ? find_material(r, r->tok[1]) : NULL;
    if (!m && r->ntok > 1)
        sc_log(SC_LOG_WARN, "%s:%d: material '%s' is not defined in a material library (default "
               "colour used)", r->name, r->line, r->tok[1]);
    memcpy(r->cur_color, m ? m->kd : white, sizeof r->cur_color);
}

/* Statements that only matter to polygon renderers or to the Advanced
 * Visualizer: read past without a note. */
static int is_ignored(const char *k)
{
    static const char *const list[] = {"vt", "vn", "s", "mg", "lod", "bevel", "c_interp",
                                       "d_interp", "shadow_obj", "trace_obj", "ctech", "stech",
                                       "maplib", "usemap", "bmat", "step", "res", NULL};
    for (int i = 0; list[i]; i++)
        if (!strcmp(k, list[i]))
            return 1;
    return 0;
}

static int body_statement(obj_reader *r)
{
    const char *k = r->tok[0];
    obj_element *el = &r->el;
    if (!strcmp(k, "parm"))
        return statement_parm(r);
    if (!strcmp(k, "trim") || !strcmp(k, "hole"))
        return el->kind == EL_SPACE_CURVE ? SC_OK : statement_loop(r, k[0] == 'h');
    if (!strcmp(k, "scrv")) {
        r->special_curves++;
        return SC_OK;
    }
    if (!strcmp(k, "sp")) {
        r->special_points++;
        return SC_OK;
    }
    if (!strcmp(k, "end")) {
        int status = SC_OK;
        if (el->kind == EL_SURF)
            status = sc_obj_finish_surf(r);
        else if (el->kind == EL_CURV2)
            status = sc_obj_finish_curv2(r);
        element_clear(el);
        return status;
    }
    return fail(r, r->line, "'%.20s' inside the %s body that begins at line %d: the body needs "
                "its end statement first", k, element_name(el->kind), el->line);
}

static int statement(obj_reader *r)
{
    const char *k = r->tok[0];
    if (r->el.kind != EL_NONE)
        return body_statement(r);
    if (!strcmp(k, "v"))
        return add_vertex(r, &r->verts, 3, 4, "v");
    if (!strcmp(k, "vp"))
        return add_vertex(r, &r->pverts, 1, 3, "vp");
    if (!strcmp(k, "surf"))
        return begin_element(r, EL_SURF);
    if (!strcmp(k, "curv2"))
        return begin_element(r, EL_CURV2);
    if (!strcmp(k, "curv"))
        return begin_element(r, EL_SPACE_CURVE);
    if (!strcmp(k, "cstype"))
        return statement_cstype(r);
    if (!strcmp(k, "deg"))
        return statement_deg(r);
    if (!strcmp(k, "f") || !strcmp(k, "l") || !strcmp(k, "p") || !strcmp(k, "fo")) {
        r->polygons++;
        return SC_OK;
    }
    if (!strcmp(k, "o") || !strcmp(k, "g")) {
        statement_name(r);
        return SC_OK;
    }
    if (!strcmp(k, "usemtl")) {
        statement_usemtl(r);
        return SC_OK;
    }
    if (!strcmp(k, "mtllib")) {
        load_mtllib(r);
        return SC_OK;
    }
    if (!strcmp(k, "con")) {
        r->connections++;
        return SC_OK;
    }
    if (!strcmp(k, "csh")) {
        r->shell_commands++;
        return SC_OK;
    }
    if (!strcmp(k, "call"))
        return fail(r, r->line, "call (reading another .obj file) is not supported");
    if (!strcmp(k, "parm") || !strcmp(k, "trim") || !strcmp(k, "hole") || !strcmp(k, "scrv") ||
        !strcmp(k, "sp") || !strcmp(k, "end"))
        return fail(r, r->line, "%s outside a curv2 or surf body", k);
    if (is_ignored(k))
        return SC_OK;
    if (!r->unknown_statements++)
        sc_log(SC_LOG_WARN, "%s:%d: unknown statement '%.20s' ignored", r->name, r->line, k);
    return SC_OK;
}

static void note_skipped(obj_reader *r, int count, const char *type, const char *reason,
                         const char *what)
{
    if (!count)
        return;
    sc_scene_skip(r->scene, type, reason, count);
    sc_log(SC_LOG_WARN, "%s: %d %s ignored", r->name, count, what);
}

static int read_all(obj_reader *r)
{
    int more;
    while ((more = next_statement(r)) > 0)
        if (statement(r))
            return SC_FAIL;
    if (more < 0)
        return SC_FAIL;
    if (r->el.kind != EL_NONE)
        return fail(r, r->el.line, "the %s body that begins here has no end statement (file "
                    "truncated?)", element_name(r->el.kind));
    note_skipped(r, r->polygons, "polygon", "not-free-form", "polygonal elements (f, l, p)");
    note_skipped(r, r->space_curves, "curv", "not-a-surface", "space curves (curv)");
    note_skipped(r, r->special_curves, "scrv", "not-rendered", "special curves (scrv)");
    note_skipped(r, r->special_points, "sp", "not-rendered", "special point statements (sp)");
    note_skipped(r, r->connections, "con", "not-used", "connectivity statements (con)");
    note_skipped(r, r->shell_commands, "csh", "not-executed", "csh statements");
    note_skipped(r, r->unknown_statements, "statement", "unknown", "unknown statements");
    return SC_OK;
}

int sc_read_obj(const char *text, size_t size, const char *name, sc_scene *scene, sc_error *err)
{
    sc_scene_init(scene);
    if (sc_check_text(text, size, name, err))
        return SC_FAIL;
    obj_reader r;
    memset(&r, 0, sizeof r);
    r.name = name;
    r.err = err;
    r.scene = scene;
    r.pos = text;
    r.end = text + size;
    r.next_line = 1;
    r.cur_color[0] = r.cur_color[1] = r.cur_color[2] = 0.8f;
    int status = read_all(&r);
    element_clear(&r.el);
    free(r.buf);
    free(r.tok);
    free(r.verts.v);
    free(r.pverts.v);
    for (int i = 0; i < r.ncurves; i++)
        sc_curve_free(&r.curves[i]);
    free(r.curves);
    free(r.materials);
    return sc_finish_read(status, name, scene, err);
}
