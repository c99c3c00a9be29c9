/* Loads every glTF test asset of ../shared and checks triangle counts against
 * ../shared/scenes/CREDITS.md, materials/textures of the richer files, and
 * that evaluated frames are finite with unit normals. */
#include "check.h"

#include "dirt/log.h"
#include "dirt/scene.h"
#include "scene/scene_internal.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

typedef struct asset {
    const char *path;           /* under scenes/ */
    size_t credits_triangles;   /* the CREDITS.md table: each mesh counted once */
    size_t frame_triangles;     /* per frame: every mesh instance */
} asset;

/* CesiumMilkTruck: the table's 2,856 counts the "Wheels" mesh (768) once, but
 * two nodes instance it, so a frame has 2856 + 768 = 3624 triangles. */
static const asset assets[] = {
    {"gltf/Fox/Fox.glb", 576, 576},
    {"gltf/CesiumMan/CesiumMan.glb", 4672, 4672},
    {"gltf/CesiumMan/glTF/CesiumMan.gltf", 4672, 4672},
    {"gltf/BoxAnimated/BoxAnimated.gltf", 254, 254},
    {"gltf/AnimatedTriangle/AnimatedTriangle.gltf", 1, 1},
    {"gltf/SimpleSkin/SimpleSkin.gltf", 8, 8},
    {"gltf/RiggedSimple/RiggedSimple.gltf", 188, 188},
    {"gltf/RiggedFigure/RiggedFigure.gltf", 256, 256},
    {"gltf/MorphStressTest/MorphStressTest.gltf", 2412, 2412},
    {"gltf/AnimatedMorphCube/AnimatedMorphCube.gltf", 12, 12},
    {"gltf/CesiumMilkTruck/CesiumMilkTruck.gltf", 2856, 3624},
    {"gltf/FlightHelmet/FlightHelmet.gltf", 94722, 94722},
    {"cornell/CornellBox.glb", 36, 36},
    {"cornell/cornell_box.glb", 4410, 4410},
};

static size_t mesh_triangles(const dirt_scene *s)
{
    size_t n = 0;
    for (size_t i = 0; i < s->num_meshes; i++)
        n += s->meshes[i].num_triangles;
    return n;
}

/* Finite positions, unit normals, valid material/instance indices, bounds
 * containing every position. */
static void check_frame(const dirt_scene *s, const dirt_frame *f, const char *name, float t)
{
    size_t bad_pos = 0, bad_nrm = 0, bad_idx = 0, out_of_bounds = 0;
    CHECK(f->num_triangles == dirt_scene_num_triangles(s));
    for (size_t v = 0; v < 3 * f->num_triangles; v++) {
        const float *p = f->position[v], *n = f->normal[v];
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
            bad_pos++;
        double l = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        if (!(fabs(l - 1.0) < 1e-4))
            bad_nrm++;
        for (int k = 0; k < 3; k++) {
            if (p[k] < f->bounds_min[k] || p[k] > f->bounds_max[k])
                out_of_bounds++;
        }
    }
    for (size_t tri = 0; tri < f->num_triangles; tri++) {
        if (f->material[tri] >= dirt_scene_num_materials(s) ||
            f->instance[tri] >= s->num_instances)
            bad_idx++;
    }
    CHECK_MSG(bad_pos == 0, "%s t=%g: %zu non-finite positions", name, t, bad_pos);
    CHECK_MSG(bad_nrm == 0, "%s t=%g: %zu non-unit normals", name, t, bad_nrm);
    CHECK_MSG(bad_idx == 0, "%s t=%g: %zu bad material/instance indices", name, t, bad_idx);
    CHECK_MSG(out_of_bounds == 0, "%s t=%g: %zu positions outside the bounds", name, t,
              out_of_bounds);
    for (size_t n = 0; n < f->num_nodes; n++) {
        for (int k = 0; k < 16; k++)
            CHECK(isfinite(f->node_world[n][k]));
    }
}

int main(void)
{
    const char *shared = test_shared_dir();
    if (!shared) {
        fprintf(stderr, "no shared assets (DIRT_SHARED_DIR); skipped\n");
        return TEST_SKIP;
    }
    char path[4096];

    for (size_t a = 0; a < sizeof(assets) / sizeof(assets[0]); a++) {
        snprintf(path, sizeof(path), "%s/scenes/%s", shared, assets[a].path);
        clock_t c0 = clock();
        dirt_scene *s = dirt_scene_load(path, NULL);
        double secs = (double)(clock() - c0) / CLOCKS_PER_SEC;
        CHECK_MSG(s != NULL, "cannot load %s", path);
        if (!s)
            continue;
        fprintf(stderr, "%s: %zu triangles, %zu materials, %zu textures, %zu clips, "
                        "%.3f s\n", assets[a].path, dirt_scene_num_triangles(s),
                dirt_scene_num_materials(s), dirt_scene_num_textures(s),
                dirt_scene_num_clips(s), secs);
        CHECK_MSG(dirt_scene_num_triangles(s) == assets[a].frame_triangles,
                  "%s: %zu triangles per frame, expected %zu", assets[a].path,
                  dirt_scene_num_triangles(s), assets[a].frame_triangles);
        CHECK_MSG(mesh_triangles(s) == assets[a].credits_triangles,
                  "%s: %zu mesh triangles, CREDITS.md says %zu", assets[a].path,
                  mesh_triangles(s), assets[a].credits_triangles);
        CHECK(dirt_scene_num_materials(s) >= 1);

        /* Rest pose, the start, middle and end of every clip. */
        dirt_eval_opts rest = {.clip = -1};
        dirt_frame *f = dirt_scene_evaluate(s, 0.0f, &rest);
        CHECK(f != NULL);
        if (f) {
            check_frame(s, f, assets[a].path, -1.0f);
            for (size_t c = 0; c < dirt_scene_num_clips(s); c++) {
                float d = dirt_scene_clip_duration(s, c);
                CHECK(d >= 0.0f && isfinite(d));
                dirt_eval_opts o = {.clip = (int)c};
                float ts[3] = {0.0f, 0.5f * d, d};
                for (int k = 0; k < 3; k++) {
                    CHECK(dirt_scene_evaluate_into(s, ts[k], &o, f));
                    check_frame(s, f, assets[a].path, ts[k]);
                }
            }
            dirt_frame_destroy(f);
        }

        if (strstr(assets[a].path, "CornellBox.glb")) {
            size_t bright = 0;
            const dirt_material *m = dirt_scene_materials(s);
            for (size_t i = 0; i < dirt_scene_num_materials(s); i++) {
                if (m[i].emissive_strength > 1.0f &&
                    (m[i].emissive[0] > 0 || m[i].emissive[1] > 0 || m[i].emissive[2] > 0))
                    bright++;
            }
            CHECK_MSG(bright >= 1, "CornellBox.glb: no material with emissive_strength > 1");
        }
        if (strstr(assets[a].path, "FlightHelmet")) {
            const dirt_material *m = dirt_scene_materials(s);
            const dirt_texture *tex = dirt_scene_textures(s);
            size_t textured = 0;
            for (size_t i = 0; i < dirt_scene_num_materials(s); i++) {
                int t = m[i].base_color_tex;
                if (t == DIRT_NO_TEXTURE || (size_t)t >= dirt_scene_num_textures(s))
                    continue;
                const dirt_texture *x = &tex[t];
                bool ok = x->width > 0 && x->height > 0 && x->rgba && x->srgb;
                /* Decoded pixels: not all one value. */
                bool varied = false;
                for (size_t p = 1; ok && p < (size_t)x->width * x->height && !varied; p++)
                    varied = memcmp(x->rgba, x->rgba + 4 * p, 4) != 0;
                if (ok && varied && m[i].metallic_roughness_tex != DIRT_NO_TEXTURE &&
                    !tex[m[i].metallic_roughness_tex].srgb)
                    textured++;
            }
            CHECK_MSG(textured >= 5, "FlightHelmet: %zu materials with decoded textures",
                      textured);
            CHECK(s->stats.textures_failed == 0);
            CHECK_MSG(secs < 10.0, "FlightHelmet took %.2f s to load", secs);
        }
        if (strstr(assets[a].path, "Fox.glb")) {
            CHECK(dirt_scene_num_clips(s) == 3);
            CHECK(dirt_scene_clip_name(s, 0) && strcmp(dirt_scene_clip_name(s, 0), "Survey") == 0);
        }
        dirt_scene_destroy(s);
    }
    return check_finish();
}
