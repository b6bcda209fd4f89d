/* test_iges_malformed.c — malformed IGES files: each must be refused with
 * the entity and its position named, or read leniently where the format's
 * readers commonly are; nothing half-read. */
#include "test.h"

#include <stdlib.h>

#include "iges_files.h"

/* ---- malformed files ---- */

/* Reads text that must fail; checks that the message holds every needle
 * (the entity and its directory number, the position). */
static int refused(const char *text, const char *needle1, const char *needle2)
{
    sc_scene s;
    sc_error err;
    if (iges_read_text(text, &s, &err) == SC_OK) {
        fprintf(stderr, "  read a malformed file without an error\n");
        sc_scene_free(&s);
        return 0;
    }
    const char *msg = iges_error_text(&err);
    if (s.nsurfaces != 0 || s.surfaces != NULL)
        return 0;
    if ((needle1 && !strstr(msg, needle1)) || (needle2 && !strstr(msg, needle2))) {
        fprintf(stderr, "  message \"%s\" lacks \"%s\" / \"%s\"\n", msg, needle1,
                needle2 ? needle2 : "");
        return 0;
    }
    return 1;
}

static const spec good[] = {
    {128, NULL, 0, 0, NULL}, /* plane, filled in */
    {110, "110,0.2,0.2,0.,0.8,0.5,0.;", 0, 0, NULL},
    {110, "110,0.8,0.5,0.,0.2,0.2,0.;", 0, 0, NULL},
    {102, "102,2,3,5;", 0, 0, NULL},
    {142, "142,0,1,7,0,2;", 0, 0, NULL},
    {144, "144,1,1,0,9;", 0, 0, NULL},
};
enum { NGOOD = 6 };

/* The good file with entity k's parameters (and optionally its directory
 * field 7) replaced. */
static char *variant(int k, const char *params, int xform)
{
    spec e[NGOOD];
    memcpy(e, good, sizeof e);
    e[0].params = iges_plane_params(1);
    if (params) {
        e[k].params = params;
        e[k].type = atoi(params);
    }
    if (xform)
        e[k].xform = xform;
    return iges_make_iges(e, NGOOD);
}

TEST(iges_malformed_truncated)
{
    char *text = variant(0, NULL, 0);
    sc_scene s;
    sc_error err;
    CHECK_INT(iges_read_text(text, &s, &err), SC_OK); /* the base file is good */
    sc_scene_free(&s);
    /* Cut after the 144's first record, before its terminator. */
    char *cut = strstr(text, "144,1,1,0,9;");
    CHECK(cut != NULL);
    cut[11] = ',';
    strcpy(strchr(cut, '\n') + 1, "");
    CHECK(refused(text, "entity 144 (D 11)", "ends before the record delimiter"));
    CHECK(refused(text, iges_position_of(text, "144,1,1,0,9,"), NULL));
    /* Cut inside a record. */
    cut[8] = 0;
    CHECK(refused(text, iges_position_of(text, "144,1,1,"), "record of 8 columns"));
    /* Cut inside the directory: an odd number of D records. */
    free(text);
    text = variant(0, NULL, 0);
    char *d = strstr(text, "     110       0");
    CHECK(d != NULL);
    strcpy(d, "");
    CHECK(refused(text, "odd number", NULL));
    free(text);
}

TEST(iges_malformed_pointer_out_of_range)
{
    char *text = variant(5, "144,99,1,0,9;", 0);
    CHECK(refused(text, "entity 144 (D 11): parameter 1: pointer 99",
                  iges_position_of(text, "144,99")));
    free(text);
    /* A parameter data pointer beyond the P section. */
    text = variant(0, NULL, 0);
    char *d = strstr(text, "D      3\n");
    CHECK(d != NULL);
    memcpy(d - 72 + 8, "     999", 8); /* field 2 of DE 3 */
    CHECK(refused(text, "entity 110 (D 3)", "outside the P section"));
    free(text);
    /* A transformation pointer to something that is not a 124. */
    text = variant(0, NULL, 5);
    CHECK(refused(text, "entity 128 (D 1)", "not to a 124"));
    free(text);
}

TEST(iges_unused_entities_never_fail)
{
    /* Next to a good plane: a 142 that nothing uses, pointing nowhere, and
     * a 406 property (not converted) whose pointer is broken. Neither is
     * used by a surface, so the file reads; the 406 is counted. */
    spec e[] = {
        {128, iges_plane_params(1), 0, 0, NULL},
        {142, "142,0,999,0,0,1;", 0, 0, NULL},
        {406, "406,1,999;", 0, 0, NULL},
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 3, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    CHECK_INT(iges_skipped_count(&s, "iges-406", "unsupported"), 1);
    sc_scene_free(&s);
    /* The same 142 used as a trim loop: now it matters and fails the file. */
    char *text = variant(4, "142,0,999,7,0,2;", 0);
    CHECK(refused(text, "entity 142 (D 9): parameter 2: pointer 999",
                  iges_position_of(text, "142,0,999")));
    free(text);
}

TEST(iges_malformed_reference_cycle)
{
    /* A composite that contains itself. */
    char *text = variant(3, "102,2,3,7;", 0);
    CHECK(refused(text, "entity 102 (D 7)", "cycle"));
    free(text);
    /* Transformation matrices that refer to each other. */
    spec e[] = {
        {128, iges_plane_params(1), 3, 0, NULL},
        {124, "124,1.,0.,0.,0.,0.,1.,0.,0.,0.,0.,1.,0.;", 5, 0, NULL},
        {124, "124,1.,0.,0.,0.,0.,1.,0.,0.,0.,0.,1.,0.;", 3, 0, NULL},
    };
    text = iges_make_iges(e, 3);
    CHECK(refused(text, "entity 128 (D 1)", "cycle"));
    free(text);
}

TEST(iges_malformed_huge_counts)
{
    char *text = variant(3, "102,1000000000,3,5;", 0);
    CHECK(refused(text, "entity 102 (D 7)", "counts larger than the data"));
    free(text);
    text = variant(0, "128,100000,100000,1,1,0,0,1,0,0,0.,0.,1.,1.;", 0);
    CHECK(refused(text, "entity 128 (D 1)", "larger than the data"));
    free(text);
    /* A 126 whose point count runs past its data. */
    text = variant(1, "126,50,3,0,0,1,0,0.,0.,0.,0.,1.,1.,1.,1.;", 0);
    CHECK(refused(text, "entity 126 (D 3)", "needs"));
    free(text);
}

TEST(iges_malformed_hollerith)
{
    /* In the parameter data of a colour the surface uses: fatal. */
    spec e[] = {
        {128, iges_plane_params(1), 0, -3, NULL},
        {314, "314,10.,20.,30.,99Habc;", 0, 0, NULL},
    };
    char *text = iges_make_iges(e, 2);
    CHECK(refused(text, "entity 314 (D 3)", "Hollerith"));
    free(text);
    /* A number where a Hollerith string follows the wrong way. */
    text = variant(1, "110,3Habcdef,0.2,0.,0.8,0.5,0.;", 0);
    CHECK(refused(text, "entity 110 (D 3)", "Hollerith"));
    free(text);
    /* In the global section: reported, the file is read. */
    text = variant(0, NULL, 0);
    char *g = strstr(text, "1H,,1H;,4Htest,5Ht.igs,;");
    CHECK(g != NULL);
    memcpy(g, "1H,,1H;,99Htest,5Ht.igs", 23);
    sc_scene s;
    sc_error err;
    CHECK_INT(iges_read_text(text, &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    CHECK_CONTAINS(iges_warnings, "t.igs:2: global section");
    sc_scene_free(&s);
    free(text);
    /* A count with extra digits is still a count, not plain text. */
    text = variant(0, NULL, 0);
    g = strstr(text, "1H,,1H;,4Htest,5Ht.igs,;");
    CHECK(g != NULL);
    const char *longer = "1H,,1H;,99999HOpen,5Ht.igs,;";
    memcpy(g, longer, strlen(longer));
    CHECK_INT(iges_read_text(text, &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    CHECK_CONTAINS(iges_warnings, "t.igs:2: global section: a Hollerith string");
    sc_scene_free(&s);
    free(text);
}

TEST(iges_malformed_binary_and_not_iges)
{
    char junk[300];
    unsigned long long state = 7;
    for (size_t i = 0; i < sizeof junk; i++)
        junk[i] = (char)(1 + test_rand(&state) * 254);
    junk[sizeof junk - 1] = 0;
    sc_scene s;
    sc_error err;
    CHECK_INT(iges_read_text(junk, &s, &err), SC_FAIL);
    CHECK_CONTAINS(iges_error_text(&err), "t.igs:");
    CHECK_INT(s.nsurfaces, 0);
    /* Text, but not IGES. */
    CHECK(refused("v 0 0 0\nv 1 0 0\n", "t.igs:1:", "record of"));
    char obj[200];
    memset(obj, 'x', 100);
    obj[100] = 0;
    CHECK(refused(obj, "t.igs:1:", "column 73"));
    CHECK(refused("", "empty", NULL));
}

TEST(iges_malformed_missing_sections)
{
    /* S and G only: no directory. */
    char *text = variant(0, NULL, 0);
    char *d = strstr(text, "     128");
    CHECK(d != NULL);
    *d = 0;
    CHECK(refused(text, "no directory section", NULL));
    free(text);
    /* No P section: every entity's parameters are missing. */
    text = variant(0, NULL, 0);
    char *p = strstr(text, "128,1,1,");
    CHECK(p != NULL);
    *p = 0;
    CHECK(refused(text, "outside the P section", "(D "));
    free(text);
    /* Sections out of order. */
    spec e[] = {{128, iges_plane_params(1), 0, 0, NULL}};
    text = iges_make_iges(e, 1);
    char *g = strstr(text, "1H,,");
    char *line2 = strstr(g, "\n") + 1; /* the first D record */
    char save[81];
    memcpy(save, g, 81);
    memmove(g, line2, 81);
    memcpy(g + 81, save, 81);
    CHECK(refused(text, "t.igs:3:", "order"));
    free(text);
}

TEST(iges_malformed_degree_and_numbers)
{
    /* Degree 3 with 2 x 2 control points. */
    char *text = variant(0, "128,1,1,3,1,0,0,1,0,0,0.,0.,0.,0.,1.,1.,1.,1.,0.,0.,1.,1.,1.,1.,1.,"
                            "1.,0.,0.,0.,1.,0.,0.,0.,1.,0.,1.,1.,0.,0.,1.,0.,1.;", 0);
    CHECK(refused(text, "entity 128 (D 1): degree 3 x 1 needs at least 4 x 2",
                  iges_position_of(text, "128,1,1,3,1")));
    free(text);
    /* Decreasing knots. */
    text = variant(0, "128,1,1,1,1,0,0,1,0,0,0.,1.,0.,1.,0.,0.,1.,1.,1.,1.,1.,1.,0.,0.,0.,1.,"
                      "0.,0.,0.,1.,0.,1.,1.,0.,0.,1.,0.,1.;", 0);
    CHECK(refused(text, "entity 128 (D 1)", "decrease"));
    free(text);
    /* A number that overflows. */
    text = variant(1, "110,1.E999,0.2,0.,0.8,0.5,0.;", 0);
    CHECK(refused(text, "entity 110 (D 3)", "not a finite number"));
    free(text);
    /* An integer beyond what any count or pointer can be. */
    text = variant(3, "102,2000000000,3,5;", 0);
    CHECK(refused(text, "entity 102 (D 7): parameter 1: integer 2000000000 is out of range",
                  iges_position_of(text, "102,2000000000")));
    free(text);
    /* Zero weight on a rational surface. */
    text = variant(0, "128,1,1,1,1,0,0,0,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,0.,1.,1.,0.,0.,0.,1.,"
                      "0.,0.,0.,1.,0.,1.,1.,0.,0.,1.,0.,1.;", 0);
    CHECK(refused(text, "entity 128 (D 1)", "weight 1"));
    free(text);
    /* A loop pointer to the wrong kind of entity. */
    text = variant(5, "144,1,1,0,7;", 0);
    CHECK(refused(text, "entity 144 (D 11)", "expected a 142"));
    free(text);
}

