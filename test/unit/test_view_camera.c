/* dirt-view's free camera and script (src/app/view_camera.c, view_script.c):
 * the printed camera reads back to the same camera bit for bit (what makes
 * dirt-render reproduce the viewer's view), orbit keeps the distance and
 * comes back after a full turn, stays off the poles, pan moves eye and
 * target together across the view, dolly scales the distance; the script
 * parser reads every action and names the line of the first bad one. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/view_camera.h"
#include "app/view_script.h"
#include "check.h"

static float dist3(const float a[3], const float b[3])
{
    return sqrtf((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                 (a[2] - b[2]) * (a[2] - b[2]));
}

/* Reads "--eye X,Y,Z --look-at ... --up ... --fov F [--znear Z] [--zfar Z]". */
static bool parse_args(const char *text, dirt_camera_look *l)
{
    memset(l, 0, sizeof(*l));
    int n = sscanf(text, "--eye %f,%f,%f --look-at %f,%f,%f --up %f,%f,%f --fov %f", &l->eye[0],
                   &l->eye[1], &l->eye[2], &l->target[0], &l->target[1], &l->target[2], &l->up[0],
                   &l->up[1], &l->up[2], &l->fov_deg);
    const char *zn = strstr(text, "--znear "), *zf = strstr(text, "--zfar ");
    if (zn)
        l->znear = strtof(zn + 8, NULL);
    if (zf)
        l->zfar = strtof(zf + 7, NULL);
    return n == 10;
}

static void check_round_trip(void)
{
    dirt_camera_look l = {.eye = {0.1f, 1.0f / 3.0f, -2.7182817f}, .target = {1e-7f, 0.5f, 3.14159f},
                          .up = {0, 1, 0}, .fov_deg = 39.597755f, .znear = 0.0123f, .zfar = 97.3f};
    vcam_orbit(&l, 13.7f, -5.1f);
    vcam_pan(&l, 0.013f, -0.021f);
    char text[512];
    vcam_format(&l, text, sizeof(text));
    dirt_camera_look back;
    CHECK_MSG(parse_args(text, &back), "%s", text);
    dirt_camera a, b;
    dirt_camera_from_look(&l, &a);
    dirt_camera_from_look(&back, &b);
    CHECK_MSG(memcmp(&a, &b, sizeof(a)) == 0, "the printed camera is another camera: %s", text);
}

static void check_moves(void)
{
    dirt_camera_look l = {.eye = {0, 1, 5}, .target = {0, 1, 0}, .up = {0, 1, 0}, .fov_deg = 45};
    float d0 = vcam_distance(&l);
    float start[3];
    memcpy(start, l.eye, sizeof(start));
    for (int i = 0; i < 8; i++)
        vcam_orbit(&l, 45, 0);
    CHECK_MSG(dist3(l.eye, start) < 1e-4f, "a full turn ends %g away", dist3(l.eye, start));
    vcam_orbit(&l, 90, 0);
    CHECK(fabsf(l.eye[0] + 5) < 1e-4f || fabsf(l.eye[0] - 5) < 1e-4f); /* a quarter turn */
    CHECK(fabsf(vcam_distance(&l) - d0) < 1e-4f);
    vcam_orbit(&l, 0, 30);
    CHECK(l.eye[1] > 1 + 2.4f && l.eye[1] < 1 + 2.6f); /* 30 degrees up: 5 sin 30 */
    CHECK(fabsf(vcam_distance(&l) - d0) < 1e-4f);
    vcam_orbit(&l, 0, 500); /* clamped 1 degree off the pole */
    float polar = acosf((l.eye[1] - 1) / vcam_distance(&l)) * 57.29578f;
    CHECK_MSG(fabsf(polar - 1) < 0.01f, "polar %g", polar);
    /* Pan: eye and target move by the same vector, across the view. */
    dirt_camera_look p = {.eye = {0, 0, 4}, .target = {0, 0, 0}, .up = {0, 1, 0}, .fov_deg = 90};
    vcam_pan(&p, 0.25f, 0);
    CHECK(fabsf(p.eye[0] - p.target[0]) < 1e-6f && fabsf(p.eye[2] - 4) < 1e-6f);
    /* The view is 2 * 4 * tan(45 deg) = 8 high: a quarter moves 2 to the left. */
    CHECK_MSG(fabsf(p.target[0] + 2) < 1e-5f, "pan moved the target to x = %g", p.target[0]);
    vcam_dolly(&p, 0.5f);
    CHECK(fabsf(vcam_distance(&p) - 2) < 1e-5f);
    vcam_fly(&p, 1, 0, 0);
    CHECK(fabsf(vcam_distance(&p) - 2) < 1e-5f && fabsf(p.eye[2] - 1) < 1e-5f);
}

static void check_script(void)
{
    const char *good = "# a demo\n"
                       "wait-samples 4\n"
                       "  orbit 30 -10   # comment\n"
                       "pan 0.1 0\ndolly 0.5\nfly 1 0 0\ncamera 0\ncamera auto\n"
                       "key W 5\nkey Shift\nclick 10 20\nset engine mmrt\nresize 320 240\n"
                       "screenshot a.png\nsave-image b.exr\nreport c.json\nprint-camera\n"
                       "wait-frames 2\nwait-file /tmp/go\nquit\n";
    view_script s;
    char why[256] = "";
    CHECK_MSG(vs_parse(good, &s, why, sizeof(why)), "%s", why);
    CHECK(s.count == 19);
    const enum vs_kind kinds[] = {VS_WAIT_SAMPLES, VS_ORBIT, VS_PAN, VS_DOLLY, VS_FLY, VS_CAMERA,
                                  VS_CAMERA, VS_KEY, VS_KEY, VS_CLICK, VS_SET, VS_RESIZE,
                                  VS_SCREENSHOT, VS_SAVE_IMAGE, VS_REPORT, VS_PRINT_CAMERA,
                                  VS_WAIT_FRAMES, VS_WAIT_FILE, VS_QUIT};
    for (size_t i = 0; i < s.count && i < 19; i++)
        CHECK_MSG(s.actions[i].kind == kinds[i], "action %zu", i);
    if (s.count == 19) {
        CHECK(s.actions[1].num[0] == 30 && s.actions[1].num[1] == -10 && s.actions[1].line == 3);
        CHECK(!strcmp(s.actions[6].name, "auto") && s.actions[5].num[0] == 0);
        CHECK(s.actions[7].num[0] == 5 && s.actions[8].num[0] == 1);
        CHECK(!strcmp(s.actions[10].name, "engine") && !strcmp(s.actions[10].text, "mmrt"));
        CHECK(!strcmp(s.actions[13].text, "b.exr"));
    }
    vs_free(&s);
    const struct { const char *text; const char *why; } bad[] = {
        {"orbit 1 2\njump 3\n", "line 2: unknown action"},
        {"orbit 1\n", "line 1: orbit takes 2"},
        {"\n\ndolly x\n", "line 3: 'x' is not a number"},
        {"dolly -1\n", "line 1: dolly: value out of range"},
        {"wait-frames 1.5\n", "line 1: wait-frames: value out of range"},
        {"screenshot a.exr\n", "line 1: screenshot takes one .png"},
        {"camera left\n", "line 1: camera 'left'"},
        {"set spp\n", "line 1: set takes an option and a value"},
        {"resize 8 8\n", "line 1: resize: value out of range"},
    };
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
        why[0] = '\0';
        CHECK_MSG(!vs_parse(bad[i].text, &s, why, sizeof(why)), "accepted: %s", bad[i].text);
        CHECK_MSG(strstr(why, bad[i].why) != NULL, "'%s' gave '%s'", bad[i].text, why);
    }
}

int main(void)
{
    check_round_trip();
    check_moves();
    check_script();
    return check_finish();
}
