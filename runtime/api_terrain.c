/* api_terrain.c — the public interface's terrains (splinecast.h): scenes
 * of triangular quartic patches made from a grid of heights or from
 * Franke's function, the scheme names, and the Table I error measure
 * (docs/splines.md). */
#include "api_private.h"

#include "splines.h"
#include "terrain_scene.h"

_Static_assert(SC_SCHEME_C0 == SC_SPLINE_C0 + 1 && SC_SCHEME_C1 == SC_SPLINE_C1 + 1 &&
                   SC_SCHEME_C2 == SC_SPLINE_C2 + 1 && SC_SCHEME_LINEAR == SC_SPLINE_LINEAR + 1,
               "public schemes are the terrain library's, shifted by the default");

/* The terrain library's scheme of a public one (default: c2). */
static sc_spline_scheme spline_scheme(sc_terrain_scheme s)
{
    return s == SC_SCHEME_DEFAULT ? SC_SPLINE_C2 : (sc_spline_scheme)(s - 1);
}

const char *sc_terrain_scheme_name(sc_terrain_scheme scheme)
{
    if ((unsigned)scheme > SC_SCHEME_LINEAR)
        return "?";
    return sc_spline_scheme_name(spline_scheme(scheme));
}

int sc_parse_terrain_scheme(const char *name, sc_terrain_scheme *out, sc_error *err)
{
    sc_spline_scheme s;
    if (!name || sc_spline_scheme_parse(name, &s) != SC_OK)
        return sc_fail(err, NULL, 0, "unknown spline scheme '%s' (c0, c1, c2 or linear)",
                       name ? name : "(null)");
    *out = (sc_terrain_scheme)(s + 1);
    return SC_OK;
}

int sc_api_make_terrain(const sc_scene_desc *d, sc_scene *out, sc_error *err)
{
    if (sc_api_check_enum(d->scheme, SC_SCHEME_LINEAR + 1, "sc_scene_desc.scheme", err))
        return SC_FAIL;
    if (!(d->spacing >= 0 && d->spacing < 1e30) || !(fabs(d->height_scale) < 1e30))
        return sc_api_invalid(err, "sc_scene_desc.spacing or height_scale", PROBLEM_RANGE,
                              "%g, %g", d->spacing, d->height_scale);
    sc_spline_scheme scheme = spline_scheme(d->scheme);
    sc_heights h;
    char name[256];
    if (d->franke) {
        if (sc_spline_franke_heights(scheme, d->franke, &h, err) != SC_OK)
            return SC_FAIL;
        snprintf(name, sizeof name, "franke-%d-%s", d->franke, sc_spline_scheme_name(scheme));
    } else {
        double scale = d->height_scale != 0 ? d->height_scale : 1;
        if (sc_heights_read(d->heights, 1, scale, &h, err) != SC_OK)
            return SC_FAIL;
        int longer = h.nx > h.ny ? h.nx : h.ny;
        h.dx = h.dy = d->spacing > 0 ? d->spacing : 1.0 / (longer - 1);
        snprintf(name, sizeof name, "%s", d->heights);
    }
    sc_tri_mesh mesh;
    int status = sc_spline_build(&h, scheme, &mesh, err);
    sc_heights_free(&h);
    if (status != SC_OK) {
        /* the building step knows no file: the error names the input */
        if (err && !err->file[0] && !d->franke)
            snprintf(err->file, sizeof err->file, "%s", name);
        return SC_FAIL;
    }
    sc_terrain_scene(&mesh, name, out);
    return SC_OK;
}

int sc_terrain_patch_count(const sc_scene *scene) { return scene->terrain->count; }
int sc_terrain_degree(const sc_scene *scene) { return scene->terrain->degree; }

int sc_measure_spline_error(const sc_spline_error_desc *desc, sc_spline_error_info *out,
                            sc_error *err)
{
    if (!desc)
        return sc_api_invalid(err, "desc", PROBLEM_NULL, NULL);
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    if (sc_api_check_enum(desc->scheme, SC_SCHEME_LINEAR + 1, "sc_spline_error_desc.scheme",
                          err) ||
        sc_api_check_int(desc->sites, 0, 100000000, "sc_spline_error_desc.sites", err))
        return SC_FAIL;
    sc_spline_scheme scheme = spline_scheme(desc->scheme);
    sc_spline_error e;
    if (sc_spline_franke_error(scheme, desc->points, desc->sites ? desc->sites : 1000000, &e,
                               err) != SC_OK)
        return SC_FAIL;
    memset(out, 0, sizeof *out);
    out->points = e.points;
    out->patches = e.patches;
    out->rel_rms = e.rel_rms;
    out->rel_max = e.rel_max;
    snprintf(out->line, sizeof out->line, "splines scheme=%s points=%d patches=%d rel_rms=%.3g "
             "rel_max=%.3g", sc_spline_scheme_name(scheme), e.points, e.patches, e.rel_rms,
             e.rel_max);
    return SC_OK;
}
