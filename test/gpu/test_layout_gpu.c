/* The shared-constants registry against a real GL: every C/GLSL twin
 * record's std430 layout as GL reports it (member offsets, array strides,
 * block size) equals the C compiler's; tags written by glsl/test/layout.comp
 * read back at the C offsets; every storage block of every registered
 * program sits at a named binding point, distinct within the program; every
 * named uniform is where the registry says; and the binding points fit the
 * context's GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "common/integrator_layout.h"
#include "common/layout.h"
#include "common/mmrt_layout.h"
#include "common/mmrt_pt_layout.h"
#include "gl/gl.h"
#include "layout_check.h"
#include "gl/program.h"
#include "gpu.h"

/* The C mirror of the Records block of glsl/test/layout.comp. */
struct records {
    struct dirt_gpu_material r_material;
    struct dirt_gpu_light r_light;
    struct dirt_gpu_vertex r_vertex;
    struct dirt_gpu_view r_view;
    struct dirt_gpu_ads_params r_ads_params;
    struct dirt_gpu_ads_counters r_ads_counters;
    struct dirt_gpu_ray r_ray;
    struct dirt_gpu_hit r_hit;
    struct dirt_gpu_gpoint r_gpoint;
    struct dirt_gpu_fetch_params r_fetch_params;
    struct dirt_gpu_path r_path;
    struct dirt_gpu_accum r_accum;
    struct dirt_gpu_model_material r_model_material;
    struct dirt_gpu_model_light r_model_light;
    struct dirt_gpu_model_lights r_model_lights;
    struct dirt_gpu_model_camera r_model_camera;
    struct dirt_gpu_model_texels r_model_texels;
    struct dirt_gpu_model_texture r_model_texture;
    struct dirt_gpu_model_tangent r_model_tangent;
    struct dirt_mmrt_gpu_params r_mmrt_params;
    struct dirt_mmrt_gpu_data r_mmrt_data;
    struct dirt_mmrt_gpu_counters r_mmrt_counters;
    struct dirt_mmrt_pt_counts r_mmrt_pt_counts;
};

typedef struct member {
    const char *name;  /* GL buffer-variable name */
    size_t offset;     /* C offset in struct records */
    int array;         /* 1: an array member (name ends in [0]) */
} member;

#define M(rec, type, m) {#rec "." #m, offsetof(struct records, rec) + offsetof(struct type, m), 0}
#define MA(rec, type, m) \
    {#rec "." #m "[0]", offsetof(struct records, rec) + offsetof(struct type, m), 1}
static const member members[] = {
    M(r_material, dirt_gpu_material, base_color), M(r_material, dirt_gpu_material, emissive),
    M(r_material, dirt_gpu_material, pbr), M(r_material, dirt_gpu_material, textures),
    M(r_light, dirt_gpu_light, position), M(r_light, dirt_gpu_light, direction),
    M(r_light, dirt_gpu_light, color), M(r_light, dirt_gpu_light, cone),
    M(r_vertex, dirt_gpu_vertex, position), M(r_vertex, dirt_gpu_vertex, normal),
    MA(r_view, dirt_gpu_view, view_proj), M(r_view, dirt_gpu_view, eye_near),
    M(r_view, dirt_gpu_view, forward_far), M(r_view, dirt_gpu_view, size),
    M(r_view, dirt_gpu_view, placement), MA(r_view, dirt_gpu_view, level_base),
    M(r_ads_params, dirt_gpu_ads_params, config), M(r_ads_params, dirt_gpu_ads_params, pool),
    M(r_ads_params, dirt_gpu_ads_params, cand),
    M(r_ads_counters, dirt_gpu_ads_counters, fill), M(r_ads_counters, dirt_gpu_ads_counters, build),
    M(r_ads_counters, dirt_gpu_ads_counters, dispatch),
    M(r_ray, dirt_gpu_ray, origin_tmin), M(r_ray, dirt_gpu_ray, dir_tmax),
    M(r_hit, dirt_gpu_hit, ids), M(r_hit, dirt_gpu_hit, bary_t),
    M(r_gpoint, dirt_gpu_gpoint, pos_prim), M(r_gpoint, dirt_gpu_gpoint, n_mat),
    M(r_fetch_params, dirt_gpu_fetch_params, config),
    M(r_fetch_params, dirt_gpu_fetch_params, reserved),
    M(r_path, dirt_gpu_path, beta_pdf), M(r_path, dirt_gpu_path, radiance),
    M(r_path, dirt_gpu_path, pending), M(r_path, dirt_gpu_path, first_albedo),
    M(r_path, dirt_gpu_path, first_normal),
    M(r_accum, dirt_gpu_accum, color), M(r_accum, dirt_gpu_accum, albedo),
    M(r_accum, dirt_gpu_accum, normal),
    M(r_model_material, dirt_gpu_model_material, base_color),
    M(r_model_material, dirt_gpu_model_material, emission),
    M(r_model_material, dirt_gpu_model_material, params),
    M(r_model_material, dirt_gpu_model_material, textures),
    M(r_model_material, dirt_gpu_model_material, textures2),
    M(r_model_material, dirt_gpu_model_material, params2),
    M(r_model_material, dirt_gpu_model_material, specular_color),
    M(r_model_material, dirt_gpu_model_material, xf),
    M(r_model_light, dirt_gpu_model_light, position),
    M(r_model_light, dirt_gpu_model_light, direction),
    M(r_model_light, dirt_gpu_model_light, color), M(r_model_light, dirt_gpu_model_light, cone),
    M(r_model_lights, dirt_gpu_model_lights, counts), M(r_model_lights, dirt_gpu_model_lights, area),
    M(r_model_camera, dirt_gpu_model_camera, eye), M(r_model_camera, dirt_gpu_model_camera, forward),
    M(r_model_camera, dirt_gpu_model_camera, right), M(r_model_camera, dirt_gpu_model_camera, up),
    M(r_model_camera, dirt_gpu_model_camera, lens),
    M(r_model_texels, dirt_gpu_model_texels, counts),
    M(r_model_texture, dirt_gpu_model_texture, extent),
    M(r_model_tangent, dirt_gpu_model_tangent, tangent),
    M(r_mmrt_params, dirt_mmrt_gpu_params, config), M(r_mmrt_params, dirt_mmrt_gpu_params, pool),
    M(r_mmrt_data, dirt_mmrt_gpu_data, ids), M(r_mmrt_data, dirt_mmrt_gpu_data, attr),
    M(r_mmrt_counters, dirt_mmrt_gpu_counters, build),
    M(r_mmrt_counters, dirt_mmrt_gpu_counters, trace),
    M(r_mmrt_counters, dirt_mmrt_gpu_counters, trace2),
    M(r_mmrt_pt_counts, dirt_mmrt_pt_counts, counts),
};
#undef M
#undef MA

/* GL's layout of the Records block equals struct records, member by member. */
static void test_record_layout(dirt_gpu *gpu)
{
    GLuint prog = gl_program_compute("test/layout.comp", NULL, 0);
    CHECK(prog != 0);
    if (!prog)
        return;
    GLuint block = glGetProgramResourceIndex(prog, GL_SHADER_STORAGE_BLOCK, "Records");
    CHECK(block != GL_INVALID_INDEX);
    if (block != GL_INVALID_INDEX) {
        const GLenum props[] = {GL_BUFFER_DATA_SIZE, GL_BUFFER_BINDING};
        GLint v[2] = {-1, -1};
        glGetProgramResourceiv(prog, GL_SHADER_STORAGE_BLOCK, block, 2, props, 2, NULL, v);
        CHECK_MSG(v[0] == (GLint)sizeof(struct records), "block size %d, C %zu", v[0],
                  sizeof(struct records));
        CHECK(v[1] == DIRT_BIND_TEST_OUT);
    }
    for (size_t i = 0; i < sizeof(members) / sizeof(members[0]); i++) {
        const member *m = &members[i];
        GLuint idx = glGetProgramResourceIndex(prog, GL_BUFFER_VARIABLE, m->name);
        CHECK_MSG(idx != GL_INVALID_INDEX, "%s not found", m->name);
        if (idx == GL_INVALID_INDEX)
            continue;
        const GLenum props[] = {GL_OFFSET, GL_ARRAY_STRIDE};
        GLint v[2] = {-1, -1};
        glGetProgramResourceiv(prog, GL_BUFFER_VARIABLE, idx, 2, props, 2, NULL, v);
        CHECK_MSG(v[0] == (GLint)m->offset, "%s: GL offset %d, C %zu", m->name, v[0], m->offset);
        if (m->array)
            CHECK_MSG(v[1] == 16, "%s: array stride %d", m->name, v[1]);
    }

    /* The tags land where C reads them. */
    struct records out;
    memset(&out, 0, sizeof(out));
    GLuint buf = gl_buffer_create(gpu, sizeof(out), &out, true, "layout records");
    CHECK(buf != 0);
    if (buf) {
        glUseProgram(prog);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DIRT_BIND_TEST_OUT, buf);
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glUseProgram(0);
        CHECK(gl_buffer_read(buf, 0, sizeof(out), &out));
        CHECK(out.r_material.textures.x == -1 && out.r_material.textures.y == 2 &&
              out.r_material.textures.z == -3 && out.r_material.textures.w == 4);
        CHECK(out.r_view.level_base[3].x == 11 && out.r_view.level_base[3].w == 14);
        CHECK(out.r_view.forward_far.w == 0.25f);
        CHECK(out.r_hit.bary_t.z == 0.5f);
        CHECK(out.r_gpoint.n_mat.y == -1.5f);
        CHECK(out.r_path.first_normal.y == 2.0f);
        CHECK(out.r_accum.normal.z == 3.0f);
        CHECK(out.r_model_camera.lens.w == 2.5f);
        CHECK(out.r_model_texture.extent.z == 17u);
        CHECK(out.r_model_tangent.tangent.w == -1.0f);
        CHECK(out.r_mmrt_counters.trace2.x == 77u);
        CHECK(out.r_mmrt_pt_counts.counts.y == 99u);
        gl_buffer_destroy(&buf);
    }
    gl_program_destroy(&prog);
}

/* Every registered program: its storage blocks at named, distinct binding
 * points inside the ranges the program may use; its named uniforms at the registry's locations when active
 * (unused ones may be dropped: -1), and every uniform of a table active in
 * at least one program using the table. */
#define MAX_TABLE 16
typedef struct table_use {
    const dirt_layout_uniform *table;
    bool active[MAX_TABLE];
} table_use;

static void test_programs(void)
{
    table_use uses[32];
    size_t num_uses = 0;
    CHECK(dirt_layout_num_programs <= 32);
    for (size_t p = 0; p < dirt_layout_num_programs && p < 32; p++) {
        const dirt_layout_program *lp = &dirt_layout_programs[p];
        table_use *tu = NULL;
        for (size_t i = 0; i < num_uses; i++)
            if (uses[i].table == lp->uniforms)
                tu = &uses[i];
        if (!tu) {
            tu = &uses[num_uses++];
            memset(tu, 0, sizeof(*tu));
            tu->table = lp->uniforms;
        }
        CHECK(lp->num_uniforms <= MAX_TABLE);
        glsl_define def = {lp->define, "1"};
        GLuint prog = gl_program_create(lp->paths[0], lp->paths, lp->define ? &def : NULL,
                                        lp->define ? 1 : 0);
        CHECK_MSG(prog != 0, "%s does not build", lp->paths[0]);
        if (!prog)
            continue;
        GLint blocks = 0;
        glGetProgramInterfaceiv(prog, GL_SHADER_STORAGE_BLOCK, GL_ACTIVE_RESOURCES, &blocks);
        int seen[DIRT_BIND_LAST + 1] = {0};
        for (GLint b = 0; b < blocks; b++) {
            const GLenum prop = GL_BUFFER_BINDING;
            GLint binding = -1;
            glGetProgramResourceiv(prog, GL_SHADER_STORAGE_BLOCK, (GLuint)b, 1, &prop, 1, NULL,
                                   &binding);
            char name[128] = "";
            glGetProgramResourceName(prog, GL_SHADER_STORAGE_BLOCK, (GLuint)b, sizeof(name), NULL,
                                     name);
            bool named = binding >= 0 && binding <= DIRT_BIND_LAST &&
                         dirt_layout_binding_name(binding) != NULL;
            CHECK_MSG(named, "%s: block %s at unnamed binding %d", lp->paths[0], name, binding);
            unsigned bit = 0;
            for (size_t r = 0; r < dirt_layout_num_ranges; r++)
                if (binding >= dirt_layout_ranges[r].first && binding <= dirt_layout_ranges[r].last)
                    bit = 1u << r;
            CHECK_MSG(lp->ranges & bit, "%s: block %s at %s, outside the program's ranges",
                      lp->paths[0], name, named ? dirt_layout_binding_name(binding) : "?");
            if (named) {
                CHECK_MSG(!seen[binding], "%s: two blocks at %s", lp->paths[0],
                          dirt_layout_binding_name(binding));
                seen[binding] = 1;
            }
        }
        for (size_t u = 0; u < lp->num_uniforms && u < MAX_TABLE; u++) {
            GLint loc = glGetUniformLocation(prog, lp->uniforms[u].name);
            CHECK_MSG(loc == -1 || loc == lp->uniforms[u].location, "%s: %s at %d, registry %d",
                      lp->paths[0], lp->uniforms[u].name, loc, lp->uniforms[u].location);
            if (loc == lp->uniforms[u].location)
                tu->active[u] = true;
        }
        gl_program_destroy(&prog);
    }
    for (size_t p = 0; p < dirt_layout_num_programs && p < 32; p++) {
        const dirt_layout_program *lp = &dirt_layout_programs[p];
        for (size_t i = 0; i < num_uses; i++)
            for (size_t u = 0; uses[i].table == lp->uniforms && u < lp->num_uniforms; u++)
                CHECK_MSG(uses[i].active[u], "%s: %s never active", lp->paths[0],
                          lp->uniforms[u].name);
    }
}

int main(void)
{
    dirt_gpu *gpu = test_gpu();
    if (!gpu)
        return TEST_SKIP;
    const dirt_gpu_caps *caps = dirt_gpu_get_caps(gpu);
    CHECK_MSG(DIRT_BIND_LAST < caps->max_ssbo_bindings, "DIRT_BIND_LAST %d, GL allows %d",
              DIRT_BIND_LAST, caps->max_ssbo_bindings);
    CHECK(DIRT_GROUP_SIZE <= caps->max_compute_group_invocations);
    test_record_layout(gpu);
    test_programs();
    CHECK(gl_check("layout test"));
    dirt_gpu_destroy(gpu);
    return check_finish();
}
