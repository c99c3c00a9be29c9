/* dirt-view's camera: which one the window shows (the scene's default,
 * the automatic one, a scene camera, the free camera), applied to the
 * sessions, and said as dirt-render options (view.h). */
#include <stdio.h>

#include "app/view.h"
#include "app/view_camera.h"

bool view_apply_camera(viewer *v, dirt_session *s)
{
    if (v->cam_mode == CAM_LOOK) {
        dirt_camera c;
        dirt_camera_from_look(&v->look, &c);
        return dirt_session_set_camera(s, DIRT_CAMERA_EXPLICIT, 0, &c);
    }
    enum dirt_camera_choice ch = v->cam_mode == CAM_SCENE ? DIRT_CAMERA_SCENE
                                 : v->cam_mode == CAM_AUTO ? DIRT_CAMERA_AUTO
                                                           : DIRT_CAMERA_DEFAULT;
    return dirt_session_set_camera(s, ch, v->cam_index, NULL);
}

void view_current_look(const viewer *v, dirt_camera_look *look)
{
    if (v->cam_mode == CAM_LOOK) {
        *look = v->look;
        return;
    }
    const dirt_camera *c = dirt_session_camera(v->s);
    const dirt_frame *f = dirt_session_frame(v->s);
    float d = 0;
    for (int k = 0; k < 3; k++)
        d += (0.5f * (f->bounds_min[k] + f->bounds_max[k]) - c->eye[k]) * c->forward[k];
    vcam_from_camera(look, c, d > 0 ? d : 0.5f * v->diag);
}

/* Switches to the free camera, starting from what is shown now. */
void view_to_look(viewer *v)
{
    if (v->cam_mode == CAM_LOOK)
        return;
    view_current_look(v, &v->look);
    v->cam_mode = CAM_LOOK;
}

/* Back to the command line's camera. */
void view_reset_camera(viewer *v)
{
    enum dirt_camera_choice c = app_camera_choice(&v->o);
    v->cam_mode = c == DIRT_CAMERA_SCENE ? CAM_SCENE
                  : c == DIRT_CAMERA_AUTO ? CAM_AUTO
                  : c == DIRT_CAMERA_EXPLICIT ? CAM_LOOK
                                              : CAM_DEFAULT;
    v->cam_index = v->o.camera >= 0 ? v->o.camera : 0;
    if (v->cam_mode == CAM_LOOK)
        v->look = v->o.look;
    v->cam_dirty = true;
}

void view_cycle_camera(viewer *v)
{
    size_t n = dirt_scene_num_cameras(v->scene);
    if (!n) {
        view_status(v, "the scene has no cameras");
        return;
    }
    v->cam_index = v->cam_mode == CAM_SCENE ? (int)((v->cam_index + 1) % n) : 0;
    v->cam_mode = CAM_SCENE;
    v->cam_dirty = true;
    view_status(v, "scene camera %d", v->cam_index);
}

void view_camera_args(const viewer *v, char *buf, size_t size)
{
    switch (v->cam_mode) {
    case CAM_LOOK:
        vcam_format(&v->look, buf, size);
        break;
    case CAM_SCENE:
        snprintf(buf, size, "--camera %d", v->cam_index);
        break;
    case CAM_AUTO:
        snprintf(buf, size, "--auto-camera");
        break;
    default:
        buf[0] = '\0';
    }
}
