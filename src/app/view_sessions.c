/* dirt-view's render sessions (view.h): the main one and the raster
 * preview shown while the camera moves, kept in step with the settings
 * (options, time, camera), and the scene they render. */
#include <cjson/cJSON.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "app/setup.h"
#include "app/view.h"
#include "dirt/input.h"

/* The session options the viewer's settings ask for, for `engine`. */
dirt_session_opts view_wanted_opts(const viewer *v, int engine)
{
    dirt_session_opts s = app_session_opts(&v->o);
    s.engine = (enum dirt_engine)engine;
    s.width = v->rw;
    s.height = v->rh;
    if (s.engine != DIRT_ENGINE_MMRT) {
        s.march = 0;
        s.march_samples = 0;
        s.thickness = 0;
    }
    if (!(s.aperture > 0))
        s.focus = 0;
    return s;
}

int view_target(const viewer *v, const dirt_session *s)
{
    return dirt_session_get_opts(s)->engine == DIRT_ENGINE_RASTER ? 1 : v->o.spp;
}

static float scene_diagonal(const dirt_frame *f)
{
    float d2 = 0;
    for (int k = 0; k < 3; k++)
        d2 += (f->bounds_max[k] - f->bounds_min[k]) * (f->bounds_max[k] - f->bounds_min[k]);
    return d2 > 0 ? sqrtf(d2) : 1.0f;
}


/* Makes the main session for the scene (the comparison and the preview
 * follow at the next sync); false after logging. */
static bool make_sessions(viewer *v)
{
    dirt_session_destroy(v->s);
    dirt_session_destroy(v->cmp);
    dirt_session_destroy(v->pre);
    v->s = v->cmp = v->pre = NULL;
    v->cmp_engine = -1;
    v->applied = view_wanted_opts(v, v->o.s.engine);
    v->s = dirt_session_create(v->gpu, v->scene, &v->applied);
    if (!v->s)
        return false;
    v->cam_dirty = v->time_dirty = true;
    v->aux_key = -1;
    v->generation++;
    return true;
}

/* Shows `sc` (taken; loaded from `path`, NULL: the default scene) from
 * its default camera. False after logging. */
bool view_load_scene(viewer *v, dirt_scene *sc, const char *path)
{
    dirt_session_destroy(v->s);
    dirt_session_destroy(v->cmp);
    dirt_session_destroy(v->pre);
    v->s = v->cmp = v->pre = NULL;
    dirt_scene_destroy(v->scene);
    v->scene = sc;
    snprintf(v->scene_name, sizeof(v->scene_name), "%s", path ? path : "default scene");
    if (!make_sessions(v))
        return false;
    v->diag = scene_diagonal(dirt_session_frame(v->s));
    view_reset_camera(v);
    view_bookmarks_open(v, path);
    char title[4200];
    snprintf(title, sizeof(title), "dirt-view: %s", v->scene_name);
    dirt_gpu_window_set_title(v->gpu, title);
    return true;
}

/* Render size: the window's, or the fixed one (height from the camera's
 * aspect when only the width is fixed). */
void view_render_size(viewer *v, int win_w, int win_h)
{
    if (v->o.s.width > 0) {
        v->rw = v->o.s.width;
        v->rh = v->o.s.height;
    } else {
        int sc = v->o.scale > 0 ? v->o.scale : 1;
        v->rw = win_w / sc >= 16 ? win_w / sc : 16;
        v->rh = win_h / sc >= 16 ? win_h / sc : 16;
    }
}

/* Remakes the environment map when its intensity or rotation changed (the
 * map bakes both in); the old one is kept until the sessions have the new
 * one (v->env_old, freed at the end of sync_sessions). False when the map
 * could not be remade (the old settings come back). */
static bool sync_env(viewer *v)
{
    if (!v->o.env_path ||
        (v->o.env_intensity == v->env_intensity && v->o.env_rotation == v->env_rotation))
        return true;
    char why[512];
    dirt_env_opts eo = app_env_opts(&v->o);
    dirt_env *e = dirt_env_load(v->o.env_path, &eo, why, sizeof(why));
    if (!e) {
        view_status(v, "environment: %s", why);
        v->o.env_intensity = v->env_intensity;
        v->o.env_rotation = v->env_rotation;
        return false;
    }
    dirt_env_destroy(v->env_old);
    v->env_old = v->env;
    v->env = e;
    v->o.s.env = e;
    v->env_intensity = v->o.env_intensity;
    v->env_rotation = v->o.env_rotation;
    return true;
}

static bool sync_all(viewer *v);

/* Brings the sessions to the settings; restarts what changed. */
bool view_sync_sessions(viewer *v)
{
    sync_env(v);
    bool ok = sync_all(v);
    /* The replaced map goes once no session holds it. */
    dirt_session *all[] = {v->s, v->cmp, v->pre};
    bool held = false;
    for (int i = 0; i < 3; i++)
        held |= all[i] && dirt_session_get_opts(all[i])->env == v->env_old;
    if (v->env_old && !held) {
        dirt_env_destroy(v->env_old);
        v->env_old = NULL;
    }
    return ok;
}

static bool sync_all(viewer *v)
{
    dirt_session_opts want = view_wanted_opts(v, v->o.s.engine);
    if (memcmp(&want, &v->applied, sizeof(want)) != 0) {
        bool restarted = false;
        if (!dirt_session_set_opts(v->s, &want, &restarted)) {
            view_status(v, "the session refused the settings (see the log); kept the old ones");
            int w = v->o.s.width, h = v->o.s.height;
            v->o.s = v->applied;
            v->o.s.width = w;
            v->o.s.height = h;
            return false;
        }
        v->applied = want;
        v->generation++;
    }
    if (v->time_dirty || v->o.time != v->applied_time || v->o.clip != v->applied_clip ||
        v->o.loop != v->applied_loop) {
        dirt_eval_opts eval = {.clip = v->o.clip, .loop = v->o.loop};
        if (!dirt_session_set_time(v->s, v->o.time, &eval)) {
            view_status(v, "clip %d does not exist; back to clip %d", v->o.clip, v->applied_clip);
            v->o.clip = v->applied_clip;
            return false;
        }
        v->applied_time = v->o.time;
        v->applied_clip = v->o.clip;
        v->applied_loop = v->o.loop;
        v->time_dirty = false;
        v->cam_dirty = true; /* an animated scene camera follows the time */
        if (v->cmp)
            dirt_session_set_time(v->cmp, v->o.time, &eval);
        if (v->pre)
            dirt_session_set_time(v->pre, v->o.time, &eval);
        v->generation++;
    }
    if (v->cam_dirty) {
        if (!view_apply_camera(v, v->s)) {
            view_status(v, "no such camera; back to the default one");
            v->cam_mode = CAM_DEFAULT;
            view_apply_camera(v, v->s);
        }
        if (v->cmp)
            view_apply_camera(v, v->cmp);
        if (v->pre)
            view_apply_camera(v, v->pre);
        v->cam_dirty = false;
        v->generation++;
    }
    if (!view_sync_compare(v))
        return false;
    /* The raster preview, made the first time the camera moves or an
     * accumulation has no completed sample yet. */
    if ((v->moving || dirt_session_samples(v->s) == 0) && !v->o.no_preview &&
        v->applied.engine != DIRT_ENGINE_RASTER) {
        dirt_session_opts po = view_wanted_opts(v, DIRT_ENGINE_RASTER);
        dirt_eval_opts eval = {.clip = v->o.clip, .loop = v->o.loop};
        if (!v->pre) {
            v->pre = dirt_session_create(v->gpu, v->scene, &po);
            if (!v->pre || !dirt_session_set_time(v->pre, v->o.time, &eval) ||
                !view_apply_camera(v, v->pre)) {
                dirt_session_destroy(v->pre);
                v->pre = NULL;
                v->o.no_preview = true;
                view_status(v, "the raster preview could not be made (see the log); off");
            }
        } else if (memcmp(&po, dirt_session_get_opts(v->pre), sizeof(po)) != 0) {
            dirt_session_set_opts(v->pre, &po, NULL);
        }
    }
    return true;
}

/* A new main session from the shader sources, proven by one sample, then
 * the presentation program; on any failure the old ones stay. */
/* The source tree of the meson build tree `dir` (the folder holding
 * meson-info/meson-info.json, whose directories.build is `dir` itself),
 * into `src`; false when `dir` is not a build tree. */
static bool build_tree_source(const char *dir, const struct stat *dir_st, char *src, size_t size)
{
    char info[PATH_MAX + 32];
    snprintf(info, sizeof(info), "%s/meson-info/meson-info.json", dir);
    enum dirt_input_error e;
    size_t len = 0;
    char *text = dirt_input_read(info, (size_t)1 << 20, &len, &e);
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    free(text);
    const cJSON *dirs = cJSON_GetObjectItemCaseSensitive(root, "directories");
    const cJSON *source = cJSON_GetObjectItemCaseSensitive(dirs, "source");
    const cJSON *build = cJSON_GetObjectItemCaseSensitive(dirs, "build");
    struct stat st;
    bool ok = cJSON_IsString(source) && cJSON_IsString(build) &&
              stat(build->valuestring, &st) == 0 && st.st_dev == dir_st->st_dev &&
              st.st_ino == dir_st->st_ino;
    if (ok)
        snprintf(src, size, "%s", source->valuestring);
    cJSON_Delete(root);
    return ok;
}

const char *view_shader_source(char *dir, size_t size, char *why, size_t why_size)
{
    dir[0] = why[0] = '\0';
    const char *env = getenv("DIRT_GLSL_DIR");
    if (env && *env) {
        snprintf(dir, size, "%s", env);
        return "DIRT_GLSL_DIR";
    }
    /* A parent folder of the program's file (the kernel's path, links
     * resolved) that is a meson build tree: meson-info names its source
     * tree. Nothing of the build's paths is stored in the program, so an
     * installed one names no source tree. */
    char exe[PATH_MAX], src[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof(exe) - 1);
    bool inside = false;
    if (n > 0) {
        exe[n] = '\0';
        for (char *slash = strrchr(exe, '/'); slash && slash > exe && !inside;
             slash = strrchr(exe, '/')) {
            *slash = '\0';
            struct stat st;
            inside = stat(exe, &st) == 0 && build_tree_source(exe, &st, src, sizeof(src));
        }
    }
    if (!inside) {
        snprintf(why, why_size, "this dirt-view is not run from a meson build tree, so its "
                 "shaders are the library's embedded ones; run it with DIRT_GLSL_DIR=a source "
                 "tree's glsl/ folder");
        return NULL;
    }
    char glsl[PATH_MAX + 64];
    snprintf(glsl, sizeof(glsl), "%s/glsl/present/present.frag", src);
    struct stat st;
    if (stat(glsl, &st) || !S_ISREG(st.st_mode)) {
        snprintf(why, why_size, "the source tree's shaders (%s/glsl) are not there; run it with "
                 "DIRT_GLSL_DIR=a source tree's glsl/ folder", src);
        return NULL;
    }
    snprintf(dir, size, "%s/glsl", src);
    return "build tree";
}

bool view_reload_shaders(viewer *v)
{
    char dir[4096], why[4400];
    const char *from = view_shader_source(dir, sizeof(dir), why, sizeof(why));
    if (!from) {
        v->shader_reload_failures++;
        view_status(v, "shader reload: unavailable: %s", why);
        snprintf(v->reload_status, sizeof(v->reload_status), "%s", v->status);
        return false;
    }
    /* From the build tree: the source tree's shaders from now on (back to
     * the ones in use if they do not compile). */
    const char *was = dirt_gpu_glsl_dir();
    char before[4096];
    snprintf(before, sizeof(before), "%s", was ? was : "");
    if (strcmp(from, "DIRT_GLSL_DIR"))
        dirt_gpu_set_glsl_dir(dir);
    dirt_eval_opts eval = {.clip = v->applied_clip, .loop = v->applied_loop};
    dirt_session *ns = dirt_session_create(v->gpu, v->scene, &v->applied);
    bool ok = ns && dirt_session_set_time(ns, v->applied_time, &eval) && view_apply_camera(v, ns) &&
              dirt_session_add_samples(ns, 1, NULL, NULL) && dirt_gpu_present_reload(v->gpu);
    if (!ok) {
        dirt_session_destroy(ns);
        if (strcmp(from, "DIRT_GLSL_DIR"))
            dirt_gpu_set_glsl_dir(before[0] ? before : NULL);
        v->shader_reload_failures++;
        view_status(v, "shader reload from %s failed (the compiler's errors are in the log); "
                    "kept the old programs", dir);
        snprintf(v->reload_status, sizeof(v->reload_status), "%s", v->status);
        return false;
    }
    dirt_session_destroy(v->s);
    v->s = ns;
    /* The comparison and the preview are made again at the next sync. */
    dirt_session_destroy(v->cmp);
    dirt_session_destroy(v->pre);
    v->cmp = v->pre = NULL;
    v->cmp_engine = -1;
    v->aux_key = -1;
    v->generation++;
    v->last = *dirt_session_get_stats(v->s);
    v->shader_reloads++;
    view_status(v, "shaders reloaded from %s (%s)", dir, from);
    snprintf(v->reload_status, sizeof(v->reload_status), "%s", v->status);
    return true;
}
