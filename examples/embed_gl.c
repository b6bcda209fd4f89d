/* embed_gl.c — splinecast inside an application's own OpenGL: the program
 * makes its context (EGL, surfaceless) and framebuffer, draws a triangle
 * mesh of its own with its own shaders, and has libsplinecast ray cast a
 * scene into the same framebuffer with the same view and projection
 * matrices. The surfaces write the depth of their hits, so the mesh and
 * the surfaces cut through each other where they intersect, whichever is
 * drawn first. Uses only the installed <splinecast.h>:
 *
 *   cc embed_gl.c $(pkg-config --cflags --libs splinecast) -o embed_gl
 *   ./embed_gl teapot out.ppm 256 256
 *
 * Prints `camera EX,EY,EZ,TX,TY,TZ,FOVY` (the view, as `splinecast ref
 * --camera` takes it), `mesh CX,CY,CZ UX,UY,UZ VX,VY,VZ` (the mesh: a flat
 * square, centre and half sides, drawn in pure magenta), `state restored`
 * when the GL state it set before the draw is still set after it, and
 * `wrote PATH WxH surface=N mesh=N order_diff=N` (pixels of each, and
 * pixels that differ when the surfaces are drawn before the mesh). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <splinecast.h>

#define APP_NAME "embed_gl"
#include "app_gl.h"

static const char mesh_vs[] =
    "#version 450 core\n"
    "layout(location = 0) in vec3 position;\n"
    "uniform mat4 view_projection;\n"
    "void main() { gl_Position = view_projection * vec4(position, 1.0); }\n";
static const char mesh_fs[] =
    "#version 450 core\n"
    "out vec4 colour;\n"
    "void main() { colour = vec4(1.0, 0.0, 1.0, 1.0); }\n";

static GLuint mesh_program(void)
{
    const char *sources[2] = {mesh_vs, mesh_fs};
    GLenum stages[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    GLuint program = glCreateProgram();
    for (int i = 0; i < 2; i++) {
        GLuint shader = glCreateShader(stages[i]);
        glShaderSource(shader, 1, &sources[i], NULL);
        glCompileShader(shader);
        glAttachShader(program, shader);
    }
    glLinkProgram(program);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    return ok ? program : 0;
}

/* The mesh: a square of n × n quads, two triangles each, centred at c with
 * half sides a and b. */
static float *square_mesh(const double c[3], const double a[3], const double b[3], int n,
                          int *nvertices)
{
    float *v = malloc((size_t)n * (size_t)n * 18 * sizeof *v), *p = v;
    static const int corner[6][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    for (int i = 0; v && i < n; i++)
        for (int j = 0; j < n; j++)
            for (int k = 0; k < 6; k++) {
                double s = 2.0 * (i + corner[k][0]) / n - 1, t = 2.0 * (j + corner[k][1]) / n - 1;
                for (int d = 0; d < 3; d++)
                    *p++ = (float)(c[d] + s * a[d] + t * b[d]);
            }
    *nvertices = 6 * n * n;
    return v;
}

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: embed_gl SCENE OUT.ppm WIDTH HEIGHT\n"
                        "  SCENE: a .bpt, .obj or .igs file, or `teapot`\n");
        return 2;
    }
    int w = atoi(argv[3]), h = atoi(argv[4]);
    if (w < 1 || h < 1 || w > 4096 || h > 4096) {
        fprintf(stderr, "embed_gl: WIDTH and HEIGHT must lie in 1..4096\n");
        return 2;
    }
    if (!make_gl_context())
        return fail("no OpenGL 4.5 core context from EGL", NULL);

    /* The application's framebuffer: colour and a 24-bit depth buffer. */
    GLuint fbo = make_framebuffer(w, h);
    if (!fbo)
        return fail("framebuffer incomplete", NULL);

    /* libsplinecast on the application's context. */
    sc_error err = {0};
    sc_context_id ctx;
    if (sc_make_context(&(sc_context_desc){.get_proc_address = eglGetProcAddress}, &ctx, &err))
        return fail("sc_make_context", &err);
    sc_scene_id scene;
    sc_renderer_id renderer;
    if (sc_make_scene(&(sc_scene_desc){.path = argv[1]}, &scene, &err))
        return fail("sc_make_scene", &err);
    if (sc_make_renderer(ctx, scene, NULL, &renderer, &err))
        return fail("sc_make_renderer", &err);

    /* A view of the scene's box from the front left, above. */
    sc_scene_info info;
    sc_query_scene_info(scene, &info, &err);
    double centre[3], size = 0;
    for (int c = 0; c < 3; c++) {
        centre[c] = 0.5 * (info.lo[c] + info.hi[c]);
        size += (info.hi[c] - info.lo[c]) * (info.hi[c] - info.lo[c]);
    }
    size = sqrt(size);
    double eye[3] = {centre[0] + 0.9 * size, centre[1] - 1.3 * size, centre[2] + 0.7 * size};
    double fovy = 30;
    float view[16], proj[16], vp[16];
    matrices(eye, centre, fovy, (double)w / h, 0.2 * size, 5 * size, view, proj);
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double sum = 0;
            for (int k = 0; k < 4; k++)
                sum += (double)proj[k * 4 + row] * view[col * 4 + k];
            vp[col * 4 + row] = (float)sum;
        }
    printf("camera %.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", eye[0], eye[1], eye[2],
           centre[0], centre[1], centre[2], fovy);

    /* The mesh: a square through the middle of the box, tilted about x. */
    double a[3] = {0.45 * size, 0, 0}, b[3] = {0, 0.4 * size * cos(0.5), 0.4 * size * sin(0.5)};
    printf("mesh %.17g,%.17g,%.17g %.17g,%.17g,%.17g %.17g,%.17g,%.17g\n", centre[0], centre[1],
           centre[2], a[0], a[1], a[2], b[0], b[1], b[2]);
    int nvertices;
    float *vertices = square_mesh(centre, a, b, 8, &nvertices);
    GLuint program = mesh_program(), vao, vbo;
    if (!program || !vertices)
        return fail("the mesh's program", NULL);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(nvertices * 3 * sizeof(float)), vertices,
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, NULL);
    free(vertices);
    glUseProgram(program);
    glUniformMatrix4fv(glGetUniformLocation(program, "view_projection"), 1, GL_FALSE, vp);

    unsigned char *pixels[2];
    sc_gl_draw_desc frame = {0};
    memcpy(frame.view, view, sizeof view);
    memcpy(frame.projection, proj, sizeof proj);
    /* Frame 0: the mesh, then the surfaces; frame 1 the other way round. */
    for (int order = 0; order < 2; order++) {
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LEQUAL);
        for (int step = 0; step < 2; step++) {
            if (step == order) {
                glDrawArrays(GL_TRIANGLES, 0, nvertices);
            } else if (sc_draw_gl(renderer, &frame, &err)) {
                return fail("sc_draw_gl", &err);
            }
        }
        /* What the application set is what it finds. */
        GLint current = 0, bound = 0, func = 0, fb = 0;
        glGetIntegerv(GL_CURRENT_PROGRAM, &current);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &bound);
        glGetIntegerv(GL_DEPTH_FUNC, &func);
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fb);
        if (order == 0)
            printf("state %s\n", (GLuint)current == program && (GLuint)bound == vao &&
                                         func == GL_LEQUAL && (GLuint)fb == fbo
                                     ? "restored"
                                     : "changed");
        glFinish();
        pixels[order] = malloc((size_t)w * (size_t)h * 4);
        glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels[order]);
    }

    long surface = 0, mesh = 0, diff = 0;
    for (long p = 0; p < (long)w * h; p++) {
        const unsigned char *px = pixels[0] + 4 * p;
        int is_mesh = px[0] == 255 && px[1] == 0 && px[2] == 255;
        mesh += is_mesh;
        surface += !is_mesh && (px[0] || px[1] || px[2]);
        diff += memcmp(px, pixels[1] + 4 * p, 3) != 0;
    }
    /* A binary PPM, rows top-down (GL's are bottom-up). */
    FILE *f = fopen(argv[2], "wb");
    if (!f)
        return fail("cannot write the image", NULL);
    fprintf(f, "P6\n%d %d\n255\n", w, h);
    for (int y = h - 1; y >= 0; y--)
        for (int x = 0; x < w; x++)
            fwrite(pixels[0] + 4 * ((size_t)y * (size_t)w + (size_t)x), 1, 3, f);
    if (fclose(f) != 0)
        return fail("cannot write the image", NULL);
    printf("wrote %s %dx%d surface=%ld mesh=%ld order_diff=%ld\n", argv[2], w, h, surface, mesh,
           diff);
    free(pixels[0]);
    free(pixels[1]);
    sc_shutdown();
    return 0;
}
