/* What each program accepts of the option table (options.h): its options
 * in the sections of its --help, with its own defaults where they differ
 * from the table's, and its usage text. */
#include "app/options.h"

/* ---- dirt-render ---- */

static const app_use render_output_opts[] = {
    {APP_OPT_OUTPUT}, {APP_OPT_WIDTH}, {APP_OPT_HEIGHT}, {APP_OPT_PNG}, {APP_OPT_EXPOSURE},
    {APP_OPT_TONEMAP}, {APP_OPT_MSE_REFERENCE}, {APP_OPT_INFO}, {APP_OPT_STATS}, {APP_OPT_NONE}};
static const app_use render_scene_opts[] = {
    {APP_OPT_TIME}, {APP_OPT_FRAMES}, {APP_OPT_FPS}, {APP_OPT_CLIP}, {APP_OPT_LOOP},
    {APP_OPT_CAMERA}, {APP_OPT_AUTO_CAMERA}, {APP_OPT_EYE}, {APP_OPT_LOOK_AT}, {APP_OPT_UP},
    {APP_OPT_FOV}, {APP_OPT_ZNEAR}, {APP_OPT_ZFAR}, {APP_OPT_APERTURE}, {APP_OPT_FOCUS},
    {APP_OPT_MAX_SCENE_MEMORY}, {APP_OPT_STRICT}, {APP_OPT_ALLOW_OUTSIDE_PATHS}, {APP_OPT_NONE}};
static const app_use render_technique_opts[] = {
    {APP_OPT_ENGINE}, {APP_OPT_MODE}, {APP_OPT_SPP}, {APP_OPT_BOUNCES}, {APP_OPT_SEED},
    {APP_OPT_AO_DISTANCE}, {APP_OPT_BACKGROUND}, {APP_OPT_ENV}, {APP_OPT_ENV_INTENSITY},
    {APP_OPT_ENV_ROTATION}, {APP_OPT_THREADS}, {APP_OPT_GPU}, {APP_OPT_CPU_TIMING},
    {APP_OPT_COUNT_WORK}, {APP_OPT_SORT_RAYS}, {APP_OPT_NONE}};
static const app_use render_dirt_opts[] = {
    {APP_OPT_DEBUG_ADS}, {APP_OPT_VIEWS}, {APP_OPT_TILE}, {APP_OPT_BUCKETS}, {APP_OPT_FACE_SIZE},
    {APP_OPT_NO_CONSERVATIVE}, {APP_OPT_BUILD}, {APP_OPT_DEPTH_BUCKETS}, {APP_OPT_LARGE},
    {APP_OPT_LARGE_GRID}, {APP_OPT_SUB_TILES}, {APP_OPT_BUCKET_MASKS}, {APP_OPT_NODE_DEPTHS},
    {APP_OPT_HIZ_TOP},
    {APP_OPT_FETCH}, {APP_OPT_DIRECT_VISIBILITY}, {APP_OPT_GRAPH_DOT}, {APP_OPT_NONE}};
static const app_use render_mmrt_opts[] = {
    {APP_OPT_MARCH}, {APP_OPT_SAMPLES}, {APP_OPT_THICKNESS}, {APP_OPT_NONE}};
static const app_use render_farm_opts[] = {
    {APP_OPT_SKIP_EXISTING}, {APP_OPT_PLACEHOLDERS}, {APP_OPT_CLAIM_TIMEOUT}, {APP_OPT_CHUNK},
    {APP_OPT_ANIMATED_SEED}, {APP_OPT_LOG}, {APP_OPT_NONE}};
static const app_use render_other_opts[] = {
    {APP_OPT_QUIET}, {APP_OPT_VERBOSE}, {APP_OPT_VERSION}, {APP_OPT_HELP}, {APP_OPT_NONE}};

static const app_section render_sections[] = {
    {"Output:", render_output_opts},
    {"Scene and camera:", render_scene_opts},
    {"Technique:", render_technique_opts},
    {"DIRT acceleration structure (--engine dirt, --debug-ads; --views, --face-size, -B\n"
     "and --hiz-top also set MMRT's):", render_dirt_opts},
    {"MMRT (--engine mmrt; tile size 1: MMRT is per pixel):", render_mmrt_opts},
    {"Sequences and farms:", render_farm_opts},
    {"Other:", render_other_opts},
    {NULL, NULL}};

const app_program app_render_program = {
    .name = "dirt-render",
    .usage =
        "Usage: dirt-render [SCENE] -o OUTPUT [options]\n"
        "       dirt-render --info [SCENE]\n"
        "       dirt-render --version\n"
        "\n"
        "Renders a glTF 2.0 (.gltf, .glb) or OBJ + MTL (.obj) scene headless through\n"
        "OpenGL 4.5 (EGL). Without SCENE (or with SCENE 'default'), renders the embedded\n"
        "default scene (a Cornell-style room).\n",
    .sections = render_sections,
    .epilogue =
        "Exit status: 0 success, 1 render failure, 2 bad option or input (unreadable\n"
        "or malformed scene, unwritable output, an output that is an input), 3 no\n"
        "OpenGL 4.5 context; the message of an exit 2 names its reason's id.\n"
        "Images are written atomically: a failed run leaves no partial file, no\n"
        "directory it made, no empty log. Each EXR's\n"
        "header records what made it: dirt.scene, dirt.engine, dirt.seed, dirt.samples,\n"
        "dirt.time, dirt.device, dirt.command_line, dirt.version and dirt.commit.\n",
    .max_scenes = 1,
};

/* ---- dirt-compare ---- */

static const app_use compare_output_opts[] = {{APP_OPT_OUTPUT_DIR}, {APP_OPT_NONE}};
static const app_use compare_sweep_opts[] = {
    {APP_OPT_RES, APP_USE_LIST},
    {APP_OPT_VIEWS, APP_USE_LIST},
    {APP_OPT_TILE, APP_USE_LIST, "1", "1: the paper's Table 2 compares at 1x1 tiles"},
    {APP_OPT_DIRT_BUCKETS, APP_USE_LIST, NULL, "4, MMRT's"},
    {APP_OPT_MMRT_BUCKETS, APP_USE_LIST},
    {APP_OPT_THICKNESS, APP_USE_LIST, "0"},
    {APP_OPT_THICKNESS_REL, APP_USE_LIST},
    {APP_OPT_MARCH, APP_USE_LIST},
    {APP_OPT_SAMPLES, APP_USE_LIST, "0", "0; Hi-Z rows take none"},
    {APP_OPT_SPP, APP_USE_LIST, "1"},
    {APP_OPT_BOUNCES, APP_USE_LIST},
    {APP_OPT_TIME, APP_USE_LIST},
    {APP_OPT_FRAMES, 0, NULL, "--time's list; at most 16 frames"},
    {APP_OPT_FPS},
    {APP_OPT_NONE}};
static const app_use compare_measure_opts[] = {
    {APP_OPT_WARMUP}, {APP_OPT_REPEAT}, {APP_OPT_FACE_SIZE}, {APP_OPT_LARGE}, {APP_OPT_LARGE_GRID},
    {APP_OPT_SUB_TILES}, {APP_OPT_BUCKET_MASKS}, {APP_OPT_NODE_DEPTHS}, {APP_OPT_DEPTH_BUCKETS},
    {APP_OPT_AGREE_RES}, {APP_OPT_NO_QUALITY}, {APP_OPT_COUNT_WORK}, {APP_OPT_IMAGES},
    {APP_OPT_SEED, 0, "7"}, {APP_OPT_MAX_SCENE_MEMORY}, {APP_OPT_STRICT},
    {APP_OPT_ALLOW_OUTSIDE_PATHS}, {APP_OPT_GPU}, {APP_OPT_PRESET}, {APP_OPT_NONE}};
static const app_use compare_lighting_opts[] = {
    {APP_OPT_BACKGROUND, 0, NULL, "none: the lighting above"}, {APP_OPT_ENV},
    {APP_OPT_ENV_INTENSITY}, {APP_OPT_ENV_ROTATION}, {APP_OPT_NONE}};
static const app_use compare_other_opts[] = {
    {APP_OPT_QUIET}, {APP_OPT_VERBOSE}, {APP_OPT_VERSION}, {APP_OPT_HELP}, {APP_OPT_NONE}};
static const app_section compare_sections[] = {
    {"Output:", compare_output_opts},
    {"Sweeps (comma-separated lists; every combination is a configuration):", compare_sweep_opts},
    {"Measurement:", compare_measure_opts},
    {"Lighting (the same for DIRT, MMRT and Embree; stated per scene in table.md and\n"
     "in every row of results.csv/json): each scene is lit as authored, by its emissive\n"
     "triangles and punctual lights, with no environment (black); a scene with neither\n"
     "is lit by the built-in sky instead (as --env sky). These replace that environment\n"
     "for every scene (the scene's own lights stay), as in dirt-render:",
     compare_lighting_opts},
    {"Other:", compare_other_opts},
    {NULL, NULL}};

const app_program app_compare_program = {
    .name = "dirt-compare",
    .usage =
        "Usage: dirt-compare SCENE... -o DIR [options]\n"
        "       dirt-compare --version\n"
        "\n"
        "Measures DIRT against the MMRT fragment A-buffer on each configuration of a\n"
        "sweep (every combination of the lists below, per SCENE; \"default\" is the\n"
        "embedded scene) and writes DIR/table.md (the DIRT paper's Table 2 layout),\n"
        "DIR/results.csv, DIR/results.json (doc/compare.md) and figures through\n"
        "gnuplot (NAME.svg, NAME.png and their data NAME.dat: memory and times vs\n"
        "image size per scene and vs triangles per image size, DIRT / MMRT ratios\n"
        "per scene and size, MMRT's hit agreement vs its thickness; one series per\n"
        "technique and setting, MMRT's per thickness; min-max bars over the\n"
        "repeats; a figure without a series of two points is left out). A rerun\n"
        "with the same DIR skips the configurations already done.\n",
    .sections = compare_sections,
    .epilogue =
        "Exit status: 0 all done, 1 a configuration failed (recorded with its reason)\n"
        "or an output could not be written, 2 bad option or input (a scene, preset or\n"
        "--env map inside DIR, which the outputs own, included), 3 no OpenGL 4.5.\n",
    .max_scenes = APP_MAX_SCENES,
};

/* ---- dirt-view ---- */

#define RT APP_USE_RUNTIME /* a script may `set` it */


static const app_use view_window_opts[] = {
    {APP_OPT_WINDOW},
    {APP_OPT_WIDTH, RT, "", "follow the window"},
    {APP_OPT_HEIGHT, RT, NULL, "follow the window, or width / the camera's aspect with --width"},
    {APP_OPT_SPP, RT, "1024", "1024: stop accumulating there"},
    {APP_OPT_SAMPLES_PER_FRAME, RT}, {APP_OPT_SLICE_MS, RT}, {APP_OPT_BUFFER, RT}, {APP_OPT_EXPOSURE, RT},
    {APP_OPT_TONEMAP, RT}, {APP_OPT_COMPARE, RT}, {APP_OPT_COMPARE_IMAGE},
    {APP_OPT_SPLIT, RT}, {APP_OPT_DIFF, RT},
    {APP_OPT_DIFF_RANGE, RT}, {APP_OPT_SCALE, RT}, {APP_OPT_NO_PREVIEW, RT}, {APP_OPT_NO_UI, RT},
    {APP_OPT_NONE}};
static const app_use view_scene_opts[] = {
    {APP_OPT_TIME, RT}, {APP_OPT_CLIP, RT}, {APP_OPT_LOOP, RT}, {APP_OPT_PLAY, RT},
    {APP_OPT_SPEED, RT}, {APP_OPT_CAMERA, RT}, {APP_OPT_AUTO_CAMERA}, {APP_OPT_EYE, RT},
    {APP_OPT_LOOK_AT, RT}, {APP_OPT_UP, RT}, {APP_OPT_FOV, RT}, {APP_OPT_ZNEAR, RT},
    {APP_OPT_ZFAR, RT}, {APP_OPT_APERTURE, RT}, {APP_OPT_FOCUS, RT},
    {APP_OPT_MAX_SCENE_MEMORY}, {APP_OPT_STRICT}, {APP_OPT_ALLOW_OUTSIDE_PATHS}, {APP_OPT_NONE}};
static const app_use view_technique_opts[] = {
    {APP_OPT_ENGINE, RT}, {APP_OPT_MODE, RT}, {APP_OPT_BOUNCES, RT}, {APP_OPT_SEED, RT},
    {APP_OPT_AO_DISTANCE, RT}, {APP_OPT_BACKGROUND, RT}, {APP_OPT_ENV},
    {APP_OPT_ENV_INTENSITY, RT}, {APP_OPT_ENV_ROTATION, RT}, {APP_OPT_THREADS, RT},
    {APP_OPT_CPU_TIMING}, {APP_OPT_SORT_RAYS, RT}, {APP_OPT_VIEWS, RT}, {APP_OPT_TILE, RT}, {APP_OPT_BUCKETS, RT},
    {APP_OPT_FACE_SIZE, RT}, {APP_OPT_NO_CONSERVATIVE, RT}, {APP_OPT_BUILD, RT},
    {APP_OPT_DEPTH_BUCKETS, RT},
    {APP_OPT_LARGE, RT}, {APP_OPT_LARGE_GRID, RT}, {APP_OPT_SUB_TILES, RT},
    {APP_OPT_BUCKET_MASKS, RT}, {APP_OPT_NODE_DEPTHS, RT}, {APP_OPT_HIZ_TOP, RT}, {APP_OPT_FETCH, RT},
    {APP_OPT_DIRECT_VISIBILITY, RT}, {APP_OPT_MARCH, RT}, {APP_OPT_SAMPLES, RT},
    {APP_OPT_THICKNESS, RT}, {APP_OPT_NONE}};
static const app_use view_script_opts[] = {
    {APP_OPT_SCRIPT}, {APP_OPT_TEST_FRAMES}, {APP_OPT_SCREENSHOT}, {APP_OPT_SAVE_IMAGE},
    {APP_OPT_REPORT}, {APP_OPT_BINDINGS}, {APP_OPT_NONE}};
static const app_use view_other_opts[] = {
    {APP_OPT_QUIET}, {APP_OPT_VERBOSE}, {APP_OPT_VERSION}, {APP_OPT_HELP}, {APP_OPT_NONE}};
static const app_section view_sections[] = {
    {"Window and render:", view_window_opts},
    {"Scene, camera and animation (as dirt-render):", view_scene_opts},
    {"Technique (as dirt-render; the DIRT and MMRT options as its sections say):",
     view_technique_opts},
    {"Scripted mode (tests, reproducible demos; a script's `set NAME VALUE` takes the\n"
     "options above but --window, --auto-camera, --env, --cpu-timing,\n"
     "--max-scene-memory, --strict and --allow-outside-paths):", view_script_opts},
    {"Other:", view_other_opts},
    {NULL, NULL}};

const app_program app_view_program = {
    .name = "dirt-view",
    .usage =
        "Usage: dirt-view [SCENE] [options]\n"
        "\n"
        "Interactive viewer: progressive path tracing of a glTF 2.0 (.gltf, .glb) or\n"
        "OBJ (.obj) scene (without SCENE, or with 'default', the embedded default scene)\n"
        "through DIRT, the MMRT A-buffer, Embree or the raster preview, with panels for\n"
        "every setting, the structure's heat maps, per-pass timings and memory. F1 in\n"
        "the window lists the key bindings (also doc/viewer.md, --bindings).\n"
        "Camera bookmarks (Ctrl + 1..9 saves, Shift + 1..9 goes to one; the Bookmarks\n"
        "panel; the script's `bookmark`) are kept in SCENE.bookmarks.json beside the\n"
        "scene, read when the scene opens and rewritten on each change (the default\n"
        "scene's in memory only). F5 reloads the shaders from a source tree.\n",
    .sections = view_sections,
    .epilogue =
        "Exit status: 0 done, 1 a write failed, 2 bad option, scene or script (or an\n"
        "output that is an input), 3 no window or OpenGL 4.5 context. A saved .exr render records what made it\n"
        "in its header (as dirt-render's do), with dirt.render_args: the dirt-render\n"
        "options of the image.\n",
    .max_scenes = 1,
};
