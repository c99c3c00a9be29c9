/* Loading alpha (doc/scenes.md): glTF alphaMode / alphaCutoff (MASK with
 * and without a cutoff, BLEND, OPAQUE stated and absent, an unknown mode
 * and a negative cutoff: warned, the defaults) and the OBJ/MTL mapping
 * (d and Tr below 1 -> BLEND with that alpha, map_d naming map_Kd's image
 * -> BLEND with the texture's alpha, another map_d -> warned, opaque). */
#include "check.h"
#include "test_scene_util.h"

#include "dirt/image.h"
#include "dirt/scene.h"

static const dirt_material *find(const dirt_scene *s, const char *name)
{
    for (size_t i = 0; i < dirt_scene_num_materials(s); i++) {
        if (!strcmp(dirt_scene_materials(s)[i].name, name))
            return &dirt_scene_materials(s)[i];
    }
    fprintf(stderr, "no material '%s'\n", name);
    return NULL;
}

static void test_gltf(void)
{
    float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    char *uri = data_uri(pos, sizeof(pos));
    char *json = strf(
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
        "{\"POSITION\":0},\"material\":0}]}],"
        "\"materials\":[{\"name\":\"none\"},{\"name\":\"opaque\",\"alphaMode\":\"OPAQUE\"},"
        "{\"name\":\"mask\",\"alphaMode\":\"MASK\",\"alphaCutoff\":0.25},"
        "{\"name\":\"mask_default\",\"alphaMode\":\"MASK\"},"
        "{\"name\":\"blend\",\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":"
        "{\"baseColorFactor\":[1,1,1,0.3]}},"
        "{\"name\":\"bad_mode\",\"alphaMode\":\"FOO\"},"
        "{\"name\":\"bad_cutoff\",\"alphaMode\":\"MASK\",\"alphaCutoff\":-1}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
        "\"min\":[0,0,0],\"max\":[1,1,0]}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
        "\"buffers\":[{\"uri\":\"%s\",\"byteLength\":36}]}", uri);
    log_capture_start();
    dirt_scene *s = dirt_scene_load_memory(json, strlen(json), "alpha.gltf", NULL);
    CHECK(s != NULL);
    if (s) {
        const dirt_material *m;
        CHECK((m = find(s, "none")) && m->alpha_mode == DIRT_ALPHA_OPAQUE && m->alpha_cutoff == 0.5f);
        CHECK((m = find(s, "opaque")) && m->alpha_mode == DIRT_ALPHA_OPAQUE);
        CHECK((m = find(s, "mask")) && m->alpha_mode == DIRT_ALPHA_MASK && m->alpha_cutoff == 0.25f);
        CHECK((m = find(s, "mask_default")) && m->alpha_mode == DIRT_ALPHA_MASK &&
              m->alpha_cutoff == 0.5f);
        CHECK((m = find(s, "blend")) && m->alpha_mode == DIRT_ALPHA_BLEND &&
              m->base_color[3] == 0.3f);
        CHECK((m = find(s, "bad_mode")) && m->alpha_mode == DIRT_ALPHA_OPAQUE);
        CHECK((m = find(s, "bad_cutoff")) && m->alpha_mode == DIRT_ALPHA_MASK &&
              m->alpha_cutoff == 0.5f);
    }
    CHECK_MSG(log_warnings_ == 2, "%d warnings (unknown mode, negative cutoff)", log_warnings_);
    CHECK(log_errors_ == 0);
    dirt_log_set_callback(NULL, NULL);
    dirt_scene_destroy(s);
    free(json);
    free(uri);
}

static void test_obj(void)
{
    uint8_t px[4 * 4] = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0, 9, 9, 9, 255};
    CHECK(dirt_write_png_rgba8(tmp_file("kd.png"), 2, 2, px));
    CHECK(dirt_write_png_rgba8(tmp_file("other.png"), 2, 2, px));
    write_text(tmp_file("alpha.mtl"),
               "newmtl solid\nKd 0.5 0.5 0.5\nd 1\n"
               "newmtl half\nKd 0.5 0.5 0.5\nd 0.5\n"
               "newmtl tr\nKd 0.5 0.5 0.5\nTr 0.25\n"
               "newmtl cut\nKd 1 1 1\nmap_Kd kd.png\nmap_d kd.png\n"
               "newmtl other\nKd 1 1 1\nmap_d other.png\n");
    write_text(tmp_file("alpha.obj"),
               "mtllib alpha.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
               "usemtl solid\nf 1/1 2/2 3/3\nusemtl half\nf 1/1 2/2 3/3\n"
               "usemtl tr\nf 1/1 2/2 3/3\nusemtl cut\nf 1/1 2/2 3/3\n"
               "usemtl other\nf 1/1 2/2 3/3\n");
    log_capture_start();
    dirt_scene *s = dirt_scene_load(tmp_file("alpha.obj"), NULL);
    CHECK(s != NULL);
    if (s) {
        const dirt_material *m;
        CHECK((m = find(s, "solid")) && m->alpha_mode == DIRT_ALPHA_OPAQUE &&
              m->base_color[3] == 1.0f);
        CHECK((m = find(s, "half")) && m->alpha_mode == DIRT_ALPHA_BLEND &&
              m->base_color[3] == 0.5f);
        CHECK((m = find(s, "tr")) && m->alpha_mode == DIRT_ALPHA_BLEND &&
              m->base_color[3] == 0.75f);
        CHECK((m = find(s, "cut")) && m->alpha_mode == DIRT_ALPHA_BLEND &&
              m->base_color[3] == 1.0f && m->base_color_tex >= 0);
        if (m && m->base_color_tex >= 0 &&
            (size_t)m->base_color_tex < dirt_scene_num_textures(s)) {
            const dirt_texture *t = &dirt_scene_textures(s)[m->base_color_tex];
            CHECK(t->width == 2 && t->rgba[7] == 128); /* the coverage texel */
        }
        CHECK((m = find(s, "other")) && m->alpha_mode == DIRT_ALPHA_OPAQUE);
    }
    CHECK_MSG(log_warnings_ >= 1, "map_d of another image is reported");
    CHECK(log_errors_ == 0);
    dirt_log_set_callback(NULL, NULL);
    dirt_scene_destroy(s);
    static const char *const names[] = {"kd.png", "other.png", "alpha.mtl", "alpha.obj"};
    tmp_cleanup(names, 4);
}

int main(void)
{
    test_gltf();
    test_obj();
    return check_finish();
}
