/* render_scene.c — the public C API in one page: load a scene, ask the
 * runtime for the program of each variant key the scene is drawn with,
 * render it and save a PNG. Uses only the installed <splinecast.h>:
 *
 *   cc render_scene.c $(pkg-config --cflags --libs splinecast) -o render_scene
 *   ./render_scene teapot teapot.png 256 256
 *
 * Prints `renderer programs=N hulls=N compile_ms=T`, one
 * `program KEY gl=N generate_ms=T compile_ms=T` line per key and a final
 * `wrote PATH WxH covered=N` line; errors go to stderr. */
#include <stdio.h>
#include <stdlib.h>

#include <splinecast.h>

static int fail(const sc_error *err)
{
    char text[1024];
    fprintf(stderr, "render_scene: %s\n", sc_error_text(err, text, sizeof text));
    sc_shutdown();
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: render_scene SCENE OUT.png WIDTH HEIGHT\n"
                        "  SCENE: a .bpt, .obj or .igs file, or `teapot`\n");
        return 2;
    }
    sc_error err = {0};
    sc_scene_id scene;
    if (sc_make_scene(&(sc_scene_desc){.path = argv[1]}, &scene, &err) != SC_OK)
        return fail(&err);

    sc_context_id ctx;
    if (sc_make_context(&(sc_context_desc){0}, &ctx, &err) != SC_OK)
        return fail(&err);

    /* The renderer picks one key per surface; the runtime builds each
     * distinct key's program once, in the context's cache, so asking for
     * the renderer's keys below returns the very programs it draws with. */
    sc_renderer_id renderer;
    if (sc_make_renderer(ctx, scene, &(sc_renderer_desc){0}, &renderer, &err) != SC_OK)
        return fail(&err);
    sc_renderer_info rinfo;
    if (sc_query_renderer_info(renderer, &rinfo, &err) != SC_OK)
        return fail(&err);
    printf("renderer programs=%d hulls=%d compile_ms=%.1f\n", rinfo.programs, rinfo.hulls,
           rinfo.compile_ms);
    sc_key keys[64];
    int nkeys;
    if (sc_query_renderer_keys(renderer, keys, 64, &nkeys, &err) != SC_OK)
        return fail(&err);
    for (int k = 0; k < nkeys && k < 64; k++) {
        sc_program_id program;
        sc_program_info info;
        if (sc_make_program(ctx, keys[k].text, &program, &err) != SC_OK ||
            sc_query_program_info(program, &info, &err) != SC_OK)
            return fail(&err);
        printf("program %s gl=%u generate_ms=%.1f compile_ms=%.1f\n", info.key,
               (unsigned)info.gl_program, info.generate_ms, info.compile_ms);
    }

    sc_camera_desc camera = {.width = atoi(argv[3]), .height = atoi(argv[4])};
    sc_frame_id frame;
    if (sc_render(renderer, &camera, &frame, &err) != SC_OK ||
        sc_save_png(frame, argv[2], &err) != SC_OK)
        return fail(&err);

    sc_frame_info info;
    if (sc_query_frame_info(frame, &info, &err) != SC_OK)
        return fail(&err);
    long covered = 0;
    for (long p = 0; p < (long)info.width * info.height; p++)
        covered += info.surface[p] >= 0;
    printf("wrote %s %dx%d covered=%ld\n", argv[2], info.width, info.height, covered);
    sc_shutdown();
    return 0;
}
