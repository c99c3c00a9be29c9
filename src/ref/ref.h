/* DIRT engine: the CPU ground truth (Embree 3).
 *
 * Two layers:
 *  - ray casting: an Embree BVH over the world-space triangles of one
 *    dirt_frame (rebuilt per frame), closest-hit and occlusion queries, one
 *    ray or multithreaded batches. Hits name the frame's primitive id
 *    (triangle index), so they compare directly with DIRT/MMRT hit records.
 *  - rendering: path tracing (NEE + MIS, Russian roulette) and ambient
 *    occlusion with the light-transport model of integrator/integrator.h
 *    (doc/light-transport.md) and the shared RNG (doc/rng.md), so the GPU
 *    integrators can be compared to it pixel for pixel.
 *
 * Thread safety: an accel may be queried from any number of threads at once;
 * create/update/destroy need exclusive access. */
#ifndef DIRT_REF_H
#define DIRT_REF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "common/constants.h"
#include "dirt/image.h"
#include "dirt/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- ray casting -------------------------------------------------------- */

typedef struct dirt_ref_accel dirt_ref_accel;
struct dirt_ref_materials;

/* Zero-initialised = defaults. */
typedef struct dirt_ref_accel_opts {
    int threads;       /* Embree build threads; 0 = every online CPU */
    bool high_quality; /* RTC_BUILD_QUALITY_HIGH (spatial splits) instead of
                          MEDIUM; slower build, faster traversal */
    /* Alpha-tested traversal (doc/light-transport.md section 1, "Alpha"):
     * the materials and textures of the frames' triangles (borrowed: they
     * must outlive the accel; the frame's per-triangle materials and UVs
     * are copied at every build). A hit of a MASK or BLEND material that
     * dirt_alpha_accept rejects is no hit (an Embree filter function), for
     * closest-hit and occlusion queries alike; BLEND decisions use the
     * query's key (dirt_ref_intersect1_key). NULL, or no alpha-tested
     * material in the frame: every surface is opaque and no filter runs. */
    const struct dirt_ref_materials *alpha;
} dirt_ref_accel_opts;

/* Timing of the last build (create or update). */
typedef struct dirt_ref_build_stats {
    size_t prims;        /* triangles in the BVH */
    double upload_ms;    /* copying the frame into Embree's buffers */
    double build_ms;     /* rtcCommitScene: the BVH build itself */
    double mprims_per_s; /* prims / build_ms, in millions per second */
} dirt_ref_build_stats;

/* Builds a BVH over every triangle of `frame` (positions are copied; the
 * frame may be freed afterwards). Robust (watertight) intersection mode.
 * Zero-area triangles are kept and never hit. `opts` may be NULL.
 * NULL after logging on failure (Embree device error, out of memory, more
 * than UINT32_MAX / 3 triangles). */
dirt_ref_accel *dirt_ref_accel_create(const dirt_frame *frame,
                                      const dirt_ref_accel_opts *opts);

/* Rebuilds the BVH from a new frame (another time step, any triangle
 * count). On failure (false, logged) the accel is empty: every ray misses. */
bool dirt_ref_accel_update(dirt_ref_accel *accel, const dirt_frame *frame);

/* Accepts NULL. */
void dirt_ref_accel_destroy(dirt_ref_accel *accel);

void dirt_ref_accel_stats(const dirt_ref_accel *accel, dirt_ref_build_stats *out);

/* Number of triangles the accel was built from. */
size_t dirt_ref_accel_num_prims(const dirt_ref_accel *accel);

/* True when the last build installed the alpha test (opts.alpha given and a
 * triangle of the frame has a MASK or BLEND material). */
bool dirt_ref_accel_alpha_tested(const dirt_ref_accel *accel);

#define DIRT_REF_MISS UINT32_MAX

/* A ray: points org + t dir for t in [tmin, tmax]. dir need not be unit
 * length (t is then in units of |dir|). tmax may be INFINITY. */
typedef struct dirt_ref_ray {
    float org[3];
    float tmin;
    float dir[3];
    float tmax;
} dirt_ref_ray;

/* Closest hit. prim = DIRT_REF_MISS when nothing was hit (other fields are
 * then unspecified). The hit point is org + t dir
 * = (1 - u - v) p0 + u p1 + v p2 of triangle prim; ng is the unit geometric
 * normal normalize(cross(p1 - p0, p2 - p0)) (winding order, not facing). */
typedef struct dirt_ref_hit {
    uint32_t prim;
    float t, u, v;
    float ng[3];
} dirt_ref_hit;

/* One ray. Returns true on a hit (and fills *hit; hit->prim = DIRT_REF_MISS
 * otherwise). */
bool dirt_ref_intersect1(const dirt_ref_accel *accel, const dirt_ref_ray *ray,
                         dirt_ref_hit *hit);
/* True when anything blocks the ray within [tmin, tmax]. */
bool dirt_ref_occluded1(const dirt_ref_accel *accel, const dirt_ref_ray *ray);

/* The same with the ray's alpha key (dirt_rng_u32(seed, pixel, sample,
 * bounce, DIRT_RNG_DIM_ALPHA_PATH / _SHADOW), doc/rng.md) for its BLEND
 * decisions; the functions above use key 0. */
bool dirt_ref_intersect1_key(const dirt_ref_accel *accel, const dirt_ref_ray *ray,
                             uint32_t alpha_key, dirt_ref_hit *hit);
bool dirt_ref_occluded1_key(const dirt_ref_accel *accel, const dirt_ref_ray *ray,
                            uint32_t alpha_key);

/* Batches on `threads` threads (0 = every online CPU; the caller's thread
 * works too). hits[i] / occluded[i] (1 = blocked, 0 = free) answer rays[i]. */
void dirt_ref_intersect(const dirt_ref_accel *accel, const dirt_ref_ray *rays,
                        dirt_ref_hit *hits, size_t count, int threads);
void dirt_ref_occluded(const dirt_ref_accel *accel, const dirt_ref_ray *rays,
                       uint8_t *occluded, size_t count, int threads);
/* The same with alpha keys: keys[i] for rays[i] (NULL: every key 0). */
void dirt_ref_intersect_keys(const dirt_ref_accel *accel, const dirt_ref_ray *rays,
                             const uint32_t *keys, dirt_ref_hit *hits, size_t count,
                             int threads);
void dirt_ref_occluded_keys(const dirt_ref_accel *accel, const dirt_ref_ray *rays,
                            const uint32_t *keys, uint8_t *occluded, size_t count,
                            int threads);

/* ---- work of a BVH traversal (ref/bvh_work.c) ---------------------------- */

/* Embree's BVH (rtcBuildBVH: SAH, medium quality, 4 children, up to 4
 * triangles per leaf) over a frame's triangles, walked by a counting
 * traversal: what a ray costs a BVH, counted, not timed. */
typedef struct dirt_ref_bvh dirt_ref_bvh;

typedef struct dirt_ref_work {
    uint32_t bvh_nodes;      /* nodes taken from the traversal stack (inner and leaves) */
    uint32_t triangle_tests; /* triangles of the leaves reached */
} dirt_ref_work;

/* NULL after logging. The frame is copied. */
dirt_ref_bvh *dirt_ref_bvh_create(const dirt_frame *frame);
/* Accepts NULL. */
void dirt_ref_bvh_destroy(dirt_ref_bvh *bvh);
/* The closest hit (any_hit: the first found) of one ray, t in [tmin, tmax],
 * ties to the lower primitive id, and its work. `hit` may be NULL. */
void dirt_ref_bvh_trace1(const dirt_ref_bvh *bvh, const dirt_ref_ray *ray, bool any_hit,
                         dirt_ref_hit *hit, dirt_ref_work *work);
/* A batch on `threads` threads (0 = every CPU); `hits` may be NULL. */
void dirt_ref_bvh_trace(const dirt_ref_bvh *bvh, const dirt_ref_ray *rays, size_t count,
                        bool any_hit, dirt_ref_hit *hits, dirt_ref_work *work, int threads);

/* ---- rendering ---------------------------------------------------------- */

enum dirt_ref_mode {
    DIRT_REF_MODE_PT = 0, /* path tracing */
    DIRT_REF_MODE_AO = 1, /* ambient occlusion: fraction of cosine rays from
                             the first hit unblocked within ao_distance */
};

/* Progress: `done` of `total` samples (pixels x spp) are finished. Called
 * from worker threads, never two at once, `done` increasing, the last call
 * with done == total. */
typedef void (*dirt_ref_progress_fn)(void *user, uint64_t done, uint64_t total);

/* Zero-initialised = defaults. */
typedef struct dirt_ref_opts {
    int width, height;     /* image size; 0 = 640 x 480 (each) */
    int spp;               /* samples per pixel; 0 = 16 */
    uint32_t first_sample; /* sample index of the first sample, so progressive
                              passes continue the same sequence */
    int bounces;           /* K: scattering events per path (1 = direct light
                              only); 0 = 4 */
    enum dirt_ref_mode mode;
    float ao_distance;     /* AO ray length; 0 = infinite */
    uint32_t seed;         /* RNG seed (doc/rng.md) */
    float background[3];   /* radiance of rays that leave the scene: the
                              constant environment (dirt_env_constant),
                              importance-sampled like any map; ignored when
                              `env` is given */
    const struct dirt_env *env; /* environment light (borrowed; NULL = the
                              background) */
    int threads;           /* render (and BVH build) threads; 0 = all CPUs */
    const dirt_ref_accel *accel; /* BVH of this frame to reuse; NULL = build
                                    one (and report its build time) */
    dirt_ref_progress_fn progress;
    void *progress_user;
    /* A part of the image: the tiles [first_tile, first_tile + num_tiles)
     * of DIRT_REF_TILE x DIRT_REF_TILE pixels in row-major order
     * (dirt_ref_num_tiles; the last row and column may be smaller);
     * num_tiles 0 = every tile from first_tile on. A pixel's values depend
     * on the seed, the pixel and the sample index only, so parts add up
     * to the whole image bit for bit. */
    size_t first_tile, num_tiles;
    /* With a part: the image to write its pixels into, made by an earlier
     * call of the same size (its channels are found by name); the pixels
     * of other tiles are left as they are, and the call returns `into`
     * (the caller keeps owning it; on failure it is not destroyed). NULL =
     * a new image whose other pixels are 0. */
    dirt_image *into;
} dirt_ref_opts;

/* The tile size of dirt_ref_opts.first_tile / num_tiles, in pixels. */
#define DIRT_REF_TILE 16
/* Tiles of a width x height image (0 for a size below 1). */
size_t dirt_ref_num_tiles(int width, int height);

typedef struct dirt_ref_stats {
    double build_ms;        /* BVH build (0 when opts->accel was given) */
    double mprims_per_s;
    double seconds;         /* rendering wall time, without the build */
    uint64_t rays;          /* every ray cast: camera, bounce, shadow, AO, Z */
    double mrays_per_s;     /* rays / seconds / 1e6 */
    uint64_t samples;       /* paths traced (pixels x spp) */
    uint64_t invalid;       /* samples dropped because they were not finite */
    int threads;            /* threads used */
    /* Paths that reached event k (their k-th ray; k = 1 .. DIRT_PT_MAX_EVENTS
     * - 1, 0 unused): with the same seed, the GPU path tracer's
     * dirt_pt_stats.paths_at_event. */
    uint64_t paths_at_event[DIRT_PT_MAX_EVENTS];
} dirt_ref_stats;

/* Materials and textures a render shades with (a view; nothing is copied). */
typedef struct dirt_ref_materials {
    const dirt_material *materials;
    size_t num_materials;
    const dirt_texture *textures;
    size_t num_textures;
    /* Per material extra factor on the dielectric specular weight: it
     * multiplies the material's own specularFactor (KHR_materials_specular,
     * doc/light-transport.md section 2; 0 = no dielectric reflection, exactly
     * Lambert); NULL = 1 for every one. */
    const float *specular;
} dirt_ref_materials;

/* Renders `frame` (lights: frame->lights plus every emissive triangle) seen
 * by `camera` with the materials of `scene`. Returns a new image (caller
 * destroys it): RGBA = mean radiance (PT) or AO value (AO) of the spp
 * samples, A = 1; extra channels of the first hit, averaged over the samples
 * (0 for samples that miss): "albedo.R/G/B" (textured base colour),
 * "N.X/Y/Z" (world-space shading normal facing the camera); and "Z": the
 * distance along camera forward to the first hit of the ray through the
 * pixel centre (pinhole), INFINITY where it misses, and "ID": that hit's
 * primitive as a float (exact below 2^24 triangles), -1 where it misses.
 * `opts` and `stats` may be NULL. NULL after logging on failure (invalid
 * options, material index out of range, out of memory, Embree error). */
dirt_image *dirt_ref_render(const dirt_scene *scene, const dirt_frame *frame,
                            const dirt_camera *camera, const dirt_ref_opts *opts,
                            dirt_ref_stats *stats);

/* The same with materials given directly (tests, procedural content). */
dirt_image *dirt_ref_render_materials(const dirt_ref_materials *materials,
                                      const dirt_frame *frame,
                                      const dirt_camera *camera,
                                      const dirt_ref_opts *opts,
                                      dirt_ref_stats *stats);

#ifdef __cplusplus
}
#endif
#endif
