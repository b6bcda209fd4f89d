/* test_step.c — the STEP reader: our pre-scan of the exchange structure
 * (small texts written here: what it accepts, and each malformed file's
 * "file:line: what"), and the shared STEP files read through Open CASCADE
 * (face counts from a text scan of the files, exact spheres, assembly
 * placements, colours from the files' COLOUR_RGB values, the command
 * line). Areas against Open CASCADE's own: test_step_occt.c. */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <unistd.h>

#include "io.h"
#include "nurbs.h"
#include "splinecast.h"
#include "step.h"

static const char step_head[] =
    "ISO-10303-21;\n"
    "HEADER;\n"
    "FILE_DESCRIPTION(('a test'),'2;1');\n"
    "FILE_NAME('t.stp','2024-01-01T00:00:00',('someone'),(''),'','','');\n"
    "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\n"
    "ENDSEC;\n";

/* head + body, malloc'ed */
static char *with_head(const char *body)
{
    size_t n = strlen(step_head) + strlen(body) + 1;
    char *t = malloc(n);
    snprintf(t, n, "%s%s", step_head, body);
    return t;
}

static int scan(const char *text, sc_step_scan *s, sc_error *err)
{
    memset(err, 0, sizeof *err);
    return sc_step_scan_text(text, strlen(text), "t.stp", s, err);
}

TEST(step_scan_accepts_exchange_structure)
{
    char *t = with_head(
        "DATA;\n"
        "/* a comment; with ( and ' inside */\n"
        "#10 = CARTESIAN_POINT('it''s (here)', (0., 1.5E-3, -.5));\n"
        "#20=DIRECTION('',(0.,0.,1.));\n"
        "#30 = ( BOUNDED_SURFACE() B_SPLINE_SURFACE(1,1,((#10,#10),(#10,#10)),\n"
        "  .UNSPECIFIED.,.F.,.F.,.F.) RATIONAL_B_SPLINE_SURFACE(((1.,1.),(1.,1.))) );\n"
        "#40 = ADVANCED_FACE('',(),#30,.T.);\n"
        "#41 = FACE_SURFACE('', (), #30, .F.);\n"
        "#50 = DESCRIPTIVE_REPRESENTATION_ITEM('x', $, *, \"0FF\", LENGTH_MEASURE(2.));\n"
        "ENDSEC;\n"
        "END-ISO-10303-21;\n");
    sc_step_scan s;
    sc_error err;
    int status = scan(t, &s, &err);
    if (status)
        fprintf(stderr, "  %s:%d: %s\n", err.file, err.line, err.message);
    CHECK_INT(status, SC_OK);
    CHECK_INT(s.ninstances, 6);
    CHECK_INT(s.faces, 2);
    /* lines counted in the text above: the head has 6 */
    CHECK_INT(sc_step_line_of(&s, 10), 9);
    CHECK_INT(sc_step_line_of(&s, 30), 11);
    CHECK_INT(sc_step_line_of(&s, 50), 15);
    CHECK_INT(sc_step_line_of(&s, 11), 0);
    sc_step_scan_free(&s);
    free(t);
}

typedef struct bad_case {
    const char *body;     /* after the head (NULL: `whole` is the file) */
    const char *whole;
    int line;
    const char *what;
} bad_case;

TEST(step_scan_refuses_malformed_files)
{
    static const bad_case cases[] = {
        {NULL, "", 1, "must begin with `ISO-10303-21;`"},
        {NULL, "ISO-10303-22;\n", 1, "must begin with `ISO-10303-21;`"},
        {NULL, "ISO-10303-21;\nDATA;\n", 2, "expected `HEADER;`"},
        {NULL, "ISO-10303-21;\nHEADER;\nFILE_NAME('a');\n", 4, "never closed by `ENDSEC;`"},
        {"DATA;\n#1=A(1);\nENDSEC;\n", NULL, 10, "without `END-ISO-10303-21;`"},
        {"DATA;\n#1=A(1);\n", NULL, 9, "DATA section is never closed"},
        {"DATA;\n#1=A(1,(2,3);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "`;` before its last `)`"},
        {"DATA;\n#1=A('abc);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "string is never closed"},
        {"DATA;\n#1=A(1);\n#1=B(2);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 9,
         "#1 is defined twice (also on line 8)"},
        {"DATA;\n#1=A(1);\n#2=B(\n#7);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 10,
         "reference to #7, which the file does not define"},
        {"DATA;\n#1=A(1)\n#2=B(2);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 9,
         "expected `;` at the end of the instance"},
        {"DATA;\n#0=A(1);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "instance number 0"},
        {"DATA;\n#99999999999=A(1);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8,
         "instance number too large"},
        {"DATA;\n#1=A(.T);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "enumeration value"},
        {"DATA;\n#1=A(\"0G\");\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "binary value"},
        {"DATA;\n#1=A(1);\n/* open\nENDSEC;\n", NULL, 9, "comment `/*` is never closed"},
        {"DATA;\n#1=A(@);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "unexpected character `@`"},
        {"DATA;\n#1=(1);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "expected an entity name"},
        {"DATA;\n#1=();\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "complex instance with no records"},
        {"DATA;\n#1=A(1);\nENDSEC;\nEND-ISO-10303-21;\nmore\n", NULL, 11,
         "text after `END-ISO-10303-21;`"},
        {"END-ISO-10303-21;\n", NULL, 7, "no DATA section"},
        {"DATA;\n#1=A('Control Po'itn,1);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8,
         "expected `,` or `)` after a parameter"},
        {"DATA;\n#1=A(1,,2);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "missing parameter before `,`"},
        {"DATA;\n#1=A(1,);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "missing parameter before `)`"},
        {"DATA;\n#1=A(B);\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8,
         "expected `(` after a typed parameter's name"},
        {"DATA;\n#1=A(1);\x01\nENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "control character 0x01"},
        {"DATA;\n#1=A(((((((((((((((((((((((((((((((((((1)))))))))))))))))))))))))))))))))));\n"
         "ENDSEC;\nEND-ISO-10303-21;\n", NULL, 8, "nested more than 32 deep"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *t = cases[i].body ? with_head(cases[i].body) : strdup(cases[i].whole);
        sc_step_scan s;
        sc_error err;
        int status = scan(t, &s, &err);
        if (status != SC_FAIL || err.line != cases[i].line || !strstr(err.message, cases[i].what))
            fprintf(stderr, "  case %zu: status %d, %s:%d: %s\n", i, status, err.file, err.line,
                    err.message);
        CHECK_INT(status, SC_FAIL);
        CHECK_STR(err.file, "t.stp");
        CHECK_INT(err.line, cases[i].line);
        CHECK_CONTAINS(err.message, cases[i].what);
        free(t);
    }
}

/* The reader refuses what the pre-scan refuses, and a file past the size
 * cap, before any library sees it, and leaves the scene empty. */
TEST(step_read_refuses_before_the_library)
{
    char *t = with_head("DATA;\n#1=A(#2);\nENDSEC;\nEND-ISO-10303-21;\n");
    sc_scene s;
    sc_error err;
    CHECK_INT(sc_read_step(t, strlen(t), "t.stp", &s, &err), SC_FAIL);
    CHECK_INT(err.line, 8);
    CHECK_CONTAINS(err.message, "reference to #2");
    CHECK_INT(s.nsurfaces, 0);
    /* the cap is checked on the size alone: the bytes past the text are
     * never read */
    CHECK_INT(sc_read_step(t, SC_STEP_MAX_FILE_BYTES + 1, "t.stp", &s, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "larger than the limit of a STEP file");
    free(t);
}

/* A well-formed file with no shapes: an empty scene, or the error of a
 * build without Open CASCADE. */
TEST(step_read_file_without_shapes)
{
    char *t = with_head("DATA;\n#1=CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\n"
                        "END-ISO-10303-21;\n");
    sc_scene s;
    sc_error err;
    int status = sc_read_step(t, strlen(t), "t.stp", &s, &err);
#ifdef SC_HAVE_OCCT
    CHECK_INT(status, SC_OK);
    CHECK_INT(s.nsurfaces, 0);
    sc_scene_free(&s);
#else
    CHECK_INT(status, SC_FAIL);
    CHECK_CONTAINS(err.message, "built without STEP support");
#endif
    free(t);
}

/* ---- the shared files, through Open CASCADE ---- */

#ifdef SC_HAVE_OCCT
#define NEED_OCCT()
#else
#define NEED_OCCT() SKIP("built without Open CASCADE (STEP support)")
#endif

static char *slurp(const char *path)
{
    char *data;
    size_t size;
    sc_error err;
    return sc_read_file(path, &data, &size, &err) ? NULL : data;
}

/* Occurrences of `word` as an entity name (followed by optional blanks
 * and '(') in the text: a second path to the file's face count. */
static int count_entities(const char *text, const char *word)
{
    int n = 0;
    size_t len = strlen(word);
    for (const char *p = strstr(text, word); p; p = strstr(p + len, word)) {
        const char *q = p + len;
        while (*q == ' ')
            q++;
        if (*q == '(' && (p == text || !((p[-1] >= 'A' && p[-1] <= 'Z') || p[-1] == '_')))
            n++;
    }
    return n;
}

/* Files without assemblies: one surface per face of the file, none
 * skipped, no loop dropped, every face trimmed by its bounds. */
TEST(step_reads_single_part_files)
{
    NEED_OCCT();
    static const char *files[] = {
        "step/bug3883_xr2-ct-214_bolt.stp", "step/screw.step", "step/trj7_c2-ug-214.stp",
        "step/xr1-tc-rod.stp", "step/trj5_k1-al-214.stp",
    };
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        const char *path = test_data(files[i]);
        char *text = slurp(path);
        if (!text) {
            fprintf(stderr, "  %s: not found (the shared models, SC_DATA)\n", path);
            continue;
        }
        CHECK_INT(count_entities(text, "NEXT_ASSEMBLY_USAGE_OCCURRENCE"), 0);
        int faces = count_entities(text, "ADVANCED_FACE") + count_entities(text, "FACE_SURFACE");
        sc_scene s;
        sc_error err;
        int status = sc_read_scene(path, &s, &err);
        CHECK_INT(status, SC_OK);
        if (s.nsurfaces != faces)
            fprintf(stderr, "  %s: %d surfaces, %d faces in the file\n", files[i], s.nsurfaces,
                    faces);
        CHECK_INT(s.nsurfaces, faces);
        CHECK_INT(s.nskipped, 0);
        CHECK_INT(s.dropped_loops, 0);
        for (int k = 0; k < s.nsurfaces; k++) {
            CHECK(s.surfaces[k].nloops > 0);
            CHECK(strncmp(s.surfaces[k].name, "face #", 6) == 0);
        }
        sc_scene_free(&s);
        free(text);
    }
}

/* bug24283_spheres.stp: one unbounded spherical face of radius
 * 1.0000000000000009 (in the file), placed twice by an assembly. Both are
 * exact spheres (rational NURBS) at two different places. */
TEST(step_sphere_instances_are_exact)
{
    NEED_OCCT();
    REQUIRE_DATA("step/bug24283_spheres.stp");
    const char *path = test_data("step/bug24283_spheres.stp");
    char *text = slurp(path);
    CHECK_INT(count_entities(text, "ADVANCED_FACE"), 1);
    CHECK_INT(count_entities(text, "NEXT_ASSEMBLY_USAGE_OCCURRENCE"), 2);
    const char *r_at = strstr(text, "SPHERICAL_SURFACE");
    CHECK(r_at != NULL);
    const char *comma = strrchr(r_at, '\n');
    (void)comma;
    double radius = 0;
    const char *last_comma = NULL;
    for (const char *p = r_at; *p && *p != ';'; p++)
        if (*p == ',')
            last_comma = p;
    CHECK(last_comma && sscanf(last_comma + 1, "%lf", &radius) == 1);
    free(text);
    sc_scene s;
    sc_error err;
    CHECK_INT(sc_read_scene(path, &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 2);
    double centre[2][3];
    for (int k = 0; k < s.nsurfaces && k < 2; k++) {
        const sc_surface *f = &s.surfaces[k];
        CHECK(f->rational);
        double u0, u1, v0, v1, lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
        sc_surface_domain(f, &u0, &u1, &v0, &v1);
        enum { N = 24 };
        double pts[(N + 1) * (N + 1)][3];
        for (int i = 0; i <= N; i++)
            for (int j = 0; j <= N; j++) {
                double *p = pts[i * (N + 1) + j];
                sc_surface_eval_world(f, u0 + (u1 - u0) * i / N, v0 + (v1 - v0) * j / N, p, NULL,
                                      NULL);
                for (int d = 0; d < 3; d++) {
                    lo[d] = p[d] < lo[d] ? p[d] : lo[d];
                    hi[d] = p[d] > hi[d] ? p[d] : hi[d];
                }
            }
        for (int d = 0; d < 3; d++)
            centre[k][d] = 0.5 * (lo[d] + hi[d]);
        double worst = 0;
        for (int i = 0; i < (N + 1) * (N + 1); i++) {
            double r = sqrt((pts[i][0] - centre[k][0]) * (pts[i][0] - centre[k][0]) +
                            (pts[i][1] - centre[k][1]) * (pts[i][1] - centre[k][1]) +
                            (pts[i][2] - centre[k][2]) * (pts[i][2] - centre[k][2]));
            worst = fmax(worst, fabs(r - radius));
        }
        CHECK(worst < 1e-12);
    }
    double apart = sqrt((centre[0][0] - centre[1][0]) * (centre[0][0] - centre[1][0]) +
                        (centre[0][1] - centre[1][1]) * (centre[0][1] - centre[1][1]) +
                        (centre[0][2] - centre[1][2]) * (centre[0][2] - centre[1][2]));
    CHECK(apart > radius);
    sc_scene_free(&s);
}

static double srgb_to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* as1-oc-214-mat.stp: an assembly; its parts are placed more than once
 * (more surfaces than faces in the file), and its two COLOUR_RGB values
 * (sRGB in the file, linear in the scene) are on the surfaces. */
TEST(step_assembly_placements_and_colours)
{
    NEED_OCCT();
    REQUIRE_DATA("step/as1-oc-214-mat.stp");
    const char *path = test_data("step/as1-oc-214-mat.stp");
    char *text = slurp(path);
    int faces = count_entities(text, "ADVANCED_FACE");
    double rgb[2][3];
    int ncolours = 0;
    for (const char *p = strstr(text, "COLOUR_RGB("); p && ncolours < 2;
         p = strstr(p + 1, "COLOUR_RGB(")) {
        const char *q = strchr(p, ',');
        if (q && sscanf(q + 1, "%lf,%lf,%lf", &rgb[ncolours][0], &rgb[ncolours][1],
                        &rgb[ncolours][2]) == 3)
            ncolours++;
    }
    free(text);
    CHECK_INT(ncolours, 2);
    sc_scene s;
    sc_error err;
    CHECK_INT(sc_read_scene(path, &s, &err), SC_OK);
    CHECK(s.nsurfaces > faces);
    CHECK_INT(s.nskipped, 0);
    CHECK_INT(s.dropped_loops, 0);
    for (int c = 0; c < ncolours; c++) {
        int found = 0;
        for (int k = 0; k < s.nsurfaces; k++) {
            double d = 0;
            for (int a = 0; a < 3; a++)
                d = fmax(d, fabs(s.surfaces[k].color[a] - srgb_to_linear(rgb[c][a])));
            found += d < 1e-6;
        }
        if (!found)
            fprintf(stderr, "  no surface has colour %g %g %g\n", rgb[c][0], rgb[c][1], rgb[c][2]);
        CHECK(found > 0);
    }
    sc_scene_free(&s);
}

/* The command line: info on a STEP file, a malformed one refused with its
 * line, and a render against the CPU reference (real GL). */
TEST(step_cli_info_render_and_errors)
{
    NEED_OCCT();
    REQUIRE_DATA("step/screw.step");
    char cmd[2048], *out = NULL, *err = NULL;
    snprintf(cmd, sizeof cmd, "%s info %s", test_cli, test_data("step/screw.step"));
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK(strncmp(out, "surfaces 10\n", 12) == 0);
    free(out);
    out = NULL;
    char bad[512];
    snprintf(bad, sizeof bad, "%s/bad.stp", test_tmpdir());
    char *t = with_head("DATA;\n#1=A(#2);\nENDSEC;\nEND-ISO-10303-21;\n");
    sc_error e;
    CHECK_INT(sc_save_text(bad, t, strlen(t), &e), SC_OK);
    free(t);
    t = NULL;
    snprintf(cmd, sizeof cmd, "%s info %s", test_cli, bad);
    CHECK(test_run(cmd, NULL, &err) != 0);
    char want[600];
    snprintf(want, sizeof want, "%s:8: reference to #2", bad);
    CHECK_CONTAINS(err, want);
    free(err);
    /* a well-formed file with no shapes: nothing to draw is a failure */
    char empty[512];
    snprintf(empty, sizeof empty, "%s/empty.stp", test_tmpdir());
    t = with_head("DATA;\n#1=CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\nEND-ISO-10303-21;\n");
    CHECK_INT(sc_save_text(empty, t, strlen(t), &e), SC_OK);
    free(t);
    snprintf(cmd, sizeof cmd, "%s render %s -o %s/empty.png --size 16x16", test_cli, empty,
             test_tmpdir());
    err = NULL;
    CHECK_INT(test_run(cmd, NULL, &err), 1);
    CHECK_CONTAINS(err, "nothing to draw");
    free(err);
    snprintf(cmd, sizeof cmd, "%s/empty.png", test_tmpdir());
    CHECK(access(cmd, F_OK) != 0);
    snprintf(cmd, sizeof cmd, "%s render %s -o %s/screw.png --size 96x96 --frames 1 --ref",
             test_cli, test_data("step/screw.step"), test_tmpdir());
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    const char *acc = out ? strstr(out, "fail_pct=") : NULL;
    CHECK(acc != NULL);
    if (acc) {
        double fail = atof(acc + 9);
        if (fail > 0.1)
            fprintf(stderr, "  screw.step: %s", acc);
        CHECK(fail <= 0.1);
    }
    free(out);
}

/* A well-formed file whose B-spline curve lists a DIRECTION among its
 * control points: Open CASCADE dereferences a null handle on it. The
 * reader's child process dies, and the read fails with a message while
 * the caller goes on (step_isolate.c). */
TEST(step_library_crash_becomes_an_error)
{
    NEED_OCCT();
    REQUIRE_DATA("step/bug3883_xr2-ct-214_bolt.stp");
    char *text = slurp(test_data("step/bug3883_xr2-ct-214_bolt.stp"));
    char *at = strstr(text, "#84,#85,#86,#87");
    CHECK(at != NULL);
    CHECK(strstr(text, "#34=DIRECTION(") != NULL);
    if (!at) {
        free(text);
        return;
    }
    memcpy(at + 8, "#34", 3);
    sc_scene s;
    sc_error err;
    CHECK_INT(sc_read_step(text, strlen(text), "wrong_type.stp", &s, &err), SC_FAIL);
    CHECK_STR(err.file, "wrong_type.stp");
    CHECK_INT(err.line, 0);
    CHECK_CONTAINS(err.message, "Open CASCADE failed on this file");
    CHECK_INT(s.nsurfaces, 0);
    free(text);
}

/* A fuzzer's file: a mutant of xr1-tc-rod.stp (placements moved off their
 * edges, some entities broken). Open CASCADE's repair of self-intersecting
 * edges spent 6.8 s in one face's p-curves, out of the deadline's reach;
 * that repair is off (step_occt.cpp), and the file now reads in well under
 * a second. The ceiling is far above that, but below the old cost; its copy
 * in the STEP fuzz corpus keeps fuzz-smoke's 10 s timeout as a guard under
 * AddressSanitizer too. Every surface read comes from one of the file's
 * faces, counted or skipped. */
TEST(step_hostile_self_intersecting_edges_are_bounded)
{
    NEED_OCCT();
    char *text = slurp(test_root("tests/malformed/step_rod_healing.stp"));
    CHECK(text != NULL);
    if (!text)
        return;
    int faces = count_entities(text, "ADVANCED_FACE");
    CHECK_INT(faces, 4);
    sc_scene s;
    sc_error err;
    double t0 = sc_now();
    int status = sc_read_step(text, strlen(text), "rod_healing.stp", &s, &err);
    double took = sc_now() - t0;
    CHECK_INT(status, SC_OK);
    int skipped = 0;
    for (int i = 0; i < s.nskipped; i++)
        skipped += s.skipped[i].count;
    CHECK(s.nsurfaces > 0);
    CHECK(s.nsurfaces + skipped <= faces);
    CHECK(took < 4.0);
    sc_scene_free(&s);
    free(text);
}

/* The public API reads STEP from memory too, the name's extension picking
 * the reader. */
TEST(step_api_scene_from_memory)
{
    NEED_OCCT();
    REQUIRE_DATA("step/trj7_c2-ug-214.stp");
    char *text = slurp(test_data("step/trj7_c2-ug-214.stp"));
    int faces = count_entities(text, "ADVANCED_FACE");
    sc_scene_id scene;
    sc_error err;
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.text = text, .size = strlen(text),
                                             .name = "mem.STEP"}, &scene, &err), SC_OK);
    sc_scene_info info;
    CHECK_INT(sc_query_scene_info(scene, &info, &err), SC_OK);
    CHECK_INT(info.surfaces, faces);
    CHECK_INT(info.trimmed_surfaces, faces);
    sc_destroy_scene(scene);
    free(text);
}
