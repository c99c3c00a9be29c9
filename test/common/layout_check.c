/* Compile-time checks of the shared-constants registry
 * (glsl/common/constants.h) and of every C twin of a GLSL record
 * (glsl/common/{layout,integrator_layout,mmrt_layout,mmrt_pt_layout}.h),
 * all in one place, plus the registry's run-time tables (layout_check.h).
 *
 * Record rule: every member is a 16-byte vector (or an array of them), so
 * under std430 member i starts at byte 16 * i and the record's size is 16
 * times its vector count; the C compiler must give the same numbers, which
 * the asserts below pin down member by member. */
#include "layout_check.h"

#include <stdint.h>

#include "common/integrator_layout.h"
#include "common/layout.h"
#include "common/mmrt_layout.h"
#include "common/mmrt_pt_layout.h"
#include "dirt/ads.h"
#include "mmrt/mmrt.h"
#include "ref/ref.h"

/* Record `type` has `n` 16-byte vectors. */
#define RECORD(type, n) _Static_assert(sizeof(struct type) == 16 * (n), #type " size")
/* Member `m` of record `type` starts at vector `i`. */
#define AT(type, m, i) \
    _Static_assert(offsetof(struct type, m) == 16 * (i), #type "." #m " offset")

/* The vector types themselves. */
_Static_assert(sizeof(dirt_f4) == 16 && sizeof(dirt_i4) == 16 && sizeof(dirt_u4) == 16,
               "16-byte vectors");
_Static_assert(offsetof(dirt_f4, w) == 12 && offsetof(dirt_i4, w) == 12 &&
                   offsetof(dirt_u4, w) == 12, "vector components");

/* ---- common/layout.h ---- */
RECORD(dirt_gpu_material, 4);
AT(dirt_gpu_material, base_color, 0);
AT(dirt_gpu_material, emissive, 1);
AT(dirt_gpu_material, pbr, 2);
AT(dirt_gpu_material, textures, 3);

RECORD(dirt_gpu_light, 4);
AT(dirt_gpu_light, position, 0);
AT(dirt_gpu_light, direction, 1);
AT(dirt_gpu_light, color, 2);
AT(dirt_gpu_light, cone, 3);

RECORD(dirt_gpu_vertex, 2);
AT(dirt_gpu_vertex, position, 0);
AT(dirt_gpu_vertex, normal, 1);

RECORD(dirt_gpu_view, 12);
AT(dirt_gpu_view, view_proj, 0); /* [4] */
AT(dirt_gpu_view, eye_near, 4);
AT(dirt_gpu_view, forward_far, 5);
AT(dirt_gpu_view, size, 6);
AT(dirt_gpu_view, placement, 7);
AT(dirt_gpu_view, level_base, 8); /* [4] */

RECORD(dirt_gpu_ads_params, 3 + DIRT_GPU_MAX_LARGE / 4 + DIRT_GPU_MAX_VIEWS);
AT(dirt_gpu_ads_params, config, 0);
AT(dirt_gpu_ads_params, pool, 1);
AT(dirt_gpu_ads_params, cand, 2);
AT(dirt_gpu_ads_params, large, 3);
AT(dirt_gpu_ads_params, large_grid, 3 + DIRT_GPU_MAX_LARGE / 4);

RECORD(dirt_gpu_ads_counters, 3);
AT(dirt_gpu_ads_counters, fill, 0);
AT(dirt_gpu_ads_counters, build, 1);
AT(dirt_gpu_ads_counters, dispatch, 2);
_Static_assert(offsetof(struct dirt_gpu_ads_counters, dispatch) == DIRT_ADS_DISPATCH_OFFSET,
               "the compute build's indirect dispatch");

RECORD(dirt_gpu_ray, 2);
AT(dirt_gpu_ray, origin_tmin, 0);
AT(dirt_gpu_ray, dir_tmax, 1);

RECORD(dirt_gpu_hit, 2);
AT(dirt_gpu_hit, ids, 0);
AT(dirt_gpu_hit, bary_t, 1);

RECORD(dirt_gpu_ray_batch, 1);
AT(dirt_gpu_ray_batch, dispatch, 0);

RECORD(dirt_gpu_gpoint, 2);
AT(dirt_gpu_gpoint, pos_prim, 0);
AT(dirt_gpu_gpoint, n_mat, 1);

RECORD(dirt_gpu_fetch_params, 2);
AT(dirt_gpu_fetch_params, config, 0);
AT(dirt_gpu_fetch_params, reserved, 1);

RECORD(dirt_gpu_path, 5);
AT(dirt_gpu_path, beta_pdf, 0);
AT(dirt_gpu_path, radiance, 1);
AT(dirt_gpu_path, pending, 2);
AT(dirt_gpu_path, first_albedo, 3);
AT(dirt_gpu_path, first_normal, 4);

RECORD(dirt_gpu_accum, 3);
AT(dirt_gpu_accum, color, 0);
AT(dirt_gpu_accum, albedo, 1);
AT(dirt_gpu_accum, normal, 2);

/* ---- common/integrator_layout.h ---- */
RECORD(dirt_gpu_model_material, 7 + 2 * DIRT_MODEL_TEX_SLOTS);
AT(dirt_gpu_model_material, base_color, 0);
AT(dirt_gpu_model_material, emission, 1);
AT(dirt_gpu_model_material, params, 2);
AT(dirt_gpu_model_material, textures, 3);
AT(dirt_gpu_model_material, textures2, 4);
AT(dirt_gpu_model_material, params2, 5);
AT(dirt_gpu_model_material, specular_color, 6);
AT(dirt_gpu_model_material, xf, 7);

RECORD(dirt_gpu_model_light, 4);
AT(dirt_gpu_model_light, position, 0);
AT(dirt_gpu_model_light, direction, 1);
AT(dirt_gpu_model_light, color, 2);
AT(dirt_gpu_model_light, cone, 3);

RECORD(dirt_gpu_model_lights, 2);
AT(dirt_gpu_model_lights, counts, 0);
AT(dirt_gpu_model_lights, area, 1);

RECORD(dirt_gpu_model_env, 2);
AT(dirt_gpu_model_env, dims, 0);
AT(dirt_gpu_model_env, params, 1);

RECORD(dirt_gpu_model_camera, 5);
AT(dirt_gpu_model_camera, eye, 0);
AT(dirt_gpu_model_camera, forward, 1);
AT(dirt_gpu_model_camera, right, 2);
AT(dirt_gpu_model_camera, up, 3);
AT(dirt_gpu_model_camera, lens, 4);

RECORD(dirt_gpu_model_texels, 1);
AT(dirt_gpu_model_texels, counts, 0);

RECORD(dirt_gpu_model_texture, 1);
AT(dirt_gpu_model_texture, extent, 0);

RECORD(dirt_gpu_model_tangent, 1);
AT(dirt_gpu_model_tangent, tangent, 0);

/* ---- common/mmrt_layout.h, common/mmrt_pt_layout.h ---- */
RECORD(dirt_mmrt_gpu_params, 2);
AT(dirt_mmrt_gpu_params, config, 0);
AT(dirt_mmrt_gpu_params, pool, 1);

RECORD(dirt_mmrt_gpu_data, 2);
AT(dirt_mmrt_gpu_data, ids, 0);
AT(dirt_mmrt_gpu_data, attr, 1);

RECORD(dirt_mmrt_gpu_counters, 3);
AT(dirt_mmrt_gpu_counters, build, 0);
AT(dirt_mmrt_gpu_counters, trace, 1);
AT(dirt_mmrt_gpu_counters, trace2, 2);

RECORD(dirt_mmrt_pt_counts, 1);
AT(dirt_mmrt_pt_counts, counts, 0);

/* ---- Node sizes and the public mirrors of GPU records ---- */
_Static_assert(DIRT_NODE_BYTES == 2 * sizeof(uint32_t), "DIRT id node: uvec2");
_Static_assert(DIRT_DEPTH_ENTRY_BYTES == 2 * sizeof(uint32_t), "depth entry: uvec2");
_Static_assert(DIRT_HEAD_BYTES == sizeof(uint32_t), "list head: uint");
_Static_assert(DIRT_HIT_NODE_BYTES == sizeof(struct dirt_gpu_hit), "hit node");
_Static_assert(DIRT_MMRT_ID_NODE_BYTES == DIRT_MMRT_ID_UINTS * sizeof(uint32_t) &&
                   sizeof(dirt_mmrt_id_node) == DIRT_MMRT_ID_NODE_BYTES, "MMRT id node");
_Static_assert(DIRT_MMRT_ID_Z < DIRT_MMRT_ID_UINTS && DIRT_MMRT_ID_NEXT < DIRT_MMRT_ID_UINTS &&
                   DIRT_MMRT_ID_PREV < DIRT_MMRT_ID_UINTS, "MMRT id node fields");
_Static_assert(DIRT_MMRT_DATA_NODE_BYTES == sizeof(struct dirt_mmrt_gpu_data) &&
                   sizeof(dirt_mmrt_data_node) == DIRT_MMRT_DATA_NODE_BYTES, "MMRT data node");
_Static_assert(sizeof(dirt_ray) == sizeof(struct dirt_gpu_ray) &&
                   sizeof(dirt_ref_ray) == sizeof(struct dirt_gpu_ray), "ray mirrors");
_Static_assert(sizeof(dirt_hit) == sizeof(struct dirt_gpu_hit), "hit mirror");
_Static_assert(sizeof(dirt_gpoint) == sizeof(struct dirt_gpu_gpoint), "gpoint mirror");

/* ---- Workgroups ---- */
_Static_assert(DIRT_GROUPS(0) == 0 && DIRT_GROUPS(1) == 1 && DIRT_GROUPS(DIRT_GROUP_SIZE) == 1 &&
                   DIRT_GROUPS(DIRT_GROUP_SIZE + 1) == 2, "DIRT_GROUPS rounds up");
_Static_assert(DIRT_GROUPS_2D(DIRT_GROUP_SIZE_2D + 1) == 2, "DIRT_GROUPS_2D rounds up");
/* GL 4.5 guarantees 1024 invocations and 1024 in x, y per group. */
_Static_assert(DIRT_GROUP_SIZE <= 1024 && DIRT_GROUP_SIZE_2D * DIRT_GROUP_SIZE_2D <= 1024,
               "workgroup within the GL minimum");

/* ---- Binding points ---- */

#define B(name, range) {#name, name, range}
const dirt_layout_binding dirt_layout_bindings[] = {
    B(DIRT_BIND_VERTICES, "SHARED"),
    B(DIRT_BIND_VIEWS, "SHARED"),
    B(DIRT_BIND_DEPTH, "SHARED"),
    B(DIRT_BIND_RAYS, "SHARED"),
    B(DIRT_BIND_HITS, "SHARED"),
    B(DIRT_BIND_PRIM_MATERIAL, "SHARED"),
    B(DIRT_BIND_GPOINTS, "SHARED"),
    B(DIRT_BIND_RAY_BATCH, "SHARED"),
    B(DIRT_BIND_PARAMS, "ADS"),
    B(DIRT_BIND_HEADS, "ADS"),
    B(DIRT_BIND_NODES, "ADS"),
    B(DIRT_BIND_COUNTERS, "ADS"),
    B(DIRT_BIND_CANDIDATES, "ADS"),
    B(DIRT_BIND_HIT_HEADS, "TRACE"),
    B(DIRT_BIND_FETCH_PARAMS, "TRACE"),
    B(DIRT_BIND_PATHS, "INTEGRATOR"),
    B(DIRT_BIND_ACCUM, "INTEGRATOR"),
    B(DIRT_BIND_SHADOW_RAYS, "INTEGRATOR"),
    B(DIRT_BIND_NEXT_BATCH, "INTEGRATOR"),
    B(DIRT_BIND_PT_EVENTS, "INTEGRATOR"),
    B(DIRT_BIND_MMRT_PARAMS, "MMRT"),
    B(DIRT_BIND_MMRT_HEADS, "MMRT"),
    B(DIRT_BIND_MMRT_TAILS, "MMRT"),
    B(DIRT_BIND_MMRT_IDS, "MMRT"),
    B(DIRT_BIND_MMRT_DATA, "MMRT"),
    B(DIRT_BIND_MMRT_COUNTERS, "MMRT"),
    B(DIRT_BIND_MMRT_PT_COUNTS, "MMRT_PT"),
    B(DIRT_BIND_MODEL_MATERIALS, "MODEL"),
    B(DIRT_BIND_MODEL_AREA_CDF, "MODEL"),
    B(DIRT_BIND_MODEL_AREA_PRIMS, "MODEL"),
    B(DIRT_BIND_MODEL_PUNCTUAL, "MODEL"),
    B(DIRT_BIND_MODEL_CAMERA, "MODEL"),
    B(DIRT_BIND_MODEL_TEXELS, "MODEL"),
    B(DIRT_BIND_MODEL_ENV, "MODEL"),
    B(DIRT_BIND_MODEL_TANGENTS, "MODEL"),
    B(DIRT_BIND_PREVIEW_MATERIALS, "PREVIEW"),
    B(DIRT_BIND_PREVIEW_LIGHTS, "PREVIEW"),
    B(DIRT_BIND_TEST_IN, "TEST"),
    B(DIRT_BIND_TEST_OUT, "TEST"),
    B(DIRT_BIND_WORK, "WORK"),
    B(DIRT_BIND_SORT, "SORT"),
    B(DIRT_BIND_LARGE_CELLS, "LARGE"),
};
#undef B
const size_t dirt_layout_num_bindings =
    sizeof(dirt_layout_bindings) / sizeof(dirt_layout_bindings[0]);

#define R(name) {#name, DIRT_BIND_##name##_FIRST, DIRT_BIND_##name##_LAST}
const dirt_layout_range dirt_layout_ranges[] = {
    R(SHARED), R(ADS), R(TRACE), R(INTEGRATOR), R(MMRT), R(MMRT_PT), R(MODEL), R(PREVIEW), R(TEST), R(WORK),
    R(SORT), R(LARGE),
};
#undef R
const size_t dirt_layout_num_ranges = sizeof(dirt_layout_ranges) / sizeof(dirt_layout_ranges[0]);

/* The ranges tile [0, DIRT_BIND_LAST] in order (constants.h #errors on
 * overlaps; this also rejects gaps and a stale DIRT_BIND_LAST). */
_Static_assert(DIRT_BIND_SHARED_FIRST == 0 && DIRT_BIND_ADS_FIRST == DIRT_BIND_SHARED_LAST + 1 &&
                   DIRT_BIND_TRACE_FIRST == DIRT_BIND_ADS_LAST + 1 &&
                   DIRT_BIND_INTEGRATOR_FIRST == DIRT_BIND_TRACE_LAST + 1 &&
                   DIRT_BIND_MMRT_FIRST == DIRT_BIND_INTEGRATOR_LAST + 1 &&
                   DIRT_BIND_MMRT_PT_FIRST == DIRT_BIND_MMRT_LAST + 1 &&
                   DIRT_BIND_MODEL_FIRST == DIRT_BIND_MMRT_PT_LAST + 1 &&
                   DIRT_BIND_PREVIEW_FIRST == DIRT_BIND_MODEL_LAST + 1 &&
                   DIRT_BIND_TEST_FIRST == DIRT_BIND_PREVIEW_LAST + 1 &&
                   DIRT_BIND_WORK_FIRST == DIRT_BIND_TEST_LAST + 1 &&
                   DIRT_BIND_SORT_FIRST == DIRT_BIND_WORK_LAST + 1 &&
                   DIRT_BIND_LARGE_FIRST == DIRT_BIND_SORT_LAST + 1 &&
                   DIRT_BIND_LAST == DIRT_BIND_LARGE_LAST,
               "binding ranges tile [0, DIRT_BIND_LAST]");
/* As many names as binding points: with the distinct values checked by
 * dirt_layout_binding_name, every point of every range is named once. */
_Static_assert(sizeof(dirt_layout_bindings) / sizeof(dirt_layout_bindings[0]) ==
                   DIRT_BIND_LAST + 1, "every binding point named once");

#define CASE(name) \
    case name:     \
        return #name
const char *dirt_layout_binding_name(int binding)
{
    switch (binding) { /* duplicate values are a compile error here */
        CASE(DIRT_BIND_VERTICES);
        CASE(DIRT_BIND_VIEWS);
        CASE(DIRT_BIND_DEPTH);
        CASE(DIRT_BIND_RAYS);
        CASE(DIRT_BIND_HITS);
        CASE(DIRT_BIND_PRIM_MATERIAL);
        CASE(DIRT_BIND_GPOINTS);
        CASE(DIRT_BIND_RAY_BATCH);
        CASE(DIRT_BIND_PARAMS);
        CASE(DIRT_BIND_HEADS);
        CASE(DIRT_BIND_NODES);
        CASE(DIRT_BIND_COUNTERS);
        CASE(DIRT_BIND_CANDIDATES);
        CASE(DIRT_BIND_HIT_HEADS);
        CASE(DIRT_BIND_FETCH_PARAMS);
        CASE(DIRT_BIND_PATHS);
        CASE(DIRT_BIND_ACCUM);
        CASE(DIRT_BIND_SHADOW_RAYS);
        CASE(DIRT_BIND_NEXT_BATCH);
        CASE(DIRT_BIND_PT_EVENTS);
        CASE(DIRT_BIND_MMRT_PARAMS);
        CASE(DIRT_BIND_MMRT_HEADS);
        CASE(DIRT_BIND_MMRT_TAILS);
        CASE(DIRT_BIND_MMRT_IDS);
        CASE(DIRT_BIND_MMRT_DATA);
        CASE(DIRT_BIND_MMRT_COUNTERS);
        CASE(DIRT_BIND_MMRT_PT_COUNTS);
        CASE(DIRT_BIND_MODEL_MATERIALS);
        CASE(DIRT_BIND_MODEL_AREA_CDF);
        CASE(DIRT_BIND_MODEL_AREA_PRIMS);
        CASE(DIRT_BIND_MODEL_PUNCTUAL);
        CASE(DIRT_BIND_MODEL_CAMERA);
        CASE(DIRT_BIND_MODEL_TEXELS);
        CASE(DIRT_BIND_MODEL_ENV);
        CASE(DIRT_BIND_MODEL_TANGENTS);
        CASE(DIRT_BIND_PREVIEW_MATERIALS);
        CASE(DIRT_BIND_PREVIEW_LIGHTS);
        CASE(DIRT_BIND_TEST_IN);
        CASE(DIRT_BIND_TEST_OUT);
        CASE(DIRT_BIND_WORK);
        CASE(DIRT_BIND_SORT);
        CASE(DIRT_BIND_LARGE_CELLS);
    default:
        return NULL;
    }
}
#undef CASE

/* ---- Uniform locations ---- */

/* Distinct locations within each program: a switch per program, one case
 * per location (duplicates do not compile). Never called (hence unused:
 * clang warns of an unused static inline function in a .c file). */
#define L(name) case name:
__attribute__((unused)) static inline int distinct_locations(int program, int loc)
{
    switch (program) {
    case 0:
        switch (loc) {
            L(DIRT_LOC_PT_PIXELS) L(DIRT_LOC_PT_WIDTH) L(DIRT_LOC_PT_HEIGHT) L(DIRT_LOC_PT_SEED)
            L(DIRT_LOC_PT_SAMPLE) L(DIRT_LOC_PT_BOUNCE) L(DIRT_LOC_PT_BOUNCES) L(DIRT_LOC_PT_SLOT)
            L(DIRT_LOC_PT_AO_DISTANCE) L(DIRT_LOC_PT_PIXEL_OFFSET)
            L(DIRT_LOC_PT_SURFACE_OFFSET) return 1;
        }
        break;
    case 1:
        switch (loc) {
            L(DIRT_LOC_TEST_MODEL_MODE) L(DIRT_LOC_TEST_MODEL_COUNT) return 1;
        }
        break;
    case 2:
        switch (loc) {
            L(DIRT_LOC_TRACE_COUNT) L(DIRT_LOC_TRACE_HIZ_TOP) L(DIRT_LOC_TRACE_ANY_HIT)
            L(DIRT_LOC_TRACE_LINK) L(DIRT_LOC_TRACE_FROM_SURFACES) L(DIRT_LOC_RAY_BATCH) return 1;
        }
        break;
    case 3:
        switch (loc) {
            L(DIRT_LOC_MMRT_TRACE_COUNT) L(DIRT_LOC_MMRT_TRACE_MARCH) L(DIRT_LOC_MMRT_TRACE_SAMPLES)
            L(DIRT_LOC_MMRT_TRACE_TOP_LEVEL) L(DIRT_LOC_MMRT_TRACE_THICKNESS)
            L(DIRT_LOC_MMRT_TRACE_SEED) L(DIRT_LOC_MMRT_TRACE_STATS)
            L(DIRT_LOC_MMRT_TRACE_ALL_VIEWS) L(DIRT_LOC_MMRT_TRACE_FIRST_RAY)
            L(DIRT_LOC_RAY_BATCH) return 1;
        }
        break;
    case 4:
        switch (loc) {
            L(DIRT_LOC_MMRT_PT_RAYS_COUNT) L(DIRT_LOC_RAY_BATCH) return 1;
        }
        break;
    case 5:
        switch (loc) {
            L(DIRT_LOC_MMRT_TO_GPOINT_COUNT) L(DIRT_LOC_MMRT_TO_GPOINT_SLOT) L(DIRT_LOC_RAY_BATCH)
            return 1;
        }
        break;
    case 6:
        switch (loc) {
            L(DIRT_LOC_PREVIEW_VIEW_PROJ) L(DIRT_LOC_PREVIEW_EYE) L(DIRT_LOC_PREVIEW_MATERIAL)
            L(DIRT_LOC_PREVIEW_NUM_LIGHTS) L(DIRT_LOC_PREVIEW_AMBIENT)
            L(DIRT_LOC_PREVIEW_FORWARD) return 1;
        }
        break;
    case 7:
        switch (loc) {
            L(DIRT_LOC_TEST_RNG_COUNT) L(DIRT_LOC_TEST_RNG_SEED) return 1;
        }
        break;
    case 8:
        switch (loc) {
            L(DIRT_LOC_TEST_FILL_COUNT) L(DIRT_LOC_TEST_FILL_SEED) return 1;
        }
        break;
    case 9:
        switch (loc) {
            L(DIRT_LOC_DISPLAY_PIXELS) L(DIRT_LOC_DISPLAY_WIDTH) L(DIRT_LOC_DISPLAY_INV_SAMPLES)
            L(DIRT_LOC_DISPLAY_PIXEL_OFFSET) return 1;
        }
        break;
    case 10:
        switch (loc) {
            L(DIRT_LOC_PRESENT_RECT) L(DIRT_LOC_PRESENT_MODE) L(DIRT_LOC_PRESENT_SCALE)
            L(DIRT_LOC_PRESENT_TONEMAP) L(DIRT_LOC_PRESENT_CHANNEL) L(DIRT_LOC_PRESENT_RANGE)
            L(DIRT_LOC_PRESENT_SPLIT) L(DIRT_LOC_PRESENT_SPLIT_LINE) return 1;
        }
        break;
    case 11:
        switch (loc) {
            L(DIRT_LOC_COMPACT_PIXELS) L(DIRT_LOC_COMPACT_EVENT) return 1;
        }
        break;
    }
    return 0;
}
#undef L

/* The programs and their named uniforms (the GPU test compiles each and
 * asks GL where every uniform is). */
#define U(glsl, loc) {glsl, loc}
static const dirt_layout_uniform u_pt[] = {
    U("u_pixels", DIRT_LOC_PT_PIXELS),   U("u_width", DIRT_LOC_PT_WIDTH),
    U("u_height", DIRT_LOC_PT_HEIGHT),   U("u_seed", DIRT_LOC_PT_SEED),
    U("u_sample", DIRT_LOC_PT_SAMPLE),   U("u_bounce", DIRT_LOC_PT_BOUNCE),
    U("u_bounces", DIRT_LOC_PT_BOUNCES), U("u_slot", DIRT_LOC_PT_SLOT),
    U("u_ao_distance", DIRT_LOC_PT_AO_DISTANCE),
    U("u_pixel_offset", DIRT_LOC_PT_PIXEL_OFFSET), U("u_surface_offset", DIRT_LOC_PT_SURFACE_OFFSET),
};
static const dirt_layout_uniform u_resolve[] = {U("u_pixels", DIRT_LOC_RESOLVE_PIXELS)};
static const dirt_layout_uniform u_accum[] = {U("u_pixels", DIRT_LOC_ACCUM_PIXELS)};
static const dirt_layout_uniform u_display[] = {U("u_pixels", DIRT_LOC_DISPLAY_PIXELS),
                                               U("u_width", DIRT_LOC_DISPLAY_WIDTH),
                                               U("u_inv_samples", DIRT_LOC_DISPLAY_INV_SAMPLES),
                                               U("u_pixel_offset", DIRT_LOC_DISPLAY_PIXEL_OFFSET)};
static const dirt_layout_uniform u_test_model[] = {
    U("u_mode", DIRT_LOC_TEST_MODEL_MODE), U("u_count", DIRT_LOC_TEST_MODEL_COUNT)};
static const dirt_layout_uniform u_trace[] = {
    U("u_count", DIRT_LOC_TRACE_COUNT), U("u_hiz_top", DIRT_LOC_TRACE_HIZ_TOP),
    U("u_any_hit", DIRT_LOC_TRACE_ANY_HIT), U("u_link", DIRT_LOC_TRACE_LINK),
    U("u_from_surfaces", DIRT_LOC_TRACE_FROM_SURFACES),
    U("u_alpha", DIRT_LOC_ALPHA_ENABLED), U("u_alpha_key", DIRT_LOC_ALPHA_KEY),
    U("u_alpha_first_pixel", DIRT_LOC_ALPHA_FIRST_PIXEL), U("u_ray_batch", DIRT_LOC_RAY_BATCH)};
static const dirt_layout_uniform u_mip[] = {U("u_level", DIRT_LOC_MIP_LEVEL)};
static const dirt_layout_uniform u_vis[] = {U("u_view", DIRT_LOC_VISIBILITY_VIEW)};
static const dirt_layout_uniform u_vis_resolve[] = {U("u_view", DIRT_LOC_VIS_RESOLVE_VIEW)};
static const dirt_layout_uniform u_mmrt_trace[] = {
    U("u_count", DIRT_LOC_MMRT_TRACE_COUNT),         U("u_march", DIRT_LOC_MMRT_TRACE_MARCH),
    U("u_samples", DIRT_LOC_MMRT_TRACE_SAMPLES),     U("u_top_level", DIRT_LOC_MMRT_TRACE_TOP_LEVEL),
    U("u_thickness", DIRT_LOC_MMRT_TRACE_THICKNESS), U("u_seed", DIRT_LOC_MMRT_TRACE_SEED),
    U("u_stats", DIRT_LOC_MMRT_TRACE_STATS),         U("u_all_views", DIRT_LOC_MMRT_TRACE_ALL_VIEWS),
    U("u_first_ray", DIRT_LOC_MMRT_TRACE_FIRST_RAY),
    U("u_alpha", DIRT_LOC_ALPHA_ENABLED), U("u_alpha_key", DIRT_LOC_ALPHA_KEY),
    U("u_alpha_first_pixel", DIRT_LOC_ALPHA_FIRST_PIXEL), U("u_ray_batch", DIRT_LOC_RAY_BATCH)};
static const dirt_layout_uniform u_pt_rays[] = {
    U("u_count", DIRT_LOC_MMRT_PT_RAYS_COUNT), U("u_ray_batch", DIRT_LOC_RAY_BATCH)};
static const dirt_layout_uniform u_to_gpoint[] = {
    U("u_count", DIRT_LOC_MMRT_TO_GPOINT_COUNT), U("u_slot", DIRT_LOC_MMRT_TO_GPOINT_SLOT),
    U("u_ray_batch", DIRT_LOC_RAY_BATCH)};
static const dirt_layout_uniform u_fetch[] = {U("u_ray_batch", DIRT_LOC_RAY_BATCH)};
static const dirt_layout_uniform u_compact[] = {U("u_pixels", DIRT_LOC_COMPACT_PIXELS)};
static const dirt_layout_uniform u_finish[] = {U("u_event", DIRT_LOC_COMPACT_EVENT)};
static const dirt_layout_uniform u_sort[] = {
    U("u_rays", DIRT_LOC_SORT_RAYS), U("u_bmin", DIRT_LOC_SORT_BOUNDS_MIN),
    U("u_bmax", DIRT_LOC_SORT_BOUNDS_MAX)};
static const dirt_layout_uniform u_preview[] = {
    U("u_view_proj", DIRT_LOC_PREVIEW_VIEW_PROJ), U("u_eye", DIRT_LOC_PREVIEW_EYE),
    U("u_material", DIRT_LOC_PREVIEW_MATERIAL),   U("u_num_lights", DIRT_LOC_PREVIEW_NUM_LIGHTS),
    U("u_ambient", DIRT_LOC_PREVIEW_AMBIENT), U("u_forward", DIRT_LOC_PREVIEW_FORWARD)};
static const dirt_layout_uniform u_present[] = {
    U("u_rect", DIRT_LOC_PRESENT_RECT),       U("u_mode", DIRT_LOC_PRESENT_MODE),
    U("u_scale", DIRT_LOC_PRESENT_SCALE),     U("u_tonemap", DIRT_LOC_PRESENT_TONEMAP),
    U("u_channel", DIRT_LOC_PRESENT_CHANNEL), U("u_range", DIRT_LOC_PRESENT_RANGE),
    U("u_split", DIRT_LOC_PRESENT_SPLIT),     U("u_split_line", DIRT_LOC_PRESENT_SPLIT_LINE)};
static const dirt_layout_uniform u_rng[] = {
    U("u_count", DIRT_LOC_TEST_RNG_COUNT), U("u_seed", DIRT_LOC_TEST_RNG_SEED)};
static const dirt_layout_uniform u_fill[] = {
    U("u_count", DIRT_LOC_TEST_FILL_COUNT), U("u_seed", DIRT_LOC_TEST_FILL_SEED)};
static const dirt_layout_uniform u_to_image[] = {U("u_size", DIRT_LOC_TEST_TO_IMAGE_SIZE)};
static const dirt_layout_uniform u_splat[] = {U("u_add", DIRT_LOC_TEST_SPLAT_ADD)};
#undef U

#define P(a, b, r, u) {{a, b, NULL}, NULL, r, u, sizeof(u) / sizeof(u[0])}
#define SH DIRT_RANGE_SHARED
const dirt_layout_program dirt_layout_programs[] = {
    P("integrator/raygen.comp", NULL, SH | DIRT_RANGE_INTEGRATOR | DIRT_RANGE_MODEL, u_pt),
    P("integrator/shade.comp", NULL, SH | DIRT_RANGE_INTEGRATOR | DIRT_RANGE_MODEL, u_pt),
    {{"integrator/shade.comp", NULL, NULL}, "DIRT_AO", SH | DIRT_RANGE_INTEGRATOR | DIRT_RANGE_MODEL,
     u_pt, sizeof(u_pt) / sizeof(u_pt[0])},
    P("integrator/resolve.comp", NULL, SH | DIRT_RANGE_INTEGRATOR, u_resolve),
    P("integrator/accumulate.comp", NULL, SH | DIRT_RANGE_INTEGRATOR, u_accum),
    P("integrator/compact.comp", NULL, SH | DIRT_RANGE_INTEGRATOR, u_compact),
    {{"integrator/compact.comp", NULL, NULL}, "DIRT_COMPACT_FINISH", DIRT_RANGE_INTEGRATOR,
     u_finish, sizeof(u_finish) / sizeof(u_finish[0])},
    {{"integrator/sort.comp", NULL, NULL}, "DIRT_SORT_COUNT", SH | DIRT_RANGE_INTEGRATOR |
     DIRT_RANGE_SORT, u_sort, sizeof(u_sort) / sizeof(u_sort[0])},
    {{"integrator/sort.comp", NULL, NULL}, "DIRT_SORT_SCAN", SH | DIRT_RANGE_INTEGRATOR |
     DIRT_RANGE_SORT, u_sort, sizeof(u_sort) / sizeof(u_sort[0])},
    {{"integrator/sort.comp", NULL, NULL}, "DIRT_SORT_SCATTER", SH | DIRT_RANGE_INTEGRATOR |
     DIRT_RANGE_SORT, u_sort, sizeof(u_sort) / sizeof(u_sort[0])},
    P("dirt/fetch.comp", NULL, SH | DIRT_RANGE_TRACE, u_fetch),
    P("dirt/fetch_miss.comp", NULL, SH | DIRT_RANGE_TRACE, u_fetch),
    P("integrator/test_model.comp", NULL, DIRT_RANGE_TEST | DIRT_RANGE_MODEL, u_test_model),
    P("dirt/trace.comp", NULL, SH | DIRT_RANGE_ADS | DIRT_RANGE_TRACE, u_trace),
    /* The traces' alpha-tested builds read the model's materials and texels. */
    {{"dirt/trace.comp", NULL, NULL}, "DIRT_TRACE_ALPHA",
     SH | DIRT_RANGE_ADS | DIRT_RANGE_TRACE | DIRT_RANGE_MODEL, u_trace,
     sizeof(u_trace) / sizeof(u_trace[0])},
    /* The large primitives' grid (DIRT_TRACE_LARGE_GRID implies _LARGE). */
    {{"dirt/trace.comp", NULL, NULL}, "DIRT_TRACE_LARGE_GRID",
     SH | DIRT_RANGE_ADS | DIRT_RANGE_TRACE | DIRT_RANGE_LARGE, u_trace,
     sizeof(u_trace) / sizeof(u_trace[0])},
    P("views/hiz.comp", NULL, SH, u_mip),
    P("integrator/display.comp", NULL, SH | DIRT_RANGE_INTEGRATOR, u_display),
    P("dirt/visibility.vert", "dirt/visibility.frag", SH, u_vis),
    P("dirt/visibility_resolve.comp", NULL, SH | DIRT_RANGE_ADS | DIRT_RANGE_TRACE, u_vis_resolve),
    P("mmrt/trace.comp", NULL, SH | DIRT_RANGE_MMRT, u_mmrt_trace),
    {{"mmrt/trace.comp", NULL, NULL}, "DIRT_TRACE_ALPHA", SH | DIRT_RANGE_MMRT | DIRT_RANGE_MODEL,
     u_mmrt_trace, sizeof(u_mmrt_trace) / sizeof(u_mmrt_trace[0])},
    P("mmrt/pt_rays.comp", NULL, SH | DIRT_RANGE_MMRT | DIRT_RANGE_MMRT_PT, u_pt_rays),
    P("mmrt/to_gpoint.comp", NULL, SH | DIRT_RANGE_MMRT, u_to_gpoint),
    P("raster/preview.vert", "raster/preview.frag", DIRT_RANGE_PREVIEW, u_preview),
    /* The window's presentation binds textures only: no storage range. */
    P("present/present.vert", "present/present.frag", 0, u_present),
    P("test/rng.comp", NULL, DIRT_RANGE_TEST, u_rng),
    P("graph_test/fill.comp", NULL, DIRT_RANGE_TEST, u_fill),
    P("graph_test/to_image.comp", NULL, DIRT_RANGE_TEST, u_to_image),
    P("graph_test/draw.vert", "graph_test/splat.frag", DIRT_RANGE_TEST, u_splat),
};
#undef SH
#undef P
const size_t dirt_layout_num_programs =
    sizeof(dirt_layout_programs) / sizeof(dirt_layout_programs[0]);
