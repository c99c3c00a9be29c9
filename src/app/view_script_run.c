/* dirt-view's script (view.h, the parser in view_script.c): its actions
 * run as the frames pass, waiting for frames, samples or files; its `set`
 * and `key` actions are tried before the window opens. */
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "app/cli.h"
#include "app/view.h"
#include "app/view_camera.h"

/* Runs script actions until one waits; false on a failed action (the
 * viewer then quits with exit status 1). */
bool view_run_script(viewer *v)
{
    if (v->wait_frames > 0) {
        v->wait_frames--;
        return true;
    }
    if (v->wait_file[0]) {
        if (access(v->wait_file, F_OK) != 0)
            return true;
        v->wait_file[0] = '\0';
    }
    if (v->wait_samples > 0) {
        /* The image shown: the main session's, and the comparison's too. */
        dirt_session *both[2] = {v->s, v->cmp};
        for (int i = 0; i < 2; i++) {
            if (!both[i])
                continue;
            int have = dirt_session_samples(both[i]), target = view_target(v, both[i]);
            if (have < v->wait_samples && (target == 0 || have < target))
                return true;
        }
        v->wait_samples = 0;
    }
    while (v->next_action < v->script.count) {
        const vs_action *a = &v->script.actions[v->next_action++];
        switch (a->kind) {
        case VS_WAIT_FRAMES:
            v->wait_frames = (long)a->num[0];
            if (v->wait_frames > 0) {
                v->wait_frames--;
                return true;
            }
            break;
        case VS_WAIT_SAMPLES:
            v->wait_samples = (int)a->num[0];
            return true;
        case VS_WAIT_FILE:
            snprintf(v->wait_file, sizeof(v->wait_file), "%s", a->text);
            return true;
        case VS_ORBIT:
            view_to_look(v);
            vcam_orbit(&v->look, (float)a->num[0], (float)a->num[1]);
            v->cam_dirty = true;
            break;
        case VS_PAN:
            view_to_look(v);
            vcam_pan(&v->look, (float)a->num[0], (float)a->num[1]);
            v->cam_dirty = true;
            break;
        case VS_DOLLY:
            view_to_look(v);
            vcam_dolly(&v->look, (float)a->num[0]);
            v->cam_dirty = true;
            break;
        case VS_FLY:
            view_to_look(v);
            vcam_fly(&v->look, (float)a->num[0], (float)a->num[1], (float)a->num[2]);
            v->cam_dirty = true;
            break;
        case VS_CAMERA:
            v->cam_mode = !strcmp(a->name, "auto")      ? CAM_AUTO
                          : !strcmp(a->name, "default") ? CAM_DEFAULT
                                                        : CAM_SCENE;
            v->cam_index = (int)a->num[0];
            if (v->cam_mode == CAM_SCENE &&
                (size_t)v->cam_index >= dirt_scene_num_cameras(v->scene)) {
                cli_error(PROG, "script line %d: the scene has %zu camera(s)", a->line,
                          dirt_scene_num_cameras(v->scene));
                return false;
            }
            v->cam_dirty = true;
            break;
        case VS_KEY: {
            /* Down in this frame (the toggles act), held for num[0] frames. */
            unsigned char mods;
            enum dirt_key k = view_key_parse(a->name, &mods);
            v->held[k] = (int)a->num[0];
            v->pressed[k] = true;
            v->pressed_mods[k] = mods;
            break;
        }
        case VS_BOOKMARK:
            if (!strcmp(a->name, "save"))
                view_bookmark_save(v, (int)a->num[0]);
            else if (!strcmp(a->name, "go") && !view_bookmark_go(v, (int)a->num[0])) {
                cli_error(PROG, "script line %d: bookmark %d is empty", a->line, (int)a->num[0]);
                return false;
            } else if (!strcmp(a->name, "delete"))
                view_bookmark_delete(v, (int)a->num[0]);
            break;
        case VS_ZOOM:
            view_zoom_at(v, a->name[0] ? 0 : a->num[0], a->num[1] >= 0 ? a->num[1] : v->win_w / 2.0,
                         a->num[2] >= 0 ? a->num[2] : v->win_h / 2.0);
            break;
        case VS_PAN_IMAGE:
            view_pan_image(v, a->num[0], a->num[1]);
            break;
        case VS_CLICK:
            v->click_pending = true;
            v->click_x = a->num[0];
            v->click_y = a->num[1];
            break;
        case VS_SET: {
            enum app_opt id = app_find(&app_view_program, a->name, APP_USE_RUNTIME);
            if (!app_set(&app_view_program, a->name, a->text, APP_USE_RUNTIME, &v->o))
                return false;
            if (id == APP_OPT_CAMERA) {
                v->cam_mode = CAM_SCENE;
                v->cam_index = v->o.camera;
                v->cam_dirty = true;
            }
            if (id == APP_OPT_EYE || id == APP_OPT_LOOK_AT || id == APP_OPT_UP ||
                id == APP_OPT_FOV || id == APP_OPT_ZNEAR || id == APP_OPT_ZFAR) {
                view_to_look(v);
                v->look.fov_deg = v->o.look.fov_deg > 0 ? v->o.look.fov_deg : v->look.fov_deg;
                if (v->o.given[APP_OPT_EYE])
                    memcpy(v->look.eye, v->o.look.eye, sizeof(v->look.eye));
                if (v->o.given[APP_OPT_LOOK_AT])
                    memcpy(v->look.target, v->o.look.target, sizeof(v->look.target));
                memcpy(v->look.up, v->o.look.up, sizeof(v->look.up));
                if (v->o.look.znear > 0)
                    v->look.znear = v->o.look.znear;
                if (v->o.look.zfar > 0)
                    v->look.zfar = v->o.look.zfar;
                v->cam_dirty = true;
            }
            break;
        }
        case VS_RESIZE:
            dirt_gpu_window_set_size(v->gpu, (int)a->num[0], (int)a->num[1]);
            break;
        case VS_SCREENSHOT:
            v->hold = true;
            if (!cli_creatable(PROG, a->text))
                return false;
            view_screenshot(v, a->text);
            return true; /* taken at the end of this frame: the next actions wait */
        case VS_SAVE_IMAGE:
            v->hold = true;
            if (!view_save_render(v, a->text))
                return false;
            break;
        case VS_REPORT:
            v->hold = true;
            if (!view_write_report(v, a->text))
                return false;
            break;
        case VS_PRINT_CAMERA: {
            char cam[1024];
            view_camera_args(v, cam, sizeof(cam));
            printf("camera: %s\n", cam);
            break;
        }
        case VS_QUIT:
            v->quit = v->hold = true; /* --save-image at exit gets this image */
            return true;
        }
    }
    return true;
}

/* The script's `set` and `key` actions, tried on a copy of the options and
 * names, and its output paths (screenshot, save-image, report: creatable,
 * parent folders made), before the window opens. */
bool view_check_script(const view_script *sc, const app_opts *o)
{
    static app_opts scratch; /* large: its lists */
    scratch = *o;
    for (size_t i = 0; i < sc->count; i++) {
        const vs_action *a = &sc->actions[i];
        unsigned char mods;
        if (a->kind == VS_KEY && view_key_parse(a->name, &mods) == DIRT_KEY_NONE) {
            cli_error(PROG, "script line %d: unknown key '%s'", a->line, a->name);
            return false;
        }
        bool output = a->kind == VS_SCREENSHOT || a->kind == VS_SAVE_IMAGE ||
                      a->kind == VS_REPORT;
        if (output && !cli_creatable(PROG, a->text)) {
            cli_error(PROG, "script line %d: '%s' cannot be written", a->line, a->text);
            return false;
        }
        if (a->kind != VS_SET)
            continue;
        if (app_find(&app_view_program, a->name, APP_USE_RUNTIME) == APP_OPT_NONE) {
            cli_error(PROG, "script line %d: '%s' is not an option `set` can change", a->line,
                      a->name);
            return false;
        }
        if (!app_set(&app_view_program, a->name, a->text, APP_USE_RUNTIME, &scratch)) {
            cli_error(PROG, "script line %d: bad value", a->line);
            return false;
        }
    }
    return true;
}
