/* The one option table of the programs and what reads it: the parser, the
 * defaults, the help text, the shared checks (options.h). */
#include "app/options.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "dirt/input.h"
#include "dirt/log.h"

const char *const app_engine_names[] = {"dirt", "mmrt", "embree", "raster", NULL};
const char *const app_compare_names[] = {"none", "dirt", "mmrt", "embree", "raster", NULL};
const char *const app_mode_names[] = {"pt", "ao", NULL};
const char *const app_views_names[] = {"", "single", "cube", "cube+camera", NULL};
const char *const app_fetch_names[] = {"compute", "raster", NULL};
const char *const app_build_names[] = {"auto", "raster", "compute", NULL};
const char *const app_depth_buckets_names[] = {"uniform", "adaptive", NULL};
const char *const app_march_names[] = {"hiz", "linear", NULL};
const char *const app_tonemap_names[] = {"clamp", "reinhard", "aces", NULL};
const char *const app_buffer_names[] = {"beauty", "albedo", "normal", "depth", "id", "lists",
                                        "buckets", "zmin", "zmax", NULL};
static const char *const gpu_names[] = {"auto", "device", "surfaceless", NULL};
static const char *const ext_json[] = {".json", NULL};
static const char *const ext_jsonl[] = {".jsonl", NULL};
static const char *const ext_dot[] = {".dot", NULL};
static const char *const ext_png[] = {".png", NULL};
static const char *const ext_image[] = {".exr", ".png", NULL};
static const char *const ext_exr[] = {".exr", NULL};

/* Kinds: 'F' flag (bool; on/off from a script), 'i' int, 'l' long,
 * 'u' uint32_t, 'f' float, 'd' double (each in [lo, hi]), 'c' a choice of
 * `names` (int), 's' text, 'p' a path ending in one of `names`, 'b' R,G,B
 * (float[3], non-negative), 'v' X,Y,Z (float[3]), 'x' WxH (int[2], each
 * side in [lo, hi]), 'z' bytes with a K/M/G suffix (size_t), 'T' a tile
 * size (int: 1, 2, 4 or 8), 'R' frames (seq_frames), 'P' options read
 * from a file. */
#define OFF(f) offsetof(app_opts, f)
static const app_opt_def table[APP_NUM_OPTS] = {
    /* ---- outputs ---- */
    [APP_OPT_OUTPUT] = {APP_OPT_OUTPUT, "-o", "--output", NULL, "PATH", 's', OFF(output), 0, 0,
        NULL, "image to write: .exr (float RGBA + albedo, N, Z; the header records what made "
        "it) or .png (8-bit sRGB). With --frames, PATH holds one frame field: a run of # "
        "(f_####.exr: the frame zero-padded to 4) or a printf integer (f_%04d.exr). Missing "
        "directories are made", NULL, NULL},
    [APP_OPT_OUTPUT_DIR] = {APP_OPT_OUTPUT_DIR, "-o", "--output", NULL, "DIR", 's', OFF(output),
        0, 0, NULL, "directory of the results (made when missing)", NULL, NULL},
    [APP_OPT_WIDTH] = {APP_OPT_WIDTH, "-W", "--width", NULL, "N", 'i', OFF(s.width), 1, 16384,
        NULL, "image width in pixels", "640", NULL},
    [APP_OPT_HEIGHT] = {APP_OPT_HEIGHT, "-H", "--height", NULL, "N", 'i', OFF(s.height), 1, 16384,
        NULL, "image height in pixels", NULL,
        "width / the camera's aspect, 4:3 for the automatic camera"},
    [APP_OPT_PNG] = {APP_OPT_PNG, NULL, "--png", NULL, NULL, 'F', OFF(png), 0, 0, NULL,
        "with an .exr output, also write a .png preview beside it", NULL, NULL},
    [APP_OPT_EXPOSURE] = {APP_OPT_EXPOSURE, NULL, "--exposure", NULL, "STOPS", 'f', OFF(exposure),
        -64, 64, NULL, "exposure of PNG images and of the display: colour times 2^STOPS", "0",
        NULL},
    [APP_OPT_TONEMAP] = {APP_OPT_TONEMAP, NULL, "--tonemap", NULL, "OP", 'c', OFF(tonemap), 0, 0,
        app_tonemap_names, "tone map of PNG images and of the display: clamp, reinhard or aces",
        "clamp", NULL},
    [APP_OPT_MSE_REFERENCE] = {APP_OPT_MSE_REFERENCE, NULL, "--mse-reference", NULL, "FILE.exr",
        's', OFF(mse_reference), 0, 0, NULL, "print and record each frame's MSE and relative MSE "
        "against this image (it may hold a frame field)", NULL, NULL},
    [APP_OPT_INFO] = {APP_OPT_INFO, NULL, "--info", NULL, NULL, 'F', OFF(info), 0, 0, NULL,
        "print the scene's cameras, clips, lights, emitters and counts, and exit", NULL, NULL},
    [APP_OPT_STATS] = {APP_OPT_STATS, NULL, "--stats", NULL, "FILE.json", 'p', OFF(stats), 0, 0,
        ext_json, "write timings (per pass, with the clock that measured them), ray counts, "
        "paths per path event, bytes per buffer and what made the run (provenance) as JSON",
        NULL, NULL},
    [APP_OPT_GRAPH_DOT] = {APP_OPT_GRAPH_DOT, NULL, "--graph-dot", NULL, "FILE.dot", 'p',
        OFF(graph_dot), 0, 0, ext_dot, "write the path tracer's frame graph (dirt, mmrt)", NULL,
        NULL},
    [APP_OPT_DEBUG_ADS] = {APP_OPT_DEBUG_ADS, NULL, "--debug-ads", NULL, "DIR", 's',
        OFF(debug_ads), 0, 0, NULL, "build the DIRT structure for the frame, print its stats "
        "and write heat maps of list lengths and depth bounds per view into DIR (single frame "
        "only)", NULL, NULL},
    /* ---- scene, time and camera ---- */
    [APP_OPT_TIME] = {APP_OPT_TIME, "-t", "--time", NULL, "T", 'd', OFF(time), -1e6, 1e6, NULL,
        "animation time in seconds", "0", NULL},
    [APP_OPT_FRAMES] = {APP_OPT_FRAMES, NULL, "--frames", NULL, "LIST", 'R', OFF(frames), 0, 0,
        NULL, "frames A:B[:step] (A..B inclusive) or a list such as 1,5,10-20, each at time "
        "frame / fps", NULL, NULL},
    [APP_OPT_FPS] = {APP_OPT_FPS, NULL, "--fps", NULL, "F", 'd', OFF(fps), 1e-3, 1e4, NULL,
        "frames per second of --frames", "24", NULL},
    [APP_OPT_CLIP] = {APP_OPT_CLIP, NULL, "--clip", NULL, "I", 'i', OFF(clip), -1, 1000000, NULL,
        "animation clip index; -1 = the rest pose", "0", NULL},
    [APP_OPT_LOOP] = {APP_OPT_LOOP, NULL, "--loop", NULL, NULL, 'F', OFF(loop), 0, 0, NULL,
        "wrap time into the clip instead of clamping", NULL, NULL},
    [APP_OPT_PLAY] = {APP_OPT_PLAY, NULL, "--play", NULL, NULL, 'F', OFF(play), 0, 0, NULL,
        "play the animation (Space toggles it)", NULL, NULL},
    [APP_OPT_SPEED] = {APP_OPT_SPEED, NULL, "--speed", NULL, "X", 'd', OFF(speed), -100, 100, NULL,
        "animation time per second of play", "1", NULL},
    [APP_OPT_CAMERA] = {APP_OPT_CAMERA, NULL, "--camera", NULL, "I", 'i', OFF(camera), 0, 1000000,
        NULL, "look through the scene's camera I", NULL,
        "camera 0, or an automatic camera framing the scene when it has none"},
    [APP_OPT_AUTO_CAMERA] = {APP_OPT_AUTO_CAMERA, NULL, "--auto-camera", NULL, NULL, 'F',
        OFF(auto_camera), 0, 0, NULL, "ignore the scene's cameras: frame the whole animation "
        "clip (the same camera at every frame)", NULL, NULL},
    [APP_OPT_EYE] = {APP_OPT_EYE, NULL, "--eye", NULL, "X,Y,Z", 'v', OFF(look.eye), 0, 0, NULL,
        "a camera of its own: its position (with --look-at; the numbers dirt-view prints for "
        "its camera)", NULL, NULL},
    [APP_OPT_LOOK_AT] = {APP_OPT_LOOK_AT, NULL, "--look-at", NULL, "X,Y,Z", 'v', OFF(look.target),
        0, 0, NULL, "the point that camera looks at", NULL, NULL},
    [APP_OPT_UP] = {APP_OPT_UP, NULL, "--up", NULL, "X,Y,Z", 'v', OFF(look.up), 0, 0, NULL,
        "its up direction", "0,1,0", NULL},
    [APP_OPT_FOV] = {APP_OPT_FOV, NULL, "--fov", NULL, "DEG", 'f', OFF(look.fov_deg), 1e-3, 179.9,
        NULL, "its vertical field of view", NULL, "45"},
    [APP_OPT_ZNEAR] = {APP_OPT_ZNEAR, NULL, "--znear", NULL, "Z", 'f', OFF(look.znear), 1e-12, 1e30,
        NULL, "its near plane", NULL, "1/1000 of the distance to the --look-at point"},
    [APP_OPT_ZFAR] = {APP_OPT_ZFAR, NULL, "--zfar", NULL, "Z", 'f', OFF(look.zfar), 1e-12, 1e30,
        NULL, "its far plane", NULL, "infinite"},
    [APP_OPT_APERTURE] = {APP_OPT_APERTURE, NULL, "--aperture", NULL, "R", 'f', OFF(s.aperture), 0,
        1e6, NULL, "thin-lens aperture radius; 0 = a pinhole", "0", NULL},
    [APP_OPT_FOCUS] = {APP_OPT_FOCUS, NULL, "--focus", NULL, "D", 'f', OFF(s.focus), 0, 1e9, NULL,
        "focus distance of the thin lens; 0 = the distance to the scene's centre", "0",
        NULL},
    [APP_OPT_MAX_SCENE_MEMORY] = {APP_OPT_MAX_SCENE_MEMORY, NULL, "--max-scene-memory", NULL,
        "SIZE", 'z', OFF(max_scene_bytes), 1, 1099511627776.0, NULL, "the most memory "
        "loading the scene may hold (its files, the parsed glTF JSON, textures by their "
        "declared size, the vertex and index arrays and the triangles made of them; "
        "doc/scenes.md), and loading the --env map: a scene or map that needs more is refused "
        "(exit 2, TOO_LARGE) before the memory is taken. SIZE in bytes, or with a K, M or G "
        "suffix (powers of 1024)", "512M", NULL},
    [APP_OPT_STRICT] = {APP_OPT_STRICT, NULL, "--strict", NULL, NULL, 'F', OFF(strict), 0, 0,
        NULL, "every warning about the scene (a missing or undecodable texture, a missing MTL "
        "library, an ignored extension or MTL statement) exits 2 (STRICT)", NULL, NULL},
    [APP_OPT_ALLOW_OUTSIDE_PATHS] = {APP_OPT_ALLOW_OUTSIDE_PATHS, NULL, "--allow-outside-paths",
        NULL, NULL, 'F', OFF(allow_outside_paths), 0, 0, NULL, "let the scene read files "
        "outside its folder (by default a buffer, image or MTL path that leads out, by '..', "
        "an absolute path or a symbolic link, exits 2: OUTSIDE)", NULL, NULL},
    /* ---- light transport and the device ---- */
    [APP_OPT_ENGINE] = {APP_OPT_ENGINE, NULL, "--engine", NULL, "NAME", 'c', OFF(s.engine), 0, 0,
        app_engine_names, "dirt: path tracing through the DIRT structure on the GPU; mmrt: the "
        "same path tracer through the MMRT A-buffer (the fragment-based baseline, "
        "doc/mmrt.md); embree: the CPU ground truth (Embree 3); raster: rasterized preview "
        "with direct lighting", "dirt", NULL},
    [APP_OPT_MODE] = {APP_OPT_MODE, NULL, "--mode", NULL, "MODE", 'c', OFF(s.mode), 0, 0,
        app_mode_names, "pt (path tracing) or ao (ambient occlusion)", "pt", NULL},
    [APP_OPT_SPP] = {APP_OPT_SPP, NULL, "--spp", NULL, "N", 'i', OFF(spp), 1, 1 << 20, NULL,
        "samples per pixel of the image", "16", NULL},
    [APP_OPT_BOUNCES] = {APP_OPT_BOUNCES, NULL, "--bounces", NULL, "K", 'i', OFF(s.bounces), 1, 64,
        NULL, "scattering events per path, 1 = direct light", "4", NULL},
    [APP_OPT_SEED] = {APP_OPT_SEED, NULL, "--seed", NULL, "N", 'u', OFF(s.seed), 0, 4294967295.0,
        NULL, "random seed; the same seed gives the same paths in every engine", "0", NULL},
    [APP_OPT_AO_DISTANCE] = {APP_OPT_AO_DISTANCE, NULL, "--ao-distance", NULL, "D", 'f',
        OFF(s.ao_distance), 0, 1e30, NULL, "AO ray length; 0 = infinite", "0", NULL},
    [APP_OPT_BACKGROUND] = {APP_OPT_BACKGROUND, NULL, "--background", NULL, "R,G,B", 'b',
        OFF(s.background), 0, 0, NULL, "radiance of rays that leave the scene: a constant "
        "environment light", "0,0,0", NULL},
    [APP_OPT_ENV] = {APP_OPT_ENV, NULL, "--env", NULL, "FILE", 's', OFF(env_path), 0, 0, NULL,
        "environment light: an equirectangular map (.exr or .hdr, linear radiance; its centre "
        "looks along -Z), or 'sky' for the built-in sky; importance-sampled", NULL, NULL},
    [APP_OPT_ENV_INTENSITY] = {APP_OPT_ENV_INTENSITY, NULL, "--env-intensity", NULL, "X", 'f',
        OFF(env_intensity), 1e-6, 1e6, NULL, "scale of the map's radiance", NULL, "1"},
    [APP_OPT_ENV_ROTATION] = {APP_OPT_ENV_ROTATION, NULL, "--env-rotation", NULL, "DEG", 'f',
        OFF(env_rotation), -1e6, 1e6, NULL, "turn the map about +Y", "0", NULL},
    [APP_OPT_THREADS] = {APP_OPT_THREADS, NULL, "--threads", NULL, "N", 'i', OFF(s.threads), 1,
        4096, NULL, "embree: CPU threads", NULL, "all"},
    [APP_OPT_GPU] = {APP_OPT_GPU, NULL, "--gpu", NULL, "PLATFORM", 'c', OFF(gpu_platform), 0, 0,
        gpu_names, "the headless platform: auto (a hardware GPU's EGL device, else Mesa's "
        "surfaceless platform), device or surfaceless; also the environment variable DIRT_GPU",
        "auto", NULL},
    [APP_OPT_CPU_TIMING] = {APP_OPT_CPU_TIMING, NULL, "--cpu-timing", NULL, NULL, 'F',
        OFF(cpu_timing), 0, 0, NULL, "time passes with glFinish and the CPU clock (always on "
        "with a software renderer such as llvmpipe)", NULL, NULL},
    [APP_OPT_COUNT_WORK] = {APP_OPT_COUNT_WORK, NULL, "--count-work", NULL, NULL, 'F',
        OFF(s.count_work), 0, 0, NULL, "count the work per ray of every ray type (the hit-"
        "agreement rays of the image: DIRT's tiles, Hi-Z steps, list nodes and triangle tests, "
        "MMRT's fragments, Embree's BVH nodes and triangle tests over the same rays) into the "
        "stats; the image does not change", NULL, NULL},
    [APP_OPT_SORT_RAYS] = {APP_OPT_SORT_RAYS, NULL, "--sort-rays", NULL, NULL, 'F',
        OFF(s.sort_rays), 0, 0, NULL, "dirt and mmrt: sort each bounce's rays by origin and "
        "direction before tracing them (coherent rays; the image does not change)", NULL, NULL},
    /* ---- the structure ---- */
    [APP_OPT_VIEWS] = {APP_OPT_VIEWS, NULL, "--views", NULL, "MODE", 'c', OFF(s.views), 0, 0,
        app_views_names, "the structure's views: single, cube or cube+camera", "cube+camera",
        NULL},
    [APP_OPT_TILE] = {APP_OPT_TILE, "-S", "--tile", "--tile-size", "S", 'T', OFF(s.tile_size), 1,
        8, NULL, "DIRT's tile size: 1, 2, 4 or 8", NULL,
        "2, or 4 or 8 when the list heads of 2 would not fit the GPU's storage blocks"},
    [APP_OPT_BUCKETS] = {APP_OPT_BUCKETS, "-B", "--buckets", NULL, "B", 'i', OFF(s.buckets), 1,
        1024, NULL, "depth buckets per tile (DIRT) or per pixel (MMRT)", NULL,
        "dirt: 8 on a software renderer, 16 on a GPU, as measured; mmrt: 4, the MMRT paper's"},
    [APP_OPT_FACE_SIZE] = {APP_OPT_FACE_SIZE, NULL, "--face-size", "--face", "N", 'i',
        OFF(s.face_size), 1, 16384, NULL, "cube face size in pixels", NULL, "max(W,H)/2"},
    [APP_OPT_NO_CONSERVATIVE] = {APP_OPT_NO_CONSERVATIVE, NULL, "--no-conservative-raster", NULL,
        NULL, 'F', OFF(s.force_emulation), 0, 0, NULL, "emulate conservative rasterization even "
        "when GL_NV_conservative_raster is present", NULL, NULL},
    [APP_OPT_BUILD] = {APP_OPT_BUILD, NULL, "--build", NULL, "KIND", 'c', OFF(s.build), 0, 0,
        app_build_names, "how DIRT's structure is built (the same structure either way; "
        "doc/dirt-build.md): raster, compute, or auto: compute on a software renderer, raster "
        "on a GPU, as measured", "auto", NULL},
    [APP_OPT_DEPTH_BUCKETS] = {APP_OPT_DEPTH_BUCKETS, NULL, "--depth-buckets", NULL, "KIND", 'c',
        OFF(s.depth_buckets), 0, 0, app_depth_buckets_names, "where DIRT's depth buckets lie "
        "in each tile (doc/dirt-build.md): uniform (B equal slabs of the tile's depth bounds) "
        "or adaptive (edges at the depths where the tile's primitives are; -B at most 1024)",
        "uniform", NULL},
    [APP_OPT_LARGE] = {APP_OPT_LARGE, NULL, "--large", "--dirt-large", "N", 'l', OFF(large), 0,
        16, NULL, "at most N of the largest triangles are kept out of DIRT's tiles and "
        "tested by every ray (doc/dirt-trace.md; 0 = none)", "16", NULL},
    [APP_OPT_LARGE_GRID] = {APP_OPT_LARGE_GRID, NULL, "--large-grid", NULL, NULL, 'F',
        OFF(s.large_grid), 0, 0, NULL, "test the large primitives through a coarse grid of "
        "their own (per view at most 8x8 cells, each with their depth ranges there; "
        "doc/dirt-trace.md): far fewer exact triangle tests per ray (default scene 12.8 -> 2.9 "
        "per camera ray), more march steps; on llvmpipe the trace was 1.6-1.9x slower, as "
        "every lane pays for the cells' walk. The same hits and image", NULL, NULL},
    [APP_OPT_SUB_TILES] = {APP_OPT_SUB_TILES, NULL, "--sub-tiles", NULL, NULL, 'F',
        OFF(s.sub_tiles), 0, 0, NULL, "every DIRT list node also records which cells of a 4x4 "
        "grid over its tile the primitive may cover, and a ray skips the nodes whose cells its "
        "segment in the tile misses (doc/dirt-build.md, \"Sub-tile rectangles\"): fewer exact "
        "triangle tests per ray where a tile lists many small primitives. The same hits and "
        "image; scenes below 2^24 triangles (else the build fails)", NULL, NULL},
    [APP_OPT_BUCKET_MASKS] = {APP_OPT_BUCKET_MASKS, NULL, "--bucket-masks", NULL, NULL, 'F',
        OFF(s.bucket_masks), 0, 0, NULL, "DIRT's build also keeps one word per tile saying "
        "which of 32 depth slabs hold a primitive (which buckets hold nodes with adaptive "
        "buckets; buckets <= 32; 4 B per tile), and a ray skips a tile with nothing in its "
        "depth span (doc/dirt-build.md, \"Pass 3\"): fewer tiles walked (mirror69k shadow "
        "rays 0.66x, slats69k diffuse rays 0.50x), the same hits and image. Off by default: on "
        "llvmpipe the frame was 3-6 % slower with it", NULL, NULL},
    [APP_OPT_NODE_DEPTHS] = {APP_OPT_NODE_DEPTHS, NULL, "--node-depths", NULL, NULL, 'F',
        OFF(s.node_depths), 0, 0, NULL, "every DIRT list node also records its primitive's "
        "depth range in its bucket (16 sub-slabs, in the node's next word: no memory), and a "
        "ray skips the nodes whose range its depth span in the tile misses (doc/dirt-build.md, "
        "\"Node depth ranges\"): fewer exact triangle tests per ray where a tile lists many "
        "primitives at different depths. The same hits and image; buckets <= 4095", NULL, NULL},
    [APP_OPT_HIZ_TOP] = {APP_OPT_HIZ_TOP, NULL, "--hiz-top", NULL, "L", 'l', OFF(hiz_top), -1, 15,
        NULL, "highest Hi-Z level the march climbs to; 0 = tiles only, no Hi-Z; -1 = the "
        "pyramid's top", "-1", NULL},
    [APP_OPT_FETCH] = {APP_OPT_FETCH, NULL, "--fetch", NULL, "KIND", 'c', OFF(s.fetch), 0, 0,
        app_fetch_names, "DIRT's Fetch: compute, or raster (the paper's geometry pass)",
        "compute", NULL},
    [APP_OPT_DIRECT_VISIBILITY] = {APP_OPT_DIRECT_VISIBILITY, NULL, "--direct-visibility", NULL,
        NULL, 'F', OFF(s.direct_visibility), 0, 0, NULL, "DIRT: first hits from a visibility "
        "buffer of the camera view (pixel centres: no anti-aliasing or depth of field)", NULL,
        NULL},
    [APP_OPT_MARCH] = {APP_OPT_MARCH, NULL, "--march", NULL, "KIND", 'c', OFF(s.march), 0, 0,
        app_march_names, "MMRT's march: hiz (a walk of the min/max depth pyramid) or linear "
        "(jittered samples along the ray in each view)", "hiz", NULL},
    [APP_OPT_SAMPLES] = {APP_OPT_SAMPLES, NULL, "--samples", NULL, "N", 'i', OFF(s.march_samples),
        0, 65536, NULL, "MMRT's linear march: samples per view; 0 = the default", NULL, "30"},
    [APP_OPT_THICKNESS] = {APP_OPT_THICKNESS, NULL, "--thickness", NULL, "T", 'f',
        OFF(s.thickness), 0, 1e12, NULL, "MMRT: a fragment is hit when its depth is within T "
        "(eye-space depth units) of the ray's; rays start 3 T off surfaces; 0 = the default",
        NULL, "0.2% of the scene's bounding-box diagonal"},
    /* ---- sequences and farms ---- */
    [APP_OPT_SKIP_EXISTING] = {APP_OPT_SKIP_EXISTING, NULL, "--skip-existing", NULL, NULL, 'F',
        OFF(skip_existing), 0, 0, NULL, "leave frames whose files are complete alone", NULL,
        NULL},
    [APP_OPT_PLACEHOLDERS] = {APP_OPT_PLACEHOLDERS, NULL, "--placeholders", NULL, NULL, 'F',
        OFF(placeholders), 0, 0, NULL, "claim each frame (FILE.claim.N) before rendering it, so "
        "any number of workers can share one output directory; implies --skip-existing", NULL,
        NULL},
    [APP_OPT_CLAIM_TIMEOUT] = {APP_OPT_CLAIM_TIMEOUT, NULL, "--claim-timeout", NULL, "S", 'd',
        OFF(claim_timeout), 1, 1e7, NULL, "a claim not refreshed for S seconds belongs to a dead "
        "worker and is taken over; one of this host whose process is gone is taken at once",
        "600", NULL},
    [APP_OPT_CHUNK] = {APP_OPT_CHUNK, NULL, "--chunk", NULL, "K/N", 's', OFF(chunk), 0, 0, NULL,
        "render the K-th of N contiguous shares of the frames; --chunk slurm takes K and N "
        "from the Slurm job array", NULL, NULL},
    [APP_OPT_ANIMATED_SEED] = {APP_OPT_ANIMATED_SEED, NULL, "--animated-seed", NULL, NULL, 'F',
        OFF(animated_seed), 0, 0, NULL, "a different seed per frame (the seed mixed with the "
        "frame number; without it every frame has the same noise)", NULL, NULL},
    [APP_OPT_LOG] = {APP_OPT_LOG, NULL, "--log", NULL, "FILE.jsonl", 'p', OFF(log), 0, 0,
        ext_jsonl, "append one JSON record per frame as it finishes, then a summary record",
        NULL, NULL},
    /* ---- the window ---- */
    [APP_OPT_WINDOW] = {APP_OPT_WINDOW, NULL, "--window", NULL, "WxH", 'x', OFF(window), 64,
        16384, NULL, "window size", "1280x720", NULL},
    [APP_OPT_SAMPLES_PER_FRAME] = {APP_OPT_SAMPLES_PER_FRAME, NULL, "--samples-per-frame", NULL,
        "N", 'i', OFF(samples_per_frame), 1, 1024, NULL, "samples completed per displayed frame "
        "at most", "1", NULL},
    [APP_OPT_SLICE_MS] = {APP_OPT_SLICE_MS, NULL, "--slice-ms", NULL, "MS", 'i', OFF(slice_ms), 0,
        10000, NULL, "path tracing per displayed frame, in milliseconds: a sample is traced in "
        "pieces of pixels over as many frames as it needs, so the window answers between "
        "them (0: one smallest piece a frame)", "30", NULL},
    [APP_OPT_BUFFER] = {APP_OPT_BUFFER, NULL, "--buffer", NULL, "NAME", 'c', OFF(buffer), 0, 0,
        app_buffer_names, "what the window shows: beauty, albedo, normal, depth, id, lists, "
        "buckets, zmin or zmax", "beauty", NULL},
    [APP_OPT_COMPARE] = {APP_OPT_COMPARE, NULL, "--compare", NULL, "ENGINE", 'c', OFF(compare), 0,
        0, app_compare_names, "split view against a second engine on the same camera: dirt, "
        "mmrt, embree, raster or none", "none", NULL},
    [APP_OPT_COMPARE_IMAGE] = {APP_OPT_COMPARE_IMAGE, NULL, "--compare-image", NULL, "FILE.exr",
        'p', OFF(compare_image), 0, 0, ext_exr, "split view against a reference image from disk "
        "instead of a second engine (V turns it on and off); the render takes its size (with "
        "-W/-H they must be its size)", NULL, NULL},
    [APP_OPT_SPLIT] = {APP_OPT_SPLIT, NULL, "--split", NULL, "X", 'f', OFF(split), 0, 1, NULL,
        "where the split is, 0..1 of the width", "0.5", NULL},
    [APP_OPT_DIFF] = {APP_OPT_DIFF, NULL, "--diff", NULL, NULL, 'F', OFF(diff), 0, 0, NULL,
        "with --compare: a heat map of the difference instead of the split (X toggles it)",
        NULL, NULL},
    [APP_OPT_DIFF_RANGE] = {APP_OPT_DIFF_RANGE, NULL, "--diff-range", NULL, "R", 'f',
        OFF(diff_range), 1e-6, 1e6, NULL, "the difference that shows white", "0.1", NULL},
    [APP_OPT_SCALE] = {APP_OPT_SCALE, NULL, "--scale", NULL, "N", 'i', OFF(scale), 1, 16, NULL,
        "render at the window's size / N, shown enlarged (default: 1 on a GPU; on a software "
        "renderer, llvmpipe or lavapipe, the N that makes a sample take about 1 s, measured "
        "and said in the log and the Settings panel)", NULL, NULL},
    [APP_OPT_NO_PREVIEW] = {APP_OPT_NO_PREVIEW, NULL, "--no-preview", NULL, NULL, 'F',
        OFF(no_preview), 0, 0, NULL, "no raster preview: path trace while the camera moves, and "
        "show nothing until the first sample completes (without it: the raster preview then)", NULL, NULL},
    [APP_OPT_NO_UI] = {APP_OPT_NO_UI, NULL, "--no-ui", NULL, NULL, 'F', OFF(no_ui), 0, 0, NULL,
        "hide the panels (H toggles them)", NULL, NULL},
    [APP_OPT_SCRIPT] = {APP_OPT_SCRIPT, NULL, "--script", NULL, "FILE", 's', OFF(script), 0, 0,
        NULL, "timed actions (doc/viewer.md: wait-frames, wait-samples, wait-file, orbit, pan, "
        "dolly, fly, camera, key, click, set, resize, screenshot, save-image, report, "
        "print-camera, quit)", NULL, NULL},
    [APP_OPT_TEST_FRAMES] = {APP_OPT_TEST_FRAMES, NULL, "--test-frames", NULL, "N", 'l',
        OFF(test_frames), 1, 1e9, NULL, "quit after N frames", NULL, NULL},
    [APP_OPT_SCREENSHOT] = {APP_OPT_SCREENSHOT, NULL, "--screenshot", NULL, "FILE.png", 'p',
        OFF(screenshot), 0, 0, ext_png, "at exit: the window, panels included", NULL, NULL},
    [APP_OPT_SAVE_IMAGE] = {APP_OPT_SAVE_IMAGE, NULL, "--save-image", NULL, "FILE.exr", 'p',
        OFF(save_image), 0, 0, ext_image, "at exit: the render alone (.exr with a .png beside "
        "it, or .png)", NULL, NULL},
    [APP_OPT_REPORT] = {APP_OPT_REPORT, NULL, "--report", NULL, "FILE.json", 'p', OFF(report), 0,
        0, ext_json, "at exit: camera (as dirt-render options), sizes, samples, panel "
        "rectangles", NULL, NULL},
    [APP_OPT_BINDINGS] = {APP_OPT_BINDINGS, NULL, "--bindings", NULL, NULL, 'F', OFF(bindings), 0,
        0, NULL, "print the key and mouse bindings and exit", NULL, NULL},
    /* ---- measurement ---- */
    [APP_OPT_RES] = {APP_OPT_RES, NULL, "--res", NULL, "WxH", 'x', OFF(res), 1, 16384, NULL,
        "image size", "256x128", NULL},
    [APP_OPT_DIRT_BUCKETS] = {APP_OPT_DIRT_BUCKETS, NULL, "--dirt-buckets", NULL, "B", 'i',
        OFF(dirt_buckets), 1, 1024, NULL, "DIRT's depth buckets per tile (-B of its session)",
        "4", NULL},
    [APP_OPT_MMRT_BUCKETS] = {APP_OPT_MMRT_BUCKETS, NULL, "--mmrt-buckets", NULL, "B", 'i',
        OFF(mmrt_buckets), 1, 1024, NULL, "MMRT's depth buckets per pixel (-B of its session)",
        "4", NULL},
    [APP_OPT_THICKNESS_REL] = {APP_OPT_THICKNESS_REL, NULL, "--thickness-rel", NULL, "F", 'd',
        OFF(thickness_rel), 1e-9, 1, NULL, "MMRT's thickness as a fraction of the scene's "
        "diagonal (configurations in addition to --thickness's)", NULL, NULL},
    [APP_OPT_WARMUP] = {APP_OPT_WARMUP, NULL, "--warmup", NULL, "N", 'i', OFF(warmup), 0, 100,
        NULL, "unmeasured runs before the repeats", "1", NULL},
    [APP_OPT_REPEAT] = {APP_OPT_REPEAT, NULL, "--repeat", NULL, "N", 'i', OFF(repeat), 1, 64, NULL,
        "measured runs; min, median and max per pass", "3", NULL},
    [APP_OPT_AGREE_RES] = {APP_OPT_AGREE_RES, NULL, "--agree-res", NULL, "WxH", 'x',
        OFF(agree_res), 1, 16384, NULL, "camera G-buffer of the hit-agreement rays", NULL,
        "the image size"},
    [APP_OPT_NO_QUALITY] = {APP_OPT_NO_QUALITY, NULL, "--no-quality", NULL, NULL, 'F',
        OFF(no_quality), 0, 0, NULL, "skip hit agreement and relMSE against Embree", NULL, NULL},
    [APP_OPT_IMAGES] = {APP_OPT_IMAGES, NULL, "--images", NULL, NULL, 'F', OFF(images), 0, 0, NULL,
        "write each configuration's images into DIR/images", NULL, NULL},
    [APP_OPT_PRESET] = {APP_OPT_PRESET, NULL, "--preset", NULL, "FILE", 'P', OFF(preset), 0, 0,
        NULL, "read options from FILE (one or more per line, # comments; "
        "data/compare-table*.txt)", NULL, NULL},
    /* ---- every program ---- */
    [APP_OPT_QUIET] = {APP_OPT_QUIET, "-q", "--quiet", NULL, NULL, 'F', OFF(quiet), 0, 0, NULL,
        "print only errors", NULL, NULL},
    [APP_OPT_VERBOSE] = {APP_OPT_VERBOSE, "-v", "--verbose", NULL, NULL, 'F', OFF(verbose), 0, 0,
        NULL, "print debug messages", NULL, NULL},
    [APP_OPT_HELP] = {APP_OPT_HELP, "-h", "--help", NULL, NULL, 'F', OFF(help), 0, 0, NULL,
        "show this help and exit", NULL, NULL},
    [APP_OPT_VERSION] = {APP_OPT_VERSION, NULL, "--version", NULL, NULL, 'F', OFF(version), 0, 0,
        NULL, "print the version, the commit and the OpenGL renderer and exit (exit status 3 "
        "when no OpenGL 4.5 context can be made)", NULL, NULL},
};
#undef OFF

const app_opt_def *app_opt_table(enum app_opt id)
{
    return id > APP_OPT_NONE && id < APP_NUM_OPTS ? &table[id] : NULL;
}

/* ---- finding options ---- */

typedef struct found {
    const app_opt_def *def;
    const app_use *use;
} found;

/* The use of `name` (a spelling, or with `bare` a long name without its
 * dashes) among p's options. */
static found find(const app_program *p, const char *name, bool bare)
{
    for (const app_section *sec = p->sections; sec->title; sec++) {
        for (const app_use *u = sec->uses; u->id != APP_OPT_NONE; u++) {
            const app_opt_def *d = &table[u->id];
            bool hit = bare ? !strcmp(d->l + 2, name) || (d->alias && !strcmp(d->alias + 2, name))
                            : !strcmp(d->l, name) || (d->s && !strcmp(d->s, name)) ||
                                  (d->alias && !strcmp(d->alias, name));
            if (hit)
                return (found){d, u};
        }
    }
    return (found){NULL, NULL};
}

enum app_opt app_find(const app_program *p, const char *name, unsigned flags)
{
    found f = find(p, name, true);
    return f.def && (f.use->flags & flags) == flags ? f.def->id : APP_OPT_NONE;
}

/* ---- values ---- */

/* Bytes: a number with an optional K, M, G or T (powers of 1024). */
static bool parse_bytes(const char *prog, const app_opt_def *d, const char *name, const char *val,
                        size_t *out)
{
    char *end = NULL;
    errno = 0;
    double v = val ? strtod(val, &end) : 0;
    double scale = 1;
    if (end && *end) {
        const char *units = "KMGT";
        const char *u = strchr(units, toupper((unsigned char)*end));
        if (u && end[1] == '\0')
            scale = ldexp(1.0, 10 * (int)(u - units + 1));
        else
            end = NULL;
    }
    v *= scale;
    if (!val || !*val || !end || errno || !isfinite(v) || v < d->lo || v > d->hi ||
        v != floor(v)) {
        cli_error(prog, "%s expects a size in bytes (a whole number, or with a K, M or G "
                  "suffix) in [%.0f, %.0f], got '%s'", name, d->lo, d->hi, val ? val : "");
        return false;
    }
    *out = (size_t)v;
    return true;
}

static bool parse_size(const char *prog, const app_opt_def *d, const char *name, const char *val,
                       int out[2])
{
    int w, h;
    char extra;
    if (!val || sscanf(val, "%dx%d%c", &w, &h, &extra) != 2 || w < d->lo || h < d->lo ||
        w > d->hi || h > d->hi) {
        cli_error(prog, "%s expects WxH (each side %.0f..%.0f), got '%s'", name, d->lo, d->hi,
                  val ? val : "");
        return false;
    }
    out[0] = w;
    out[1] = h;
    return true;
}

static bool parse_path(const char *prog, const app_opt_def *d, const char *name, const char *val,
                       const char **out)
{
    char list[64] = "";
    for (int i = 0; d->names[i]; i++) {
        if (cli_has_ext(val, d->names[i])) {
            *out = val;
            return true;
        }
        size_t n = strlen(list);
        snprintf(list + n, sizeof(list) - n, "%s%s", i ? " or " : "", d->names[i]);
    }
    cli_error(prog, "%s file '%s' must end in %s", name, val, list);
    return false;
}

static bool read_preset(const app_program *p, const char *path, app_opts *o, int depth);
static bool parse_args(const app_program *p, int argc, char **argv, app_opts *o, int depth);

/* Sets the single value of option `d` from `val` into `dst`. */
static bool set_one(const app_program *p, const app_opt_def *d, const char *name, const char *val,
                    void *dst, app_opts *o, int depth)
{
    const char *prog = p->name;
    switch (d->kind) {
    case 'F': {
        bool on = !strcmp(val, "on") || !strcmp(val, "1") || !strcmp(val, "true");
        bool off = !strcmp(val, "off") || !strcmp(val, "0") || !strcmp(val, "false");
        if (!on && !off) {
            cli_error(prog, "%s expects on or off, got '%s'", name, val);
            return false;
        }
        *(bool *)dst = on;
        return true;
    }
    case 'T': {
        long t;
        if (!cli_int(prog, name, val, (long)d->lo, (long)d->hi, &t))
            return false;
        if (t & (t - 1)) {
            cli_error(prog, "%s expects 1, 2, 4 or 8, got '%s'", name, val);
            return false;
        }
        *(int *)dst = (int)t;
        return true;
    }
    case 'p':
        return parse_path(prog, d, name, val, dst);
    case 'x':
        return parse_size(prog, d, name, val, dst);
    case 'z':
        return parse_bytes(prog, d, name, val, dst);
    case 'R': {
        char why[256];
        seq_frames_free(dst);
        if (!seq_frames_parse(val, dst, why, sizeof(why))) {
            cli_error(prog, "%s %s", name, why);
            return false;
        }
        return true;
    }
    case 'P':
        *(const char **)dst = val;
        return read_preset(p, val, o, depth);
    default:
        return cli_value(prog, name, val, d->kind, dst, d->lo, d->hi, d->names);
    }
}

/* A list: each comma-separated item as the single value would be. */
static bool set_list(const app_program *p, const app_opt_def *d, const char *name, const char *val,
                     app_opts *o)
{
    app_list *l = &o->lists[d->id];
    l->n = 0;
    char buf[1024];
    snprintf(buf, sizeof(buf), "%s", val);
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok;
         tok = strtok_r(NULL, ",", &save)) {
        if (l->n == APP_MAX_LIST) {
            cli_error(p->name, "%s: at most %d values", name, APP_MAX_LIST);
            return false;
        }
        union { int i; long l; uint32_t u; float f; double d; int wh[2]; } v;
        memset(&v, 0, sizeof(v));
        if (!set_one(p, d, name, tok, &v, o, 0))
            return false;
        double *out = l->v[l->n++];
        switch (d->kind) {
        case 'l': out[0] = (double)v.l; break;
        case 'u': out[0] = v.u; break;
        case 'f': out[0] = v.f; break;
        case 'd': out[0] = v.d; break;
        case 'x': out[0] = v.wh[0], out[1] = v.wh[1]; break;
        default: out[0] = v.i; break; /* 'i', 'c', 'T' */
        }
    }
    if (!l->n)
        cli_error(p->name, "%s expects a list", name);
    return l->n > 0;
}

static bool apply(const app_program *p, found f, const char *name, const char *val, app_opts *o,
                  int depth)
{
    if (f.use->flags & APP_USE_LIST)
        return set_list(p, f.def, name, val, o);
    return set_one(p, f.def, name, val, (char *)o + f.def->off, o, depth);
}

/* The default value of `u` (the program's, else the table's); NULL: none. */
static const char *default_value(const app_use *u)
{
    const char *v = u->dflt ? u->dflt : table[u->id].dflt;
    return v && v[0] ? v : NULL;
}

void app_opts_init(const app_program *p, app_opts *o)
{
    memset(o, 0, sizeof(*o));
    o->camera = -1;
    for (const app_section *sec = p->sections; sec->title; sec++) {
        for (const app_use *u = sec->uses; u->id != APP_OPT_NONE; u++) {
            const char *v = default_value(u);
            if (v && !apply(p, (found){&table[u->id], u}, table[u->id].l, v, o, 0)) {
                /* A default that does not parse is the table's bug. */
                DIRT_ERROR("%s: the default '%s' of %s does not parse", p->name, v,
                           table[u->id].l);
                abort();
            }
        }
    }
}

void app_opts_free(app_opts *o)
{
    seq_frames_free(&o->frames);
}

/* Text of --preset files, kept for the program's life (their values are
 * pointed at like argv's). */
static char preset_store[16384];
static size_t preset_used;

static bool read_preset(const app_program *p, const char *path, app_opts *o, int depth)
{
    if (depth > 4) {
        cli_error(p->name, "--preset nested too deeply");
        return false;
    }
    /* A regular file of at most 1 MiB (a FIFO or device fails at once). */
    enum dirt_input_error e = DIRT_INPUT_ERR_OK;
    size_t size = 0;
    char *text = dirt_input_read(path, (size_t)1 << 20, &size, &e);
    if (!text) {
        cli_error(p->name, "%s: --preset %s: %s", dirt_input_error_name(e), path,
                  e == DIRT_INPUT_ERR_IO ? strerror(errno) : dirt_input_error_str(e));
        return false;
    }
    if (o->num_presets < (int)(sizeof(o->presets) / sizeof(o->presets[0])))
        o->presets[o->num_presets++] = path;
    char *argv[256];
    int argc = 1;
    argv[0] = (char *)p->name;
    char line[1024];
    for (char *next = text, *nl; *next; next = nl ? nl + 1 : next + strlen(next)) {
        nl = strchr(next, '\n');
        snprintf(line, sizeof(line), "%.*s", nl ? (int)(nl - next) : (int)strlen(next), next);
        char *hash = strchr(line, '#');
        if (hash)
            *hash = 0;
        for (char *save = NULL, *tok = strtok_r(line, " \t\r\n", &save); tok;
             tok = strtok_r(NULL, " \t\r\n", &save)) {
            size_t n = strlen(tok) + 1;
            if (argc == 256 || preset_used + n > sizeof(preset_store)) {
                free(text);
                cli_error(p->name, "--preset %s: too long", path);
                return false;
            }
            memcpy(preset_store + preset_used, tok, n);
            argv[argc++] = preset_store + preset_used;
            preset_used += n;
        }
    }
    free(text);
    return parse_args(p, argc, argv, o, depth + 1);
}

static bool parse_args(const app_program *p, int argc, char **argv, app_opts *o, int depth)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        found f = a[0] == '-' && a[1] ? find(p, a, false) : (found){NULL, NULL};
        if (f.def) {
            o->given[f.def->id] = true;
            if (f.def->kind == 'F' && !(f.use->flags & APP_USE_LIST)) {
                *(bool *)((char *)o + f.def->off) = true;
                continue;
            }
            if (i + 1 >= argc) {
                cli_error(p->name, "option %s needs a value", a);
                return false;
            }
            if (!apply(p, f, a, argv[++i], o, depth))
                return false;
        } else if (a[0] == '-' && a[1] != '\0') {
            cli_error(p->name, "unknown option '%s' (see --help)", a);
            return false;
        } else if (o->num_scenes < p->max_scenes) {
            o->scenes[o->num_scenes++] = a;
        } else if (p->max_scenes == 1) {
            cli_error(p->name, "more than one scene given ('%s' and '%s')", o->scenes[0], a);
            return false;
        } else {
            cli_error(p->name, p->max_scenes ? "at most %d scenes" : "no scene is taken (%d)",
                      p->max_scenes);
            return false;
        }
    }
    return true;
}

int app_parse(const app_program *p, int argc, char **argv, app_opts *o)
{
    bool ok = parse_args(p, argc, argv, o, 0);
    if (o->verbose)
        dirt_log_set_level(DIRT_LOG_DEBUG);
    if (o->quiet)
        dirt_log_set_level(DIRT_LOG_ERROR);
    return ok ? APP_PARSE_OK : APP_PARSE_USAGE;
}

bool app_set(const app_program *p, const char *name, const char *value, unsigned flags,
             app_opts *o)
{
    found f = find(p, name, true);
    if (!f.def || (f.use->flags & flags) != flags) {
        cli_error(p->name, "'%s' is not an option that can be set here", name);
        return false;
    }
    char spelled[96];
    snprintf(spelled, sizeof(spelled), "--%s", name);
    if (!apply(p, f, spelled, value, o, 0))
        return false;
    o->given[f.def->id] = true;
    return true;
}

/* ---- checks ---- */

bool app_check(const app_program *p, const app_opts *o)
{
    const char *prog = p->name;
    bool look = o->given[APP_OPT_EYE] || o->given[APP_OPT_LOOK_AT] || o->given[APP_OPT_UP] ||
                o->given[APP_OPT_FOV] || o->given[APP_OPT_ZNEAR] || o->given[APP_OPT_ZFAR];
    char why[256];
    dirt_session_opts s = app_session_opts(o);
    if (!s.width)
        s.width = 640; /* dirt-view: the window's */
    if (look && !(o->given[APP_OPT_EYE] && o->given[APP_OPT_LOOK_AT]))
        cli_error(prog, "a camera of its own needs both --eye and --look-at");
    else if (look && (o->given[APP_OPT_CAMERA] || o->auto_camera))
        cli_error(prog, "--eye/--look-at and --camera/--auto-camera choose different cameras");
    else if (o->given[APP_OPT_CAMERA] && o->auto_camera)
        cli_error(prog, "--camera and --auto-camera choose different cameras");
    else if (look && o->look.zfar > 0 && o->look.znear > 0 && !(o->look.zfar > o->look.znear))
        cli_error(prog, "--zfar must be beyond --znear");
    else if (o->env_path && o->given[APP_OPT_BACKGROUND])
        cli_error(prog, "--env and --background both set the environment: give one");
    else if (!o->env_path && (o->given[APP_OPT_ENV_INTENSITY] || o->given[APP_OPT_ENV_ROTATION]))
        cli_error(prog, "--env-intensity and --env-rotation need an --env map");
    else if (!dirt_session_check_opts(&s, why, sizeof(why)))
        cli_error(prog, "%s", why);
    else
        return true;
    return false;
}

/* ---- the session's options ---- */

dirt_session_opts app_session_opts(const app_opts *o)
{
    dirt_session_opts s = o->s;
    s.hiz_levels = (int)(o->hiz_top + 1);
    s.large = o->large ? (int)o->large : -1;
    return s;
}

enum dirt_camera_choice app_camera_choice(const app_opts *o)
{
    bool look = o->given[APP_OPT_EYE] || o->given[APP_OPT_LOOK_AT];
    return look ? DIRT_CAMERA_EXPLICIT
           : o->camera >= 0 ? DIRT_CAMERA_SCENE
           : o->auto_camera ? DIRT_CAMERA_AUTO
                            : DIRT_CAMERA_DEFAULT;
}

dirt_camera app_look_camera(const app_opts *o)
{
    dirt_camera c;
    dirt_camera_from_look(&o->look, &c);
    return c;
}

/* ---- help ---- */

#define HELP_COLUMN 24
#define HELP_WIDTH 79

/* Prints `text` from column `col` (already there), wrapped at HELP_WIDTH
 * with the continuation lines at HELP_COLUMN. */
static void wrap(FILE *out, const char *text, int col)
{
    const char *w = text;
    while (*w) {
        while (*w == ' ')
            w++;
        size_t len = strcspn(w, " ");
        if (!len)
            break;
        if (col > HELP_COLUMN && col + 1 + (int)len > HELP_WIDTH) {
            fprintf(out, "\n%*s", HELP_COLUMN, "");
            col = HELP_COLUMN;
        } else if (col > HELP_COLUMN) {
            fputc(' ', out);
            col++;
        }
        fwrite(w, 1, len, out);
        col += (int)len;
        w += len;
    }
    fputc('\n', out);
}

static void print_option(FILE *out, const app_use *u)
{
    const app_opt_def *d = &table[u->id];
    bool list = u->flags & APP_USE_LIST;
    char name[96];
    int n = snprintf(name, sizeof(name), "  %s%s%s", d->s ? d->s : "    ", d->s ? ", " : "", d->l);
    if (d->meta)
        n += snprintf(name + n, sizeof(name) - (size_t)n, " %s%s", d->meta, list ? ",..." : "");
    fputs(name, out);
    if (n >= HELP_COLUMN - 1)
        fprintf(out, "\n%*s", HELP_COLUMN, "");
    else
        fprintf(out, "%*s", HELP_COLUMN - n, "");
    char text[1024];
    const char *dflt = u->note ? u->note : u->dflt ? u->dflt : d->note ? d->note : d->dflt;
    size_t t = (size_t)snprintf(text, sizeof(text), "%s", d->help);
    if (d->alias && t < sizeof(text))
        t += (size_t)snprintf(text + t, sizeof(text) - t, "; also %s", d->alias);
    if (dflt && dflt[0] && t < sizeof(text))
        snprintf(text + t, sizeof(text) - t, " (default %s)", dflt);
    /* The first word at the column, the rest wrapped after it. */
    size_t first = strcspn(text, " ");
    fwrite(text, 1, first, out);
    wrap(out, text + first, HELP_COLUMN + (int)first);
}

void app_print_help(const app_program *p, FILE *out)
{
    fputs(p->usage, out);
    for (const app_section *sec = p->sections; sec->title; sec++) {
        fprintf(out, "\n%s\n", sec->title);
        for (const app_use *u = sec->uses; u->id != APP_OPT_NONE; u++)
            print_option(out, u);
    }
    if (p->epilogue)
        fprintf(out, "\n%s", p->epilogue);
}
