/* api_render.c — the public interface's GL side (splinecast.h): contexts,
 * programs by key, renderers, frames drawn on the GPU or by the CPU
 * reference, and what is done with frames (PNG and AOV files,
 * comparison), and sc_shutdown. Scenes, keys and generation are in api.c;
 * handles and checks in api_objects.c. */
#include "api_private.h"

#include "gl_state.h"

/* ---- contexts and programs ---- */

int sc_make_context(const sc_context_desc *desc, sc_context_id *out, sc_error *err)
{
    static const sc_context_desc defaults = {0};
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    if (!desc)
        desc = &defaults;
    if (sc_api_check_enum(desc->backend, SC_BACKEND_OSMESA + 1, "sc_context_desc.backend", err))
        return SC_FAIL;
    sc_gl_context_desc gl_desc = {.backend = desc->backend, .debug = desc->debug};
    context_object *c = sc_alloc(1, sizeof *c);
    if ((desc->get_proc_address
             ? sc_gl_context_wrap((sc_gl_app_get_proc_fn)desc->get_proc_address, &c->gl, err)
             : sc_gl_context_create(&gl_desc, &c->gl, err)) != SC_OK) {
        sc_api_current_context = NULL;  /* a failed attempt may have changed it */
        free(c);
        return SC_FAIL;
    }
    /* Creating made one of the library's current; the application's is
     * its own business (sc_api_make_current). */
    sc_api_current_context = sc_gl_context_is_app(c->gl) ? NULL : c;
    c->programs = sc_program_cache_create(sc_gl_context_gl(c->gl));
    if (sc_program_cache_set_sources(c->programs, desc->programs_dir, desc->generate_missing != 0,
                                     desc->binary_cache_dir, err) != SC_OK ||
        (out->id = sc_api_pool_insert(&sc_api_contexts, c, err)) == 0) {
        sc_program_cache_destroy(c->programs);
        sc_gl_context_destroy(c->gl);
        sc_api_current_context = NULL;
        free(c);
        return SC_FAIL;
    }
    return SC_OK;
}


void sc_destroy_context(sc_context_id ctx)
{
    context_object *c = sc_api_pool_get(&sc_api_contexts, ctx.id, NULL);
    if (!c)
        return;
    sc_api_destroy_peers(c);
    for (int i = 0; i < sc_api_renderers.count; i++) {
        renderer_object *r = sc_api_renderers.slots[i].object;
        if (r && r->context == c) {
            sc_api_pool_remove(&sc_api_renderers, sc_api_slot_id(&sc_api_renderers, i));
            sc_api_destroy_renderer_object(r);
        }
    }
    for (int i = 0; i < sc_api_programs.count; i++) {
        program_object *p = sc_api_programs.slots[i].object;
        if (p && p->context == c) {
            sc_api_pool_remove(&sc_api_programs, sc_api_slot_id(&sc_api_programs, i));
            free(p);
        }
    }
    if (sc_api_make_current(c, NULL) == SC_OK)
        sc_program_cache_destroy(c->programs);
    sc_gl_context_destroy(c->gl);
    sc_api_current_context = NULL;
    sc_api_pool_remove(&sc_api_contexts, ctx.id);
    free(c);
}

int sc_query_context_info(sc_context_id ctx, sc_context_info *info, sc_error *err)
{
    context_object *c = sc_api_pool_get(&sc_api_contexts, ctx.id, err);
    if (!c)
        return SC_FAIL;
    if (!info)
        return sc_api_invalid(err, "info", PROBLEM_NULL, NULL);
    memset(info, 0, sizeof *info);
    info->backend = sc_gl_context_backend(c->gl);
    snprintf(info->description, sizeof info->description, "%s",
             sc_gl_context_description(c->gl));
    return SC_OK;
}

int sc_make_program(sc_context_id ctx, const char *key, sc_program_id *out, sc_error *err)
{
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    context_object *c = sc_api_pool_get(&sc_api_contexts, ctx.id, err);
    if (!c || sc_check_key(key, err) != SC_OK || sc_api_make_current(c, err) != SC_OK)
        return SC_FAIL;
    scg_key parsed;
    scg_key_parse(key, &parsed, NULL);
    sc_program program;
    if (sc_program_for_key(c->programs, &parsed, &program, err) != SC_OK)
        return SC_FAIL;
    for (int i = 0; i < sc_api_programs.count; i++) {
        const program_object *p = sc_api_programs.slots[i].object;
        if (p && p->context == c && p->program.id == program.id) {
            out->id = sc_api_slot_id(&sc_api_programs, i);
            return SC_OK;
        }
    }
    program_object *p = sc_alloc(1, sizeof *p);
    p->context = c;
    p->program = program;
    if ((out->id = sc_api_pool_insert(&sc_api_programs, p, err)) == 0) {
        free(p);
        return SC_FAIL;
    }
    return SC_OK;
}

int sc_query_program_info(sc_program_id program, sc_program_info *info, sc_error *err)
{
    program_object *p = sc_api_pool_get(&sc_api_programs, program.id, err);
    if (!p)
        return SC_FAIL;
    if (!info)
        return sc_api_invalid(err, "info", PROBLEM_NULL, NULL);
    memset(info, 0, sizeof *info);
    sc_program_cache *cache = p->context->programs;
    scg_key_format(sc_program_key(cache, p->program), info->key, sizeof info->key);
    info->gl_program = sc_program_gl_name(cache, p->program);
    sc_program_times(cache, p->program, &info->generate_ms, &info->compile_ms);
    return SC_OK;
}

/* ---- renderers ---- */


/* The accuracy target of a desc (docs/accuracy.md), refused with the
 * field's name when out of range. */
static int accuracy_target(const sc_renderer_desc *d, const sc_scene *scene,
                           sc_accuracy_target *t, sc_error *err)
{
    memset(t, 0, sizeof *t);
    if (d->accuracy_px == 0 && d->accuracy_normal_deg == 0)
        return SC_OK;
    if (d->accuracy_px == 0)
        return sc_api_invalid(err, "sc_renderer_desc.accuracy_normal_deg", PROBLEM_RANGE,
                              "%g: a normal bound needs a position bound (accuracy_px)",
                              d->accuracy_normal_deg);
    const char *why = sc_accuracy_check(d->accuracy_px, d->accuracy_normal_deg);
    if (why)
        return sc_api_invalid(err, "sc_renderer_desc.accuracy_px", PROBLEM_RANGE,
                              "%g, %g degrees: %s", d->accuracy_px, d->accuracy_normal_deg, why);
    t->px = d->accuracy_px;
    t->normal_deg = d->accuracy_normal_deg;
    return sc_api_make_camera(d->accuracy_view, scene, &t->view, err);
}

int sc_make_renderer(sc_context_id ctx, sc_scene_id scene, const sc_renderer_desc *desc,
                     sc_renderer_id *out, sc_error *err)
{
    static const sc_renderer_desc defaults = {0};
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    context_object *c = sc_api_pool_get(&sc_api_contexts, ctx.id, err);
    if (c && desc && desc->pack)
        return sc_api_make_packed_renderer(c, scene, desc, out, err);
    scene_object *s = c ? sc_api_pool_get(&sc_api_scenes, scene.id, err) : NULL;
    sc_render_desc internal;
    if (!s || sc_api_render_desc(desc ? desc : &defaults, &internal, err) != SC_OK ||
        accuracy_target(desc ? desc : &defaults, &s->scene, &internal.accuracy, err) != SC_OK ||
        sc_api_make_current(c, err) != SC_OK)
        return SC_FAIL;
    /* The context's cache: sc_make_program on the renderer's keys returns
     * the very programs it draws with. */
    internal.programs = desc && desc->own_programs ? NULL : c->programs;
    renderer_object *r = sc_alloc(1, sizeof *r);
    r->context = c;
    r->scene = s;
    if (sc_renderer_create(sc_gl_context_gl(c->gl), &s->scene, &internal, &r->renderer, err) !=
        SC_OK) {
        free(r);
        return SC_FAIL;
    }
    s->users++;
    if ((out->id = sc_api_pool_insert(&sc_api_renderers, r, err)) == 0) {
        sc_api_destroy_renderer_object(r);
        return SC_FAIL;
    }
    return SC_OK;
}

void sc_destroy_renderer(sc_renderer_id renderer)
{
    renderer_object *r = sc_api_pool_get(&sc_api_renderers, renderer.id, NULL);
    if (!r)
        return;
    sc_api_pool_remove(&sc_api_renderers, renderer.id);
    sc_api_destroy_renderer_object(r);
}

int sc_query_renderer_keys(sc_renderer_id renderer, sc_key *keys, int capacity, int *count,
                           sc_error *err)
{
    renderer_object *r = sc_api_pool_get(&sc_api_renderers, renderer.id, err);
    if (!r)
        return SC_FAIL;
    int nsurfaces = sc_renderer_scene(r->renderer)->nsurfaces, n = 0;
    char (*texts)[SCG_KEY_MAX] = sc_alloc((size_t)(nsurfaces ? nsurfaces : 1), SCG_KEY_MAX);
    for (int s = 0; s < nsurfaces; s++) {
        scg_key_format(sc_renderer_surface_key(r->renderer, s), texts[n], SCG_KEY_MAX);
        int seen = 0;
        for (int k = 0; k < n && !seen; k++)
            seen = !strcmp(texts[k], texts[n]);
        n += !seen;
    }
    int status = sc_api_count_keys((const char (*)[SCG_KEY_MAX])texts, n, keys, capacity, count, err);
    free(texts);
    return status;
}

int sc_query_renderer_surface(sc_renderer_id renderer, int surface,
                              sc_renderer_surface_info *info, sc_error *err)
{
    renderer_object *r = sc_api_pool_get(&sc_api_renderers, renderer.id, err);
    if (!r)
        return SC_FAIL;
    if (!info)
        return sc_api_invalid(err, "info", PROBLEM_NULL, NULL);
    if (sc_api_check_int(surface, 0, r->scene->scene.nsurfaces - 1, "surface", err))
        return SC_FAIL;
    memset(info, 0, sizeof *info);
    const scg_key *key = sc_renderer_surface_key(r->renderer, surface);
    scg_key_format(key, info->key.text, sizeof info->key.text);
    info->max_iters = key->max_iters;
    info->tolerance_px = scg_key_tolerance(key);
    sc_renderer_surface_hulls(r->renderer, surface, &info->hulls, &info->hull_tolerance);
    const sc_accuracy_choice *choice = sc_renderer_surface_choice(r->renderer, surface);
    if (choice) {
        info->footprint = choice->footprint;
        info->radius = choice->radius;
    }
    return SC_OK;
}

int sc_query_renderer_info(sc_renderer_id renderer, sc_renderer_info *info, sc_error *err)
{
    renderer_object *r = sc_api_pool_get(&sc_api_renderers, renderer.id, err);
    if (!r)
        return SC_FAIL;
    if (!info)
        return sc_api_invalid(err, "info", PROBLEM_NULL, NULL);
    /* The intersection count is read from the renderer's GL buffer. */
    if (sc_api_make_current(r->context, err) != SC_OK)
        return SC_FAIL;
    /* What the surface updates since the last frame left is sent now, so
     * that uploaded_bytes counts it. */
    if (sc_renderer_send_updates(r->renderer, err) != SC_OK)
        return SC_FAIL;
    sc_render_stats stats;
    sc_renderer_stats(r->renderer, &stats);
    *info = (sc_renderer_info){
        .programs = stats.programs,
        .hulls = stats.hulls,
        .triangles = stats.triangles,
        .gpu_bytes = stats.gpu_bytes,
        .uploaded_bytes = stats.bytes_uploaded,
        .compile_ms = stats.compile_ms,
        .draw_calls = stats.draw_calls,
        .program_switches = stats.program_switches,
        .culled_hulls = stats.culled_hulls,
        .readbacks = stats.readbacks,
        .intersections = stats.intersections,
        .intersect_ms = stats.intersect_ms,
        .intersect_query_ms = stats.intersect_query_ms,
        .uploaded_total_bytes = stats.bytes_uploaded_total,
        .qhull_hulls = stats.qhull_hulls,
        .peel_layers = stats.peel_layers,
    };
    if (!sc_renderer_view_bounds(r->renderer, info->lo, info->hi))
        sc_scene_bounds(sc_renderer_scene(r->renderer), info->lo, info->hi);
    return SC_OK;
}

int sc_check_camera(const sc_camera_desc *camera, sc_error *err)
{
    sc_camera cam;
    return sc_api_make_camera(camera, NULL, &cam, err);
}

static void expand_to_rgba(const sc_image *rgb, sc_image *rgba)
{
    sc_image_alloc(rgba, rgb->width, rgb->height, 4);
    size_t n = (size_t)rgb->width * (size_t)rgb->height;
    for (size_t p = 0; p < n; p++) {
        memcpy(rgba->pixels + 4 * p, rgb->pixels + (size_t)rgb->channels * p, 3);
        rgba->pixels[4 * p + 3] = rgb->channels == 4 ? rgb->pixels[4 * p + 3] : 255;
    }
}

static int add_frame(frame_object *f, sc_frame_id *out, sc_error *err)
{
    if ((out->id = sc_api_pool_insert(&sc_api_frames, f, err)) != 0)
        return SC_OK;
    sc_image_free(&f->rgba);
    sc_aov_free(&f->aov);
    free(f);
    return SC_FAIL;
}

/* sc_draw, writing the AOVs when aovs is 1 whatever the renderer's
 * sc_renderer_desc.aovs says. */
static int draw(sc_renderer_id renderer, const sc_camera_desc *camera, int aovs, sc_error *err)
{
    renderer_object *r = sc_api_pool_get(&sc_api_renderers, renderer.id, err);
    if (!r)
        return SC_FAIL;
    sc_camera cam;
    double lo[3], hi[3];
    int any = sc_renderer_view_bounds(r->renderer, lo, hi);
    if (sc_api_make_camera_framing(camera, any ? lo : NULL, any ? hi : NULL, &cam, err) != SC_OK ||
        sc_api_make_current(r->context, err) != SC_OK)
        return SC_FAIL;
    /* In an application's context the renderer's own target is drawn, and
     * what that changes is put back. */
    sc_gl_state saved;
    int app = sc_gl_context_is_app(r->context->gl);
    const sc_gl *gl = sc_gl_context_gl(r->context->gl);
    if (app)
        sc_gl_state_save(gl, &saved);
    int status = aovs ? sc_renderer_draw_aovs(r->renderer, &cam, err)
                      : sc_renderer_draw(r->renderer, &cam, err);
    if (app)
        sc_gl_state_restore(gl, &saved);
    return status;
}

int sc_draw(sc_renderer_id renderer, const sc_camera_desc *camera, sc_error *err)
{
    return draw(renderer, camera, 0, err);
}

int sc_draw_gl(sc_renderer_id renderer, const sc_gl_draw_desc *desc, sc_error *err)
{
    renderer_object *r = sc_api_pool_get(&sc_api_renderers, renderer.id, err);
    if (!r)
        return SC_FAIL;
    if (!desc)
        return sc_api_invalid(err, "desc", PROBLEM_NULL, NULL);
    if (!sc_gl_context_is_app(r->context->gl))
        return sc_api_invalid(err, "renderer", PROBLEM_NOT_APP_CONTEXT,
                              "sc_draw_gl draws into an application's context "
                              "(sc_context_desc.get_proc_address); use sc_draw or sc_render");
    for (int i = 0; i < 16; i++)
        if (!isfinite(desc->view[i]) || !isfinite(desc->projection[i]))
            return sc_api_invalid(err, "sc_gl_draw_desc", PROBLEM_CAMERA,
                                  "%s[%d] is not finite", isfinite(desc->view[i]) ? "projection" : "view", i);
    return sc_renderer_draw_app(r->renderer, desc->view, desc->projection, err);
}

/* The frame of the renderer's last draw; render_ms is the caller's. */
static int read_frame(renderer_object *r, double render_ms, sc_frame_id *out, sc_error *err)
{
    if (sc_api_make_current(r->context, err) != SC_OK)
        return SC_FAIL;
    frame_object *f = sc_alloc(1, sizeof *f);
    sc_image image = {0};
    sc_gl_state saved;
    int app = sc_gl_context_is_app(r->context->gl);
    const sc_gl *gl = sc_gl_context_gl(r->context->gl);
    if (app)
        sc_gl_state_save(gl, &saved);
    int status = sc_renderer_read(r->renderer, &image, &f->aov, err);
    if (app)
        sc_gl_state_restore(gl, &saved);
    if (status != SC_OK) {
        sc_image_free(&image);
        sc_aov_free(&f->aov);
        free(f);
        return SC_FAIL;
    }
    f->render_ms = render_ms;
    if (image.channels == 4) {
        f->rgba = image;
    } else {
        expand_to_rgba(&image, &f->rgba);
        sc_image_free(&image);
    }
    return add_frame(f, out, err);
}

int sc_read_frame(sc_renderer_id renderer, sc_frame_id *out, sc_error *err)
{
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    renderer_object *r = sc_api_pool_get(&sc_api_renderers, renderer.id, err);
    return r ? read_frame(r, 0, out, err) : SC_FAIL;
}

int sc_render(sc_renderer_id renderer, const sc_camera_desc *camera, sc_frame_id *out,
              sc_error *err)
{
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    double t0 = sc_now();
    if (draw(renderer, camera, 1, err) != SC_OK)
        return SC_FAIL;
    /* draw found the handle valid. */
    renderer_object *r = sc_api_pool_get(&sc_api_renderers, renderer.id, NULL);
    return read_frame(r, 1e3 * (sc_now() - t0), out, err);
}

int sc_render_reference(sc_scene_id scene, const sc_camera_desc *camera,
                        const sc_reference_desc *desc, sc_frame_id *out, sc_error *err)
{
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    scene_object *s = sc_api_pool_get(&sc_api_scenes, scene.id, err);
    sc_camera cam;
    if (!s || sc_api_make_camera(camera, &s->scene, &cam, err) != SC_OK)
        return SC_FAIL;
    if (desc && sc_api_check_int(desc->threads, 0, 1024, "sc_reference_desc.threads", err))
        return SC_FAIL;
    sc_refcast *rc;
    if (sc_refcast_prepare(&s->scene, &rc, err) != SC_OK)
        return SC_FAIL;
    frame_object *f = sc_alloc(1, sizeof *f);
    sc_refcast_options opt = {0};
    if (desc) {
        opt.threads = desc->threads;
        opt.progress = desc->progress;
        opt.progress_user = desc->progress_user;
    }
    double t0 = sc_now();
    sc_refcast_stats stats;
    int status = sc_refcast_render(rc, &cam, &opt, &f->aov, &stats, err);
    sc_refcast_free(rc);
    if (status != SC_OK) {
        sc_aov_free(&f->aov);
        free(f);
        return SC_FAIL;
    }
    f->render_ms = 1e3 * (sc_now() - t0);
    f->reference = (sc_reference_stats){
        .seconds = stats.seconds,
        .rays = stats.rays,
        .hits = stats.hits,
        .subdivisions = stats.subdivisions,
        .over_budget = stats.over_budget,
        .threads = stats.threads,
    };
    sc_image rgb;
    sc_shade_aov(&f->aov, &s->scene, &rgb);
    f->opaque = 1;
    expand_to_rgba(&rgb, &f->rgba);
    sc_image_free(&rgb);
    return add_frame(f, out, err);
}

/* ---- frames ---- */

int sc_load_frame(const char *aov_path, sc_frame_id *out, sc_error *err)
{
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    if (!aov_path)
        return sc_api_invalid(err, "aov_path", PROBLEM_NULL, NULL);
    frame_object *f = sc_alloc(1, sizeof *f);
    if (sc_aov_read(aov_path, &f->aov, err) != SC_OK) {
        sc_aov_free(&f->aov);
        free(f);
        return SC_FAIL;
    }
    sc_image rgb;
    sc_shade_aov(&f->aov, NULL, &rgb);
    f->opaque = 1;
    expand_to_rgba(&rgb, &f->rgba);
    sc_image_free(&rgb);
    return add_frame(f, out, err);
}

void sc_destroy_frame(sc_frame_id frame)
{
    frame_object *f = sc_api_pool_get(&sc_api_frames, frame.id, NULL);
    if (!f)
        return;
    sc_api_pool_remove(&sc_api_frames, frame.id);
    sc_image_free(&f->rgba);
    sc_aov_free(&f->aov);
    free(f);
}

int sc_query_frame_info(sc_frame_id frame, sc_frame_info *info, sc_error *err)
{
    frame_object *f = sc_api_pool_get(&sc_api_frames, frame.id, err);
    if (!f)
        return SC_FAIL;
    if (!info)
        return sc_api_invalid(err, "info", PROBLEM_NULL, NULL);
    const sc_aov *a = &f->aov;
    *info = (sc_frame_info){
        .width = a->width,
        .height = a->height,
        .fovy_deg = a->camera.fovy_deg,
        .rgba = f->rgba.pixels,
        .surface = a->surface,
        .uv = a->uv,
        .t = a->t,
        .point = a->point,
        .normal = a->normal,
        .iters = a->has_iters ? a->iters : NULL,
        .render_ms = f->render_ms,
        .reference = f->reference,
    };
    sc_camera_format(&a->camera, info->camera, sizeof info->camera);
    memcpy(info->eye, a->camera.eye, sizeof info->eye);
    memcpy(info->target, a->camera.target, sizeof info->target);
    return SC_OK;
}

int sc_save_png(sc_frame_id frame, const char *path, sc_error *err)
{
    frame_object *f = sc_api_pool_get(&sc_api_frames, frame.id, err);
    if (!f)
        return SC_FAIL;
    if (!path)
        return sc_api_invalid(err, "path", PROBLEM_NULL, NULL);
    if (!f->opaque)
        return sc_png_write(path, &f->rgba, err);
    /* The alpha of a shaded frame says nothing: the PNG of `ref` is RGB. */
    sc_image rgb;
    size_t n = (size_t)f->rgba.width * (size_t)f->rgba.height;
    sc_image_alloc(&rgb, f->rgba.width, f->rgba.height, 3);
    for (size_t p = 0; p < n; p++)
        memcpy(rgb.pixels + 3 * p, f->rgba.pixels + 4 * p, 3);
    int status = sc_png_write(path, &rgb, err);
    sc_image_free(&rgb);
    return status;
}

int sc_save_aov(sc_frame_id frame, const char *path, sc_error *err)
{
    frame_object *f = sc_api_pool_get(&sc_api_frames, frame.id, err);
    if (!f)
        return SC_FAIL;
    if (!path)
        return sc_api_invalid(err, "path", PROBLEM_NULL, NULL);
    return sc_aov_write(path, &f->aov, err);
}

int sc_compare_frames(sc_frame_id reference, sc_frame_id test, sc_comparison *out,
                      sc_error *err)
{
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    memset(out, 0, sizeof *out);
    frame_object *ref = sc_api_pool_get(&sc_api_frames, reference.id, err);
    frame_object *tst = ref ? sc_api_pool_get(&sc_api_frames, test.id, err) : NULL;
    sc_accuracy acc;
    if (!tst || sc_accuracy_compare(&ref->aov, &tst->aov, &acc, err) != SC_OK)
        return SC_FAIL;
    *out = (sc_comparison){
        .reference_hits = acc.ref_hits,
        .test_hits = acc.test_hits,
        .both_hit = acc.both_hit,
        .holes = acc.holes,
        .false_hits = acc.false_hits,
        .off = acc.off,
        .coverage_pct = acc.coverage_pct,
        .fail_pct = acc.fail_pct,
        .pos_median_px = acc.pos_median_px,
        .pos_max_px = acc.pos_max_px,
        .normal_mean_deg = acc.normal_mean_deg,
        .normal_max_deg = acc.normal_max_deg,
        .pos_p99_px = acc.pos_p99_px,
        .normal_p99_deg = acc.normal_p99_deg,
        .has_iters = acc.has_iters,
        .iters_mean = acc.iters_mean,
        .iters_max = acc.iters_max,
    };
    sc_accuracy_format(&acc, out->line, sizeof out->line);
    return SC_OK;
}

/* ---- shutdown ---- */

static void destroy_all(pool *p, void (*destroy)(uint32_t id))
{
    for (int i = 0; i < p->count; i++)
        if (p->slots[i].object)
            destroy(sc_api_slot_id(p, i));
    free(p->slots);
    p->slots = NULL;
    p->count = 0;
}

static void destroy_frame_id(uint32_t id) { sc_destroy_frame((sc_frame_id){id}); }
static void destroy_renderer_id(uint32_t id) { sc_destroy_renderer((sc_renderer_id){id}); }
static void destroy_context_id(uint32_t id) { sc_destroy_context((sc_context_id){id}); }
static void destroy_scene_id(uint32_t id) { sc_destroy_scene((sc_scene_id){id}); }

void sc_shutdown(void)
{
    destroy_all(&sc_api_frames, destroy_frame_id);
    destroy_all(&sc_api_renderers, destroy_renderer_id);
    sc_api_destroy_peers(NULL);
    /* Contexts take their programs with them. */
    destroy_all(&sc_api_contexts, destroy_context_id);
    free(sc_api_programs.slots);
    sc_api_programs.slots = NULL;
    sc_api_programs.count = 0;
    destroy_all(&sc_api_scenes, destroy_scene_id);
}
