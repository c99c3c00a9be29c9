/* dirt-view's camera bookmarks (view.h): nine slots of the free camera and
 * the lens, kept in "<scene>.bookmarks.json" beside the scene (the default
 * scene's in memory only).
 *
 * The file (cJSON), written whole and atomically on every change:
 *   {"format": "dirt-view bookmarks", "version": 1,
 *    "bookmarks": [{"slot": 1..9, "eye": [x,y,z], "look_at": [x,y,z],
 *                   "up": [x,y,z], "fov": degrees, "znear": z, "zfar": z,
 *                   "aperture": a, "focus": f,
 *                   "camera_args": "--eye ... (dirt-render's options)"}, ...]}
 * Reading takes every field but camera_args (said for a person); a file of
 * another version, or one with any field missing or out of range, is
 * malformed as a whole: no bookmark of it is taken and the file is never
 * written over. */
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "app/view.h"
#include "app/view_camera.h"
#include "dirt/file.h"
#include "dirt/input.h"

#define BM_VERSION 1
#define BM_MAX_BYTES ((size_t)1 << 20)

void view_bookmarks_path(const char *scene_path, char *buf, size_t size)
{
    if (!scene_path || !strcmp(scene_path, "default"))
        buf[0] = '\0';
    else
        snprintf(buf, size, "%s.bookmarks.json", scene_path);
}

static bool vec3(const cJSON *o, const char *key, float out[3])
{
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!cJSON_IsArray(a) || cJSON_GetArraySize(a) != 3)
        return false;
    for (int k = 0; k < 3; k++) {
        const cJSON *e = cJSON_GetArrayItem(a, k);
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble) || fabs(e->valuedouble) > 3e38)
            return false;
        out[k] = (float)e->valuedouble;
    }
    return true;
}

static bool number(const cJSON *o, const char *key, double lo, double hi, float *out)
{
    const cJSON *e = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!cJSON_IsNumber(e) || !(e->valuedouble >= lo && e->valuedouble <= hi))
        return false;
    *out = (float)e->valuedouble;
    return true;
}

/* Parses the file's text into `bm` (all slots); false with why. */
static bool parse(const char *text, struct view_bookmark bm[NUM_BOOKMARKS], char *why,
                  size_t size)
{
    cJSON *root = cJSON_Parse(text);
    bool ok = false;
    if (!root) {
        snprintf(why, size, "not JSON");
        goto done;
    }
    const cJSON *ver = cJSON_GetObjectItemCaseSensitive(root, "version");
    if (!cJSON_IsNumber(ver) || ver->valuedouble != BM_VERSION) {
        snprintf(why, size, "no \"version\": %d", BM_VERSION);
        goto done;
    }
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(root, "bookmarks");
    if (!cJSON_IsArray(list)) {
        snprintf(why, size, "no \"bookmarks\" list");
        goto done;
    }
    int i = 0;
    const cJSON *b;
    cJSON_ArrayForEach(b, list) {
        i++;
        const cJSON *slot = cJSON_GetObjectItemCaseSensitive(b, "slot");
        if (!cJSON_IsNumber(slot) || slot->valuedouble != floor(slot->valuedouble) ||
            slot->valuedouble < 1 || slot->valuedouble > NUM_BOOKMARKS) {
            snprintf(why, size, "bookmark %d: \"slot\" is not 1 .. %d", i, NUM_BOOKMARKS);
            goto done;
        }
        struct view_bookmark *m = &bm[(int)slot->valuedouble - 1];
        if (m->set) {
            snprintf(why, size, "bookmark %d: slot %d twice", i, (int)slot->valuedouble);
            goto done;
        }
        memset(m, 0, sizeof(*m));
        dirt_camera_look *l = &m->look;
        if (!vec3(b, "eye", l->eye) || !vec3(b, "look_at", l->target) || !vec3(b, "up", l->up) ||
            !number(b, "fov", 1e-3, 179.9, &l->fov_deg) ||
            !number(b, "znear", 0, 3e38, &l->znear) || !number(b, "zfar", 0, 3e38, &l->zfar) ||
            !number(b, "aperture", 0, 3e38, &m->aperture) ||
            !number(b, "focus", 0, 3e38, &m->focus)) {
            snprintf(why, size, "bookmark %d: eye, look_at, up (3 numbers each), fov (0 .. 180), "
                     "znear, zfar, aperture, focus (>= 0) are not all there", i);
            goto done;
        }
        double d2 = 0, u2 = 0, c2 = 0, d[3];
        for (int k = 0; k < 3; k++) {
            d[k] = (double)l->target[k] - l->eye[k];
            d2 += d[k] * d[k];
            u2 += (double)l->up[k] * l->up[k];
        }
        double c[3] = {d[1] * l->up[2] - d[2] * l->up[1], d[2] * l->up[0] - d[0] * l->up[2],
                       d[0] * l->up[1] - d[1] * l->up[0]};
        for (int k = 0; k < 3; k++)
            c2 += c[k] * c[k];
        if (!(d2 > 0) || !(u2 > 0) || !(c2 > 1e-12 * d2 * u2)) {
            snprintf(why, size, "bookmark %d: the eye is the target, or up is along the view", i);
            goto done;
        }
        m->set = true;
    }
    ok = true;
done:
    cJSON_Delete(root);
    return ok;
}

void view_bookmarks_open(viewer *v, const char *scene_path)
{
    memset(v->bookmarks, 0, sizeof(v->bookmarks));
    v->bm_keep_file = false;
    view_bookmarks_path(scene_path, v->bm_path, sizeof(v->bm_path));
    if (!v->bm_path[0]) {
        snprintf(v->bm_note, sizeof(v->bm_note),
                 "the default scene: bookmarks are kept in memory only");
        return;
    }
    enum dirt_input_error e;
    size_t len = 0;
    char *text = dirt_input_read(v->bm_path, BM_MAX_BYTES, &len, &e);
    char why[512];
    if (!text && e == DIRT_INPUT_ERR_MISSING) {
        snprintf(v->bm_note, sizeof(v->bm_note), "file: %s (none yet)", v->bm_path);
        return;
    }
    if (!text)
        snprintf(why, sizeof(why), "%s: %s%s%s", dirt_input_error_name(e), dirt_input_error_str(e),
                 e == DIRT_INPUT_ERR_IO ? ": " : "", e == DIRT_INPUT_ERR_IO ? strerror(errno) : "");
    else if (memchr(text, '\0', len))
        snprintf(why, sizeof(why), "INVALID: not text");
    struct view_bookmark bm[NUM_BOOKMARKS] = {0};
    char inner[400];
    bool ok = text && !memchr(text, '\0', len) && parse(text, bm, inner, sizeof(inner));
    if (text && !ok && !memchr(text, '\0', len))
        snprintf(why, sizeof(why), "INVALID: %s", inner);
    free(text);
    if (!ok) {
        v->bm_keep_file = true;
        cli_error(PROG, "bookmarks '%s' not read (%s); no bookmarks, and the file is left as it "
                  "is (not written in this session)", v->bm_path, why);
        snprintf(v->bm_note, sizeof(v->bm_note), "%s not read (%s): bookmarks in memory only, "
                 "the file is left as it is", v->bm_path, why);
        return;
    }
    memcpy(v->bookmarks, bm, sizeof(bm));
    int n = 0;
    for (int i = 0; i < NUM_BOOKMARKS; i++)
        n += bm[i].set;
    snprintf(v->bm_note, sizeof(v->bm_note), "file: %s (%d read)", v->bm_path, n);
    if (!v->o.quiet)
        fprintf(stderr, "%s: %d camera bookmark(s) from %s\n", PROG, n, v->bm_path);
}

static cJSON *to_json(const struct view_bookmark bm[NUM_BOOKMARKS])
{
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "format", "dirt-view bookmarks");
    cJSON_AddNumberToObject(root, "version", BM_VERSION);
    cJSON *list = cJSON_AddArrayToObject(root, "bookmarks");
    for (int i = 0; list && i < NUM_BOOKMARKS; i++) {
        if (!bm[i].set)
            continue;
        const dirt_camera_look *l = &bm[i].look;
        cJSON *b = cJSON_CreateObject();
        cJSON_AddItemToArray(list, b);
        cJSON_AddNumberToObject(b, "slot", i + 1);
        cJSON_AddItemToObject(b, "eye", cJSON_CreateFloatArray(l->eye, 3));
        cJSON_AddItemToObject(b, "look_at", cJSON_CreateFloatArray(l->target, 3));
        cJSON_AddItemToObject(b, "up", cJSON_CreateFloatArray(l->up, 3));
        cJSON_AddNumberToObject(b, "fov", l->fov_deg);
        cJSON_AddNumberToObject(b, "znear", l->znear);
        cJSON_AddNumberToObject(b, "zfar", l->zfar);
        cJSON_AddNumberToObject(b, "aperture", bm[i].aperture);
        cJSON_AddNumberToObject(b, "focus", bm[i].focus);
        char args[1024];
        vcam_format(l, args, sizeof(args));
        cJSON_AddStringToObject(b, "camera_args", args);
    }
    return root;
}

/* Writes every bookmark to the file (or says why it stays in memory). */
static void store(viewer *v, const char *what)
{
    if (!v->bm_path[0]) {
        view_status(v, "%s (the default scene: in memory only)", what);
        return;
    }
    if (v->bm_keep_file) {
        view_status(v, "%s in memory only: %s could not be read, so it is not written over",
                    what, v->bm_path);
        return;
    }
    cJSON *root = to_json(v->bookmarks);
    char *text = root ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    size_t n = text ? strlen(text) : 0;
    char *line = text ? realloc(text, n + 2) : NULL;
    if (line) {
        line[n] = '\n', line[n + 1] = '\0';
        text = line;
    }
    bool ok = line && dirt_write_file_atomic(v->bm_path, text, n + 1);
    free(text);
    if (ok)
        view_status(v, "%s (%s)", what, v->bm_path);
    else
        view_status(v, "%s in memory only: cannot write %s (see the log)", what, v->bm_path);
}

static bool slot_ok(viewer *v, int slot)
{
    if (slot >= 1 && slot <= NUM_BOOKMARKS)
        return true;
    view_status(v, "bookmark %d: slots are 1 .. %d", slot, NUM_BOOKMARKS);
    return false;
}

bool view_bookmark_save(viewer *v, int slot)
{
    if (!slot_ok(v, slot))
        return false;
    struct view_bookmark *m = &v->bookmarks[slot - 1];
    view_current_look(v, &m->look);
    m->aperture = v->o.s.aperture > 0 ? v->o.s.aperture : 0;
    m->focus = v->o.s.focus > 0 ? v->o.s.focus : 0;
    m->set = true;
    char what[64];
    snprintf(what, sizeof(what), "bookmark %d saved", slot);
    store(v, what);
    return true;
}

bool view_bookmark_go(viewer *v, int slot)
{
    if (!slot_ok(v, slot))
        return false;
    const struct view_bookmark *m = &v->bookmarks[slot - 1];
    if (!m->set) {
        view_status(v, "bookmark %d is empty (Ctrl + %d saves it)", slot, slot);
        return false;
    }
    v->look = m->look;
    v->cam_mode = CAM_LOOK;
    v->o.s.aperture = m->aperture;
    v->o.s.focus = m->focus;
    v->cam_dirty = true;
    view_status(v, "bookmark %d", slot);
    return true;
}

bool view_bookmark_delete(viewer *v, int slot)
{
    if (!slot_ok(v, slot))
        return false;
    if (!v->bookmarks[slot - 1].set) {
        view_status(v, "bookmark %d is empty", slot);
        return false;
    }
    memset(&v->bookmarks[slot - 1], 0, sizeof(v->bookmarks[0]));
    char what[64];
    snprintf(what, sizeof(what), "bookmark %d deleted", slot);
    store(v, what);
    return true;
}
