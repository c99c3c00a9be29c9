/* GL 4.5 core contexts: headless EGL (Mesa surfaceless, then EGL devices) and
 * GLFW windows; the capability probe. */
#include "gl/gl.h"
#include "gl/window.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <errno.h>
#include <GLFW/glfw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

static const char *egl_error_name(EGLint e)
{
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error";
    }
}

static bool has_ext(const char *list, const char *name)
{
    if (!list)
        return false;
    size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)); p += n) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    }
    return false;
}

/* Initialises `dpy` and makes a 4.5 core context current without a surface.
 * Returns false (with `dpy` terminated) when that is not possible. */
static bool egl_make_context(dirt_gpu *gpu, EGLDisplay dpy)
{
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor)) {
        DIRT_DEBUG("eglInitialize failed: %s", egl_error_name(eglGetError()));
        return false;
    }
    const char *exts = eglQueryString(dpy, EGL_EXTENSIONS);
    if (!has_ext(exts, "EGL_KHR_surfaceless_context")) {
        DIRT_DEBUG("EGL display lacks EGL_KHR_surfaceless_context");
        goto error;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        DIRT_DEBUG("eglBindAPI(OpenGL) failed: %s", egl_error_name(eglGetError()));
        goto error;
    }
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_ext(exts, "EGL_KHR_no_config_context")) {
        const EGLint cfg_attr[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                   EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(dpy, cfg_attr, &config, 1, &n) || n < 1) {
            DIRT_DEBUG("no EGL config with OpenGL + pbuffer");
            goto error;
        }
    }
    EGLint ctx_attr[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4,
        EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        EGL_CONTEXT_OPENGL_DEBUG, gpu->opts.no_debug ? EGL_FALSE : EGL_TRUE,
        EGL_NONE,
    };
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, ctx_attr);
    if (ctx == EGL_NO_CONTEXT) {
        DIRT_DEBUG("eglCreateContext(4.5 core) failed: %s", egl_error_name(eglGetError()));
        goto error;
    }
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        DIRT_DEBUG("eglMakeCurrent failed: %s", egl_error_name(eglGetError()));
        eglDestroyContext(dpy, ctx);
        goto error;
    }
    gpu->egl_display = dpy;
    gpu->egl_context = ctx;
    return true;
error:
    eglTerminate(dpy);
    return false;
}

const char *const dirt_gpu_platform_names[4] = {"auto", "device", "surfaceless", NULL};

/* The platform the options and DIRT_GPU ask for; false after logging when
 * DIRT_GPU names none. */
static bool chosen_platform(const dirt_gpu_opts *o, enum dirt_gpu_platform *out)
{
    *out = o->force_device_platform ? DIRT_GPU_PLATFORM_DEVICE : o->platform;
    const char *env = getenv("DIRT_GPU");
    if (*out != DIRT_GPU_PLATFORM_AUTO || !env || !*env)
        return true;
    for (int i = 0; i < 3; i++) {
        if (!strcmp(env, dirt_gpu_platform_names[i])) {
            *out = (enum dirt_gpu_platform)i;
            return true;
        }
    }
    DIRT_ERROR("DIRT_GPU=%s: expected auto, device or surfaceless", env);
    return false;
}

static bool egl_surfaceless(dirt_gpu *gpu, const char *client)
{
    if (!has_ext(client, "EGL_MESA_platform_surfaceless"))
        return false;
    EGLDisplay dpy = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY,
                                           NULL);
    if (dpy == EGL_NO_DISPLAY || !egl_make_context(gpu, dpy))
        return false;
    gpu->caps.platform = "egl-surfaceless";
    return true;
}

/* The first EGL device that makes a context: hardware devices only
 * (`software` false) or Mesa's software device only (true). */
static bool egl_device(dirt_gpu *gpu, const char *client, bool software)
{
    if (!has_ext(client, "EGL_EXT_platform_device"))
        return false;
    PFNEGLQUERYDEVICESEXTPROC query_devices =
        (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    PFNEGLQUERYDEVICESTRINGEXTPROC query_string =
        (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
    EGLDeviceEXT devices[16];
    EGLint n = 0;
    if (!query_devices || !query_devices(16, devices, &n))
        return false;
    for (EGLint i = 0; i < n; i++) {
        const char *exts = query_string ? query_string(devices[i], EGL_EXTENSIONS) : NULL;
        if (has_ext(exts, "EGL_MESA_device_software") != software)
            continue;
        EGLDisplay dpy = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
        if (dpy != EGL_NO_DISPLAY && egl_make_context(gpu, dpy)) {
            gpu->caps.platform = software ? "egl-device (software)" : "egl-device";
            return true;
        }
    }
    return false;
}

static bool egl_create(dirt_gpu *gpu)
{
    enum dirt_gpu_platform want;
    if (!chosen_platform(&gpu->opts, &want))
        return false;
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    bool ok;
    switch (want) {
    case DIRT_GPU_PLATFORM_SURFACELESS:
        ok = egl_surfaceless(gpu, client);
        break;
    case DIRT_GPU_PLATFORM_DEVICE:
        ok = egl_device(gpu, client, false) || egl_device(gpu, client, true);
        break;
    default:
        ok = egl_device(gpu, client, false) || egl_surfaceless(gpu, client) ||
             egl_device(gpu, client, true);
    }
    if (ok)
        return true;
    DIRT_ERROR("no headless OpenGL 4.5 core context on the %s EGL platform%s (is "
               "libegl-mesa0 or an NVIDIA driver installed?)", dirt_gpu_platform_names[want],
               want == DIRT_GPU_PLATFORM_AUTO ? "s (EGL devices, Mesa surfaceless)" : "");
    return false;
}

static void glfw_error(int code, const char *desc)
{
    DIRT_WARN("GLFW error 0x%x: %s", code, desc);
}

static bool glfw_create(dirt_gpu *gpu)
{
    glfwSetErrorCallback(glfw_error);
    if (!glfwInit()) {
        DIRT_ERROR("glfwInit failed: no window system (set DISPLAY, or use xvfb-run)");
        return false;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, gpu->opts.no_debug ? GLFW_FALSE : GLFW_TRUE);
    int w = gpu->opts.width > 0 ? gpu->opts.width : 1280;
    int h = gpu->opts.height > 0 ? gpu->opts.height : 720;
    GLFWwindow *win = glfwCreateWindow(w, h, gpu->opts.title ? gpu->opts.title : "DIRT",
                                       NULL, NULL);
    if (!win) {
        DIRT_ERROR("could not open a %dx%d window with an OpenGL 4.5 core context", w, h);
        glfwTerminate();
        return false;
    }
    glfwMakeContextCurrent(win);
    glfwSwapInterval(gpu->opts.vsync ? 1 : 0);
    gpu->window = win;
    gpu->caps.platform = "glfw";
    /* The input callbacks go first: a UI attached later chains to them. */
    return gl_window_init(gpu);
}

static bool contains_ci(const char *s, const char *needle)
{
    size_t n = strlen(needle);
    for (; *s; s++) {
        size_t i = 0;
        while (i < n && s[i] && (s[i] | 32) == (needle[i] | 32))
            i++;
        if (i == n)
            return true;
    }
    return false;
}

/* The test hook DIRT_MAX_BLOCK_BYTES (bytes, or with a K, M or G suffix of
 * 1024^1..3): the storage block size to use when it is below the driver's
 * `driver` (at least 4096 bytes: one record of every split array and one
 * path of the path tracer fit). 0 when unset, not smaller, or malformed
 * (warned). */
static int64_t block_override(int64_t driver)
{
    const char *e = getenv("DIRT_MAX_BLOCK_BYTES");
    if (!e || !*e)
        return 0;
    char *end = NULL;
    errno = 0;
    unsigned long long v = strtoull(e, &end, 10);
    unsigned long long unit = 1;
    if (end && (*end == 'K' || *end == 'k'))
        unit = 1ull << 10;
    else if (end && (*end == 'M' || *end == 'm'))
        unit = 1ull << 20;
    else if (end && (*end == 'G' || *end == 'g'))
        unit = 1ull << 30;
    if (unit > 1)
        end++;
    if (errno || end == e || *end || e[0] == '-' || v > (1ull << 40) / unit ||
        v * unit < 4096) {
        DIRT_WARN("DIRT_MAX_BLOCK_BYTES=%s is not a size of at least 4096 bytes "
                  "(such as 65536 or 64K); ignored", e);
        return 0;
    }
    v *= unit;
    return driver > 0 && (int64_t)v >= driver ? 0 : (int64_t)v;
}

void gl_gpu_set_block_bytes(dirt_gpu *gpu, int64_t bytes)
{
    dirt_gpu_caps *c = &gpu->caps;
    bool lower = bytes > 0 && (c->driver_ssbo_size <= 0 || bytes < c->driver_ssbo_size);
    c->block_override = lower ? bytes : 0;
    c->max_ssbo_size = lower ? bytes : c->driver_ssbo_size;
}

static void probe_caps(dirt_gpu *gpu)
{
    dirt_gpu_caps *c = &gpu->caps;
    glGetIntegerv(GL_MAJOR_VERSION, &c->gl_major);
    glGetIntegerv(GL_MINOR_VERSION, &c->gl_minor);
    snprintf(c->version, sizeof(c->version), "%s", (const char *)glGetString(GL_VERSION));
    snprintf(c->renderer, sizeof(c->renderer), "%s", (const char *)glGetString(GL_RENDERER));
    snprintf(c->vendor, sizeof(c->vendor), "%s", (const char *)glGetString(GL_VENDOR));
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; i++) {
        const char *e = (const char *)glGetStringi(GL_EXTENSIONS, (GLuint)i);
        if (e && strcmp(e, "GL_NV_conservative_raster") == 0)
            c->nv_conservative_raster = true;
    }
    if (gpu->opts.disable_conservative)
        c->nv_conservative_raster = false;
    c->software = contains_ci(c->renderer, "llvmpipe") || contains_ci(c->renderer, "softpipe");
    GLint bits = 0;
    glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
    c->timer_query = bits > 0;
    c->timer_bits = bits;
    bits = 0;
    glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &bits);
    c->timestamp_bits = bits;
    GLint64 v64 = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &v64);
    c->driver_ssbo_size = c->max_ssbo_size = v64;
    int64_t lowered = block_override(v64);
    if (lowered > 0) {
        c->block_override = lowered;
        c->max_ssbo_size = lowered;
        DIRT_INFO("DIRT_MAX_BLOCK_BYTES: storage blocks of %lld bytes (the driver's: %lld)",
                  (long long)lowered, (long long)v64);
    }
    v64 = 0;
    glGetInteger64v(GL_MAX_TEXTURE_BUFFER_SIZE, &v64);
    c->max_texel_buffer = v64;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &c->max_texture_size);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &c->max_array_layers);
    glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &c->max_compute_group_invocations);
    glGetIntegerv(GL_MAX_IMAGE_UNITS, &c->max_image_units);
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &c->max_texture_units);
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &c->max_ssbo_bindings);
}

/* The GPU current on this thread (gl_current). */
static _Thread_local dirt_gpu *current_gpu;

dirt_gpu *gl_current(void)
{
    return current_gpu;
}

/* True when environment variable `name` is set to something other than
 * "" or "0". */
static bool env_flag(const char *name)
{
    const char *v = getenv(name);
    return v && *v && strcmp(v, "0") != 0;
}

dirt_gpu *dirt_gpu_create(const dirt_gpu_opts *opts)
{
    dirt_gpu *gpu = calloc(1, sizeof(*gpu));
    if (!gpu) {
        DIRT_ERROR("out of memory");
        return NULL;
    }
    if (opts)
        gpu->opts = *opts;
    /* Mesa's zink (22.3) specializes shaders on the values of uniforms
     * that steer branches ("inlined uniforms") and, when the program
     * changes and the new one's values equal the previous program's,
     * keeps the new one's variant made for its old values: MMRT's trace
     * read a stale u_ray_batch in chunked renders (test gl_uniforms). Off
     * before the driver reads it, unless the environment says otherwise;
     * no other driver reads the variable. */
    setenv("ZINK_INLINE_UNIFORMS", "0", 0);
    if (!(gpu->opts.window ? glfw_create(gpu) : egl_create(gpu)))
        goto error;
    probe_caps(gpu);
    if (gpu->caps.gl_major * 10 + gpu->caps.gl_minor < 45) {
        DIRT_ERROR("OpenGL %d.%d context, need 4.5 core (%s)", gpu->caps.gl_major,
                   gpu->caps.gl_minor, gpu->caps.renderer);
        goto error;
    }
    const char *want = getenv("DIRT_EXPECT_RENDERER");
    if (want && *want && !contains_ci(gpu->caps.renderer, want)) {
        DIRT_ERROR("DIRT_EXPECT_RENDERER=%s, but the context's renderer is '%s' (did the "
                   "driver fall back?)", want, gpu->caps.renderer);
        goto error;
    }
    if (!gpu->opts.no_debug)
        gl_debug_install(gpu);
    gpu->poison = gpu->opts.poison || env_flag("DIRT_POISON");
    current_gpu = gpu;
    if (!gl_check_init(gpu))
        goto error;
    char desc[512];
    dirt_gpu_describe(gpu, desc, sizeof(desc));
    DIRT_DEBUG("%s", desc);
    return gpu;
error:
    dirt_gpu_destroy(gpu);
    return NULL;
}

void dirt_gpu_destroy(dirt_gpu *gpu)
{
    if (!gpu)
        return;
    /* GL objects go while the context is current. */
    if (gpu->ui) {
        DIRT_WARN("dirt_gpu_destroy: its dirt_ui is still attached; destroying it first");
        gl_ui_release(gpu);
    }
    gl_present_release(gpu);
    if (current_gpu == gpu)
        current_gpu = NULL;
    gl_check_release(gpu);
    if (gpu->egl_display) {
        eglMakeCurrent(gpu->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (gpu->egl_context)
            eglDestroyContext(gpu->egl_display, gpu->egl_context);
        eglTerminate(gpu->egl_display);
        eglReleaseThread();
    }
    gl_window_release(gpu);
    if (gpu->window) {
        glfwDestroyWindow(gpu->window);
        glfwTerminate();
    }
    free(gpu);
}

const dirt_gpu_caps *dirt_gpu_get_caps(const dirt_gpu *gpu)
{
    return &gpu->caps;
}

void dirt_gpu_describe(const dirt_gpu *gpu, char *buf, size_t size)
{
    const dirt_gpu_caps *c = &gpu->caps;
    snprintf(buf, size, "OpenGL %s | %s | %s | %s | conservative raster: %s | timer queries: %s",
             c->version, c->renderer, c->vendor, c->platform,
             c->nv_conservative_raster ? "GL_NV_conservative_raster" : "no (emulated)",
             c->timer_query ? (c->software ? "yes (software: raster not timed)" : "yes") : "no");
}

enum dirt_clock dirt_gpu_clock(const dirt_gpu *gpu)
{
    const dirt_gpu_caps *c = &gpu->caps;
    if (gpu->opts.cpu_timing || !c->timer_query || (c->software && !gpu->opts.gpu_timing))
        return DIRT_CLOCK_CPU;
    return DIRT_CLOCK_GPU;
}

void dirt_gpu_finish(dirt_gpu *gpu)
{
    (void)gpu;
    glFinish();
}

bool dirt_gpu_window_should_close(dirt_gpu *gpu)
{
    return gpu->window ? glfwWindowShouldClose(gpu->window) : false;
}

void dirt_gpu_window_swap(dirt_gpu *gpu)
{
    if (gpu->window)
        glfwSwapBuffers(gpu->window);
}

void dirt_gpu_window_poll(dirt_gpu *gpu)
{
    if (!gpu->window)
        return;
    gl_window_poll_begin(gpu);
    if (gpu->ui)
        gl_ui_make_current(gpu);
    glfwPollEvents();
    gl_window_poll_end(gpu);
}

void dirt_gpu_window_size(dirt_gpu *gpu, int *width, int *height)
{
    *width = *height = 0;
    if (gpu->window)
        glfwGetFramebufferSize(gpu->window, width, height);
}

bool dirt_gpu_poisons(const dirt_gpu *gpu)
{
    return gpu->poison;
}

uint64_t dirt_gpu_error_count(const dirt_gpu *gpu)
{
    return __atomic_load_n(&gpu->error_count, __ATOMIC_RELAXED);
}
