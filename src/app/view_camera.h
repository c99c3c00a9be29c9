/* dirt-view's free camera: orbit, pan, dolly and fly on a dirt_camera_look
 * (the numbers dirt-render's --eye/--look-at/--up/--fov/--znear/--zfar
 * take, so the viewer's camera can be rendered offline exactly). */
#ifndef DIRT_APP_VIEW_CAMERA_H
#define DIRT_APP_VIEW_CAMERA_H

#include <stddef.h>

#include "dirt/scene.h"

/* The look of an evaluated camera: the same eye, the target `distance`
 * along its forward axis, world up (+Y) unless the camera looks along it
 * (then its own up), its field of view and depth range. */
void vcam_from_camera(dirt_camera_look *look, const dirt_camera *cam, float distance);

/* Turns the eye around the target: `yaw` degrees about the up axis, then
 * `pitch` degrees about the camera's right axis (positive = look down
 * from higher up), kept 1 degree away from the poles. */
void vcam_orbit(dirt_camera_look *look, float yaw, float pitch);
/* Moves eye and target across the view: `dx`, `dy` in view heights at the
 * target's distance (positive = the scene moves right / up). */
void vcam_pan(dirt_camera_look *look, float dx, float dy);
/* Scales the eye's distance to the target by `factor` (< 1 = closer). */
void vcam_dolly(dirt_camera_look *look, float factor);
/* Moves eye and target along the view's forward, right and up axes. */
void vcam_fly(dirt_camera_look *look, float forward, float right, float up);
/* Distance from eye to target. */
float vcam_distance(const dirt_camera_look *look);

/* The dirt-render options that give this camera ("--eye X,Y,Z --look-at
 * ... --up ... --fov ... --znear ... --zfar ..."), every float printed so
 * that it reads back to the same bits. */
void vcam_format(const dirt_camera_look *look, char *buf, size_t size);

#endif
