/* test_key.c — variant keys: the canonical text form, exact round trips,
 * refusal of non-canonical and malformed text with the canonical spelling,
 * and refusal of reserved values. */
#include <stdlib.h>

#include "io.h"
#include "ir.h"
#include "key.h"
#include "scene_keys.h"
#include "test.h"

TEST(key_default_text)
{
    scg_key k;
    char buf[SCG_KEY_MAX];
    scg_key_default(&k, SCG_PATCH_BEZIER, 3, 3);
    CHECK_STR(scg_key_format(&k, buf, sizeof buf),
              "bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade");
    scg_key back;
    sc_error err;
    CHECK_INT(scg_key_parse(buf, &back, &err), SC_OK);
    CHECK(scg_key_equal(&k, &back));
    CHECK_INT(scg_key_check(&k, &err), SC_OK);
}

/* Random keys over every field: parse(format(k)) == k and the text is
 * stable through a second round. */
TEST(key_roundtrip_random)
{
    unsigned long long rng = 99;
    for (int n = 0; n < 2000; n++) {
        scg_key k;
        scg_key_default(&k, (scg_patch_kind)(test_rand(&rng) * 3),
                        1 + (int)(test_rand(&rng) * SCG_MAX_DEGREE),
                        1 + (int)(test_rand(&rng) * SCG_MAX_DEGREE));
        k.rational = test_rand(&rng) < 0.5;
        k.eval = (scg_eval_form)(test_rand(&rng) * 3);
        if (k.eval == SCG_EVAL_LOOP)
            k.deg_u = k.deg_v = 0;
        else if (k.kind == SCG_PATCH_TRIANGLE)   /* one total degree, 1 … 4 */
            k.deg_u = k.deg_v = 1 + k.deg_u % SCG_MAX_TRI_DEGREE;
        k.trim = (sc_trim_method)(SC_TRIM_FAST + (int)(test_rand(&rng) * 4));
        bool trimmed = k.trim != SC_TRIM_NONE;
        k.trim_degree = trimmed ? 1 + (int)(test_rand(&rng) * SCG_MAX_DEGREE) : 0;
        k.trim_iters = trimmed ? 1 + (int)(test_rand(&rng) * SCG_MAX_TRIM_ITERS) : 0;
        k.method = (sc_method)(SC_METHOD_NEWTON + (int)(test_rand(&rng) * 5));
        k.start = (sc_start)(SC_START_MID + (int)(test_rand(&rng) * 4));
        k.max_iters = 1 + (int)(test_rand(&rng) * SCG_MAX_ITERS);
        k.tol_milli = 1 + (int)(test_rand(&rng) * 1000000);
        k.ert = (scg_ert)(test_rand(&rng) * 3);
        k.outputs = 1 + (unsigned)(test_rand(&rng) * SCG_OUTPUT_ALL);
        char text[SCG_KEY_MAX], again[SCG_KEY_MAX];
        scg_key_format(&k, text, sizeof text);
        scg_key back;
        sc_error err;
        CHECK_INT(scg_key_parse(text, &back, &err), SC_OK);
        CHECK(scg_key_equal(&k, &back));
        CHECK_STR(scg_key_format(&back, again, sizeof again), text);
        for (const char *c = text; *c; c++)
            CHECK(strchr("abcdefghijklmnopqrstuvwxyz0123456789._-", *c) != NULL);
    }
}

TEST(key_tolerance_exact)
{
    static const struct { const char *text; int milli; } cases[] = {
        {"0.001", 1}, {"0.01", 10}, {"0.1", 100}, {"0.25", 250}, {"1", 1000},
        {"1.5", 1500}, {"2.125", 2125}, {"1000", 1000000}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[SCG_KEY_MAX];
        snprintf(text, sizeof text, "nurbs5x6-rat-dc-trim0-newton-cp-it16-tol%s-ert2-out.shade.aov",
                 cases[i].text);
        scg_key k;
        sc_error err;
        CHECK_INT(scg_key_parse(text, &k, &err), SC_OK);
        CHECK_INT(k.tol_milli, cases[i].milli);
        CHECK_INT(k.deg_u, 5);
        CHECK_INT(k.deg_v, 6);
        CHECK_INT(k.outputs, SCG_OUTPUT_SHADE | SCG_OUTPUT_AOV);
    }
}

TEST(key_noncanonical_refused)
{
    static const struct { const char *text, *canonical; } cases[] = {
        {"bez3x3-poly-dc-trim0-newton-mid-it4-tol0.250-ert0-out.shade", "'tol0.25'"},
        {"bez3x3-poly-dc-trim0-newton-mid-it04-tol0.25-ert0-out.shade", "'it4'"},
        {"bez03x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade", "'bez3x3'"},
        {"bez3x3-poly-dc-trim0-newton-mid-it4-tol1.0-ert0-out.shade", "'tol1'"},
        {"bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.aov.shade", "'out.shade.aov'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        scg_key k;
        sc_error err;
        CHECK_INT(scg_key_parse(cases[i].text, &k, &err), SC_FAIL);
        CHECK_CONTAINS(err.message, "not canonical");
        CHECK_CONTAINS(err.message, cases[i].canonical);
        CHECK_STR(err.key, cases[i].text);
    }
}

TEST(key_malformed_refused)
{
    static const struct { const char *text, *says; } cases[] = {
        {"", "expected"},
        {"bez3x3-poly", "fields"},
        {"Bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade", "character 'B'"},
        {"bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade-x", "too many"},
        {"bez17x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade", "degrees from 1 to 16"},
        {"bez3x3-half-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade", "poly or rat"},
        {"bez3x3-poly-dc-trim0-secant-mid-it4-tol0.25-ert0-out.shade", "method"},
        {"bez3x3-poly-dc-trim0-newton-mid-it0-tol0.25-ert0-out.shade", "from 1 to 64"},
        {"bez3x3-poly-dc-trim0-newton-mid-it4-tol0-ert0-out.shade", "tolerance"},
        {"bez3x3-poly-dc-trim0-newton-mid-it4-tol0.0005-ert0-out.shade", "at most 3 decimals"},
        /* Just above the range, in the whole part and in the fraction. */
        {"bez3x3-poly-dc-trim0-newton-mid-it4-tol1001-ert0-out.shade", "0.001 to 1000"},
        {"bez3x3-poly-dc-trim0-newton-mid-it4-tol1000.001-ert0-out.shade", "0.001 to 1000"},
        {"bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert6-out.shade", "ert0, ert1, ert2, ert3, ert4 or ert5"},
        {"bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.", "outputs"},
        {"bez3x3-poly-loop-trim0-newton-cp-it6-tol0.05-ert0-out.shade", "dyn"},
        {"bezdyn-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade", "dyn"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        scg_key k;
        sc_error err;
        CHECK_INT(scg_key_parse(cases[i].text, &k, &err), SC_FAIL);
        CHECK_CONTAINS(err.message, cases[i].says);
    }
}

/* The methods that subdivide need the record's Bézier points unrolled, and
 * subdivision spells its (unused) start one way only, so that no two keys
 * name the same program; Broyden takes every form. */
TEST(key_method_combinations)
{
    static const struct { const char *text, *says; } refused[] = {
        {"bez3x3-poly-dc-trim0-subdiv-cp-it24-tol0.05-ert0-out.shade", "write 'mid'"},
        {"bezdyn-poly-loop-trim0-subdiv-mid-it24-tol0.05-ert0-out.shade", "unrolled Bézier"},
        {"nurbs3x3-poly-dc-trim0-subdiv-mid-it24-tol0.05-ert0-out.shade", "unrolled Bézier"},
        {"bez3x3-poly-dc-trim0-bclip-cp-it32-tol0.05-ert0-out.shade", "write 'mid'"},
        {"nurbs3x3-poly-dc-trim0-bclip-mid-it32-tol0.05-ert0-out.shade", "unrolled Bézier"},
        {"nurbs3x3-poly-pow-trim0-newton-cp-it6-tol0.05-ert0-out.shade", "for Bézier keys"},
        {"bez7x3-poly-pow-trim0-newton-cp-it6-tol0.05-ert0-out.shade", "up to degree 6"},
        {"bez3x3-poly-pow-trim0-hybrid-cp-it6-tol0.05-ert5-out.shade", "write 'mid'"},
        {"bez3x3-poly-dc-trim0-newton-mid-it6-tol0.05-ert5-out.shade.hull", "hull view"},
        {"tri4-poly-dc-trim0-newton-secure-it6-tol0.05-ert5-out.shade", "Manhattan sets"},
    };
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        scg_key k;
        sc_error err;
        CHECK_INT(scg_key_parse(refused[i].text, &k, &err), SC_OK);
        CHECK_INT(scg_key_check(&k, &err), SC_FAIL);
        CHECK_CONTAINS(err.message, refused[i].says);
        CHECK_STR(err.key, refused[i].text);
    }
    static const char *const built[] = {
        "bez3x3-poly-dc-trim0-subdiv-mid-it24-tol0.05-ert1-out.shade.aov",
        "bez2x4-rat-bern-fast2i16-subdiv-mid-it8-tol0.05-ert2-out.shade",
        "bez3x3-poly-dc-trim0-broyden-cp-it6-tol0.05-ert1-out.shade.aov",
        "nurbsdyn-rat-loop-clip3i16-broyden-mid-it6-tol0.05-ert0-out.shade",
        "bez3x3-poly-dc-trim0-bclip-mid-it32-tol0.05-ert1-out.shade.aov",
        "nurbs3x3-rat-dc-trim0-hybrid-cp-it6-tol0.05-ert1-out.shade.aov",
        "bez6x1-rat-pow-clip3i16-hybrid-view-it6-tol0.05-ert4-out.shade.aov",
        "bez2x3-poly-pow-trim0-bclip-mid-it32-tol0.05-ert1-out.shade",
        "bez3x3-poly-pow-trim0-hybrid-mid-it6-tol0.05-ert5-out.shade.aov",
        "nurbsdyn-rat-loop-fast2i16-newton-mid-it6-tol0.05-ert5-out.shade.iters",
    };
    for (size_t i = 0; i < sizeof built / sizeof built[0]; i++) {
        scg_key k;
        sc_error err;
        scg_program *prog = NULL;
        CHECK_INT(scg_key_parse(built[i], &k, &err), SC_OK);
        CHECK_INT(scg_build_program(&k, &prog, &err), SC_OK);
        scg_program_free(prog);
    }
}

/* Reserved values parse (the form is stable) but cannot be built yet. */
TEST(key_reserved_refused)
{
    static const struct { const char *text, *says; } cases[] = {
        {"nurbs3x3-poly-bern-trim0-newton-mid-it4-tol0.25-ert0-out.shade", "basis form for NURBS"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        scg_key k;
        sc_error err;
        CHECK_INT(scg_key_parse(cases[i].text, &k, &err), SC_OK);
        CHECK_INT(scg_key_check(&k, &err), SC_FAIL);
        CHECK_CONTAINS(err.message, "not implemented yet");
        CHECK_CONTAINS(err.message, cases[i].says);
        /* The error record names the key; the text names it once. */
        CHECK_STR(err.key, cases[i].text);
        char text[1024];
        const char *shown = sc_error_text(&err, text, sizeof text);
        const char *first = strstr(shown, cases[i].text);
        CHECK(first != NULL && strstr(first + 1, cases[i].text) == NULL);
    }
}

/* Distinct sorted keys: duplicates collapse, rational and degree split,
 * high degrees go generic, NURBS stays Bézier unless asked. */
TEST(key_scene_keys)
{
    sc_scene scene;
    sc_scene_init(&scene);
    static const int shapes[][5] = {
        /* deg_u, deg_v, nu, nv, rational */
        {3, 3, 4, 4, 0}, {3, 3, 4, 4, 0}, {3, 3, 7, 4, 0}, {2, 2, 3, 3, 1}, {12, 12, 13, 13, 0}};
    for (size_t i = 0; i < sizeof shapes / sizeof shapes[0]; i++) {
        sc_surface *s = sc_scene_add_surface(&scene);
        sc_surface_alloc(s, shapes[i][0], shapes[i][1], shapes[i][2], shapes[i][3]);
        s->rational = shapes[i][4];
    }
    char (*keys)[SCG_KEY_MAX];
    int count;
    sc_error err;
    CHECK_INT(sc_scene_keys(&scene, NULL, &keys, &count, &err), SC_OK);
    CHECK_INT(count, 3);
    CHECK_STR(keys[0], "bez2x2-rat-pow-trim0-hybrid-cp-it6-tol0.05-ert1-out.shade.aov");
    CHECK_STR(keys[1], "bez3x3-poly-pow-trim0-hybrid-cp-it6-tol0.05-ert1-out.shade.aov");
    CHECK_STR(keys[2], "bezdyn-poly-loop-trim0-hybrid-cp-it6-tol0.05-ert1-out.shade.aov");
    free(keys);
    sc_key_options opts;
    memset(&opts, 0, sizeof opts);
    opts.nurbs_direct = 1;
    opts.max_iters = 8;
    opts.generic_above = 12;
    CHECK_INT(sc_scene_keys(&scene, &opts, &keys, &count, &err), SC_OK);
    CHECK_INT(count, 4);
    CHECK_STR(keys[0], "bez12x12-poly-dc-trim0-hybrid-cp-it8-tol0.05-ert1-out.shade.aov");
    CHECK_STR(keys[3], "nurbs3x3-poly-dc-trim0-hybrid-cp-it8-tol0.05-ert1-out.shade.aov");
    free(keys);
    sc_scene_free(&scene);
}

/* The evaluation form of unrolled Bézier keys: the power form by default
 * up to SC_DEFAULT_POW_MAX_DEGREE and de Casteljau above; asked for, each
 * form, the power form up to SC_MAX_POW_DEGREE; NURBS and generic keys
 * keep theirs. */
TEST(key_scene_keys_evaluation_form)
{
    static const struct { int p, q, nu; sc_eval asked; int nurbs; const char *form; } cases[] = {
        {3, 3, 4, SC_EVAL_DEFAULT, 0, "pow"},   {4, 2, 5, SC_EVAL_DEFAULT, 0, "pow"},
        {5, 3, 6, SC_EVAL_DEFAULT, 0, "dc"},    {3, 3, 4, SC_EVAL_DC, 0, "dc"},
        {3, 3, 4, SC_EVAL_BERN, 0, "bern"},     {6, 6, 7, SC_EVAL_POW, 0, "pow"},
        {7, 2, 8, SC_EVAL_POW, 0, "dc"},        {3, 3, 7, SC_EVAL_DEFAULT, 1, "dc"},
        {12, 12, 13, SC_EVAL_POW, 0, "loop"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        sc_surface s;
        memset(&s, 0, sizeof s);
        sc_surface_alloc(&s, cases[i].p, cases[i].q, cases[i].nu, cases[i].q + 1);
        sc_key_options opts;
        memset(&opts, 0, sizeof opts);
        opts.eval = cases[i].asked;
        opts.nurbs_direct = cases[i].nurbs;
        scg_key key;
        sc_surface_key(&s, &opts, &key);
        char text[SCG_KEY_MAX], form[16] = "";
        sscanf(scg_key_format(&key, text, sizeof text), "%*[^-]-%*[^-]-%15[^-]", form);
        if (strcmp(form, cases[i].form) != 0)
            TEST_FAIL_("case %zu: %s, expected the form %s", i, text, cases[i].form);
        sc_error err;
        CHECK_INT(scg_key_check(&key, &err), SC_OK);
        sc_surface_free(&s);
    }
}

/* Surfaces the GPU programs cannot draw: degree 17 in one direction (the
 * scene model takes any degree), and a trim curve of degree 17 in a scene
 * built in code (readers drop such loops). By default the scene's keys
 * fail naming the first; skipping them leaves the drawable surface's key
 * and one warning each. The trim degree is never clamped into a key. */
TEST(key_scene_keys_undrawable_surfaces)
{
    sc_scene scene;
    sc_scene_init(&scene);
    snprintf(scene.source, sizeof scene.source, "parts.obj");
    static const int shapes[][4] = {{2, 2, 3, 3}, {17, 1, 18, 2}, {3, 3, 4, 4}};
    for (int i = 0; i < 3; i++) {
        sc_surface *s = sc_scene_add_surface(&scene);
        sc_surface_alloc(s, shapes[i][0], shapes[i][1], shapes[i][2], shapes[i][3]);
        snprintf(s->name, sizeof s->name, "part%d", i);
    }
    sc_surface *trimmed = &scene.surfaces[2];
    trimmed->nloops = 1;
    trimmed->loops = sc_alloc(1, sizeof(sc_loop));
    trimmed->loops[0].ncurves = 1;
    trimmed->loops[0].curves = sc_alloc(1, sizeof(sc_curve));
    sc_curve_alloc(&trimmed->loops[0].curves[0], 2, 17, 18);
    sc_error err = {0};
    CHECK_INT(sc_surface_drawable(&scene, 0, &err), SC_OK);
    CHECK_INT(sc_surface_drawable(&scene, 2, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "surface 2 (part2): a trim curve of degree 17 is above 16");
    scg_key key;
    sc_surface_key(trimmed, NULL, &key);
    CHECK_INT(key.trim_degree, 17);
    CHECK_INT(scg_key_check(&key, &err), SC_FAIL);

    char (*keys)[SCG_KEY_MAX] = NULL;
    int count = -1;
    memset(&err, 0, sizeof err);
    CHECK_INT(sc_scene_keys(&scene, NULL, &keys, &count, &err), SC_FAIL);
    CHECK(keys == NULL);
    CHECK_INT(count, 0);
    CHECK_STR(err.file, "parts.obj");
    CHECK_CONTAINS(err.message, "surface 1 (part1): degree 17×1 is above 16");

    sc_key_options opts;
    memset(&opts, 0, sizeof opts);
    opts.skip_undrawable = 1;
    test_warnings w;
    memset(&w, 0, sizeof w);
    sc_set_logger(test_gather_warnings, &w);
    int status = sc_scene_keys(&scene, &opts, &keys, &count, &err);
    sc_set_logger(NULL, NULL);
    CHECK_INT(status, SC_OK);
    CHECK_INT(count, 1);
    CHECK_STR(keys[0], "bez2x2-poly-pow-trim0-hybrid-cp-it6-tol0.05-ert1-out.shade.aov");
    free(keys);
    CHECK_INT(w.count, 2);
    CHECK_CONTAINS(w.text, "parts.obj: surface 1 (part1): degree 17×1 is above 16");
    CHECK_CONTAINS(w.text, "parts.obj: surface 2 (part2): a trim curve of degree 17");
    sc_scene_free(&scene);
}

/* The embedded teapot: 32 bicubic polynomial patches, one key. */
TEST(key_scene_keys_teapot)
{
    sc_scene scene;
    sc_error err;
    sc_scene_init(&scene);
    if (sc_read_scene("teapot", &scene, &err) != SC_OK)
        SKIP("teapot not readable: %s", err.message);
    char (*keys)[SCG_KEY_MAX];
    int count;
    CHECK_INT(sc_scene_keys(&scene, NULL, &keys, &count, &err), SC_OK);
    CHECK_INT(count, 1);
    CHECK_STR(keys[0], "bez3x3-poly-pow-trim0-hybrid-cp-it6-tol0.05-ert1-out.shade.aov");
    free(keys);
    sc_scene_free(&scene);
}
