/* packed_gl.c — build time to run time: a program in plain OpenGL (its own
 * EGL context and framebuffer) draws a scene packed at build time with
 * programs generated at build time, and never calls the compiler: the
 * pack holds the GPU data (`splinecast pack`), the folder the GLSL and its
 * manifest (`splinecast gen`), and linked programs are kept in a binary
 * cache folder, so that a second start compiles nothing either. Uses only
 * the installed <splinecast.h>:
 *
 *   splinecast gen --scene part.igs -o shaders
 *   splinecast pack part.igs -o part.pack
 *   cc packed_gl.c $(pkg-config --cflags --libs splinecast) -o packed_gl
 *   ./packed_gl part.pack shaders cache out.ppm 512 512
 *
 * Prints `first_frame_ms=T` (from the start of main to the first frame
 * drawn and finished: context, programs, data, frame) and `wrote PATH WxH
 * covered=N`. CACHE may be `-` for none. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <splinecast.h>

#define APP_NAME "packed_gl"
#include "app_gl.h"

int main(int argc, char **argv)
{
    double t0 = sc_now();
    if (argc != 7) {
        fprintf(stderr, "usage: packed_gl PACK SHADER_DIR CACHE_DIR|- OUT.ppm WIDTH HEIGHT\n");
        return 2;
    }
    int w = atoi(argv[5]), h = atoi(argv[6]);
    if (w < 1 || h < 1 || w > 4096 || h > 4096) {
        fprintf(stderr, "packed_gl: WIDTH and HEIGHT must lie in 1..4096\n");
        return 2;
    }
    if (!make_gl_context())
        return fail("no OpenGL 4.5 core context from EGL", NULL);
    GLuint fbo = make_framebuffer(w, h);
    if (!fbo)
        return fail("framebuffer incomplete", NULL);

    /* Programs from the gen folder (a key it lacks is an error, not a
     * compile), linked ones kept in the cache folder. */
    sc_error err = {0};
    sc_context_id ctx;
    sc_context_desc cd = {.get_proc_address = eglGetProcAddress, .programs_dir = argv[2],
                          .binary_cache_dir = strcmp(argv[3], "-") ? argv[3] : NULL};
    if (sc_make_context(&cd, &ctx, &err))
        return fail("sc_make_context", &err);
    sc_renderer_id renderer;
    if (sc_make_renderer(ctx, (sc_scene_id){0}, &(sc_renderer_desc){.pack = argv[1]}, &renderer,
                         &err))
        return fail("sc_make_renderer", &err);

    /* The view: the pack's box from the front left, above. */
    sc_renderer_info info;
    if (sc_query_renderer_info(renderer, &info, &err))
        return fail("sc_query_renderer_info", &err);
    double centre[3], size = 0;
    for (int c = 0; c < 3; c++) {
        centre[c] = 0.5 * (info.lo[c] + info.hi[c]);
        size += (info.hi[c] - info.lo[c]) * (info.hi[c] - info.lo[c]);
    }
    size = sqrt(size);
    double eye[3] = {centre[0] + 1.0 * size, centre[1] - 1.4 * size, centre[2] + 0.8 * size};
    sc_gl_draw_desc frame = {0};
    matrices(eye, centre, 30, (double)w / h, 0.2 * size, 5 * size, frame.view, frame.projection);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (sc_draw_gl(renderer, &frame, &err))
        return fail("sc_draw_gl", &err);
    glFinish();
    printf("first_frame_ms=%.1f\n", 1e3 * (sc_now() - t0));

    unsigned char *pixels = malloc((size_t)w * (size_t)h * 4);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    long covered = 0;
    for (long p = 0; p < (long)w * h; p++)
        covered += pixels[4 * p] || pixels[4 * p + 1] || pixels[4 * p + 2];
    FILE *f = fopen(argv[4], "wb");
    if (!f)
        return fail("cannot write the image", NULL);
    fprintf(f, "P6\n%d %d\n255\n", w, h);
    for (int y = h - 1; y >= 0; y--)
        for (int x = 0; x < w; x++)
            fwrite(pixels + 4 * ((size_t)y * (size_t)w + (size_t)x), 1, 3, f);
    if (fclose(f) != 0)
        return fail("cannot write the image", NULL);
    printf("wrote %s %dx%d covered=%ld\n", argv[4], w, h, covered);
    free(pixels);
    sc_shutdown();
    return 0;
}
