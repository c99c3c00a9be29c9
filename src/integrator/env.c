/* DIRT engine: the environment light of the light-transport model
 * (doc/light-transport.md, "Environment"). Every function that the path
 * tracers call per sample has a GLSL twin in glsl/integrator/model.glsl;
 * keep them formula for formula. */
#include "integrator/integrator.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec3.h"
#include "dirt/image.h"
#include "dirt/log.h"

#define PI_F 3.14159265358979323846f
#define PI_D 3.14159265358979323846

/* Largest side accepted (the GPU addresses texels with 32-bit indices). */
#define ENV_MAX_SIDE 16384

void dirt_env_destroy(dirt_env *env)
{
    if (!env)
        return;
    free(env->rgb);
    free(env->row_cos);
    free(env->cdf);
    free(env->col_cos);
    free(env->col_sin);
    free(env);
}

/* dirt_env_create of texels `stride` floats apart (3: packed RGB; 4: a
 * dirt_image's RGBA). */
static dirt_env *env_create(const float *rgb, size_t stride, int width, int height,
                            const dirt_env_opts *opts)
{
    dirt_env_opts o = opts ? *opts : (dirt_env_opts){0};
    float intensity = o.intensity != 0.0f ? o.intensity : 1.0f;
    if (!rgb || width < 1 || height < 1 || width > ENV_MAX_SIDE || height > ENV_MAX_SIDE) {
        DIRT_ERROR("environment: size %dx%d out of [1, %d]", width, height, ENV_MAX_SIDE);
        return NULL;
    }
    if (!(intensity > 0.0f) || !isfinite(intensity) || !isfinite(o.rotation)) {
        DIRT_ERROR("environment: intensity must be finite and > 0, rotation finite");
        return NULL;
    }
    size_t n = (size_t)width * (size_t)height;
    for (size_t k = 0; k < n; k++) {
        for (size_t c = 0; c < 3; c++) {
            float x = rgb[k * stride + c];
            if (!(x >= 0.0f) || !isfinite(x)) {
                DIRT_ERROR("environment: texel %zu (row %zu) is negative or not finite (%g)", k,
                           k / (size_t)width, (double)x);
                return NULL;
            }
        }
    }
    dirt_env *env = calloc(1, sizeof(*env));
    if (!env)
        goto oom;
    env->width = width;
    env->height = height;
    env->rgb = malloc(3 * n * sizeof(float));
    env->row_cos = malloc(((size_t)height + 1) * sizeof(float));
    env->cdf = malloc(n * sizeof(float));
    env->col_cos = malloc(((size_t)width + 1) * sizeof(float));
    env->col_sin = malloc(((size_t)width + 1) * sizeof(float));
    if (!env->rgb || !env->row_cos || !env->cdf || !env->col_cos || !env->col_sin)
        goto oom;
    for (int i = 0; i <= width; i++) {
        double phi = 2.0 * PI_D * (double)i / (double)width - PI_D;
        env->col_cos[i] = (float)cos(phi);
        env->col_sin[i] = (float)sin(phi);
    }
    for (size_t k = 0; k < n; k++) {
        for (size_t c = 0; c < 3; c++)
            env->rgb[3 * k + c] = rgb[k * stride + c] * intensity;
    }
    for (int j = 0; j <= height; j++)
        env->row_cos[j] = (float)cos(PI_D * (double)j / (double)height);
    env->row_cos[0] = 1.0f;
    env->row_cos[height] = -1.0f;
    double sum = 0.0;
    for (int j = 0; j < height; j++) {
        double band = (double)env->row_cos[j] - (double)env->row_cos[j + 1];
        for (int i = 0; i < width; i++) {
            size_t k = (size_t)j * (size_t)width + (size_t)i;
            dirt_vec3 c = v3_load(&env->rgb[3 * k]);
            sum += (double)v3_luminance(c) * band;
            env->cdf[k] = (float)sum;
        }
    }
    env->total = env->cdf[n - 1];
    double rot = (double)o.rotation * PI_D / 180.0;
    env->rot_cos = (float)cos(rot);
    env->rot_sin = (float)sin(rot);
    return env;
oom:
    DIRT_ERROR("environment: out of memory for %dx%d texels", width, height);
    dirt_env_destroy(env);
    return NULL;
}

dirt_env *dirt_env_create(const float *rgb, int width, int height, const dirt_env_opts *opts)
{
    return env_create(rgb, 3, width, height, opts);
}

dirt_env *dirt_env_constant(const float rgb[3])
{
    return dirt_env_create(rgb, 1, 1, NULL);
}

/* The sky's radiance along map-frame direction e (unit). */
static void sky_radiance(dirt_vec3 e, dirt_vec3 sun, float out[3])
{
    dirt_vec3 c;
    if (e.y >= 0.0f) {
        float t = sqrtf(e.y);
        dirt_vec3 horizon = v3(0.85f, 0.88f, 0.92f), zenith = v3(0.20f, 0.40f, 0.85f);
        c = v3_add(v3_scale(horizon, 1.0f - t), v3_scale(zenith, t));
    } else {
        c = v3(0.16f, 0.15f, 0.13f);
    }
    if (v3_dot(e, sun) >= cosf(2.0f * PI_F / 180.0f))
        c = v3(400.0f, 390.0f, 360.0f);
    out[0] = c.x;
    out[1] = c.y;
    out[2] = c.z;
}

dirt_env *dirt_env_sky(const dirt_env_opts *opts)
{
    enum { W = 512, H = 256 };
    float *rgb = malloc((size_t)W * H * 3 * sizeof(float));
    if (!rgb) {
        DIRT_ERROR("environment: out of memory for the sky");
        return NULL;
    }
    float elev = 40.0f * PI_F / 180.0f, az = 0.6f;
    dirt_vec3 sun = v3(cosf(elev) * sinf(az), sinf(elev), -cosf(elev) * cosf(az));
    for (int j = 0; j < H; j++) {
        float theta = PI_F * ((float)j + 0.5f) / (float)H;
        for (int i = 0; i < W; i++) {
            float phi = 2.0f * PI_F * ((float)i + 0.5f) / (float)W - PI_F;
            dirt_vec3 e = v3(sinf(theta) * sinf(phi), cosf(theta), -sinf(theta) * cosf(phi));
            sky_radiance(e, sun, &rgb[3 * ((size_t)j * W + (size_t)i)]);
        }
    }
    dirt_env *env = dirt_env_create(rgb, W, H, opts);
    free(rgb);
    return env;
}

static bool ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    if (n < m)
        return false;
    for (size_t i = 0; i < m; i++) {
        char c = s[n - m + i];
        if (c >= 'A' && c <= 'Z')
            c = (char)(c - 'A' + 'a');
        if (c != suffix[i])
            return false;
    }
    return true;
}

dirt_env *dirt_env_load(const char *path, const dirt_env_opts *opts, char *why, size_t size)
{
    char dummy[8];
    if (!why) {
        why = dummy;
        size = sizeof(dummy);
    }
    why[0] = '\0';
    if (!path || !*path) {
        snprintf(why, size, "no environment file given");
        return NULL;
    }
    if (!strcmp(path, "sky")) {
        dirt_env *env = dirt_env_sky(opts);
        if (!env)
            snprintf(why, size, "cannot make the built-in sky");
        return env;
    }
    if (!ends_with(path, ".exr") && !ends_with(path, ".hdr")) {
        snprintf(why, size, "INVALID: '%s': an environment map must be .exr or .hdr (or 'sky')",
                 path);
        return NULL;
    }
    /* The image read and the map's tables (rgb and cdf, 16 bytes a texel)
     * within the budget. */
    dirt_image_read_opts ro = {.max_bytes = opts && opts->max_bytes ? opts->max_bytes
                                                                     : DIRT_ENV_DEFAULT_MAX_BYTES,
                               .extra_per_pixel = 16,
                               .need_colour = true};
    enum dirt_input_error err = DIRT_INPUT_ERR_OK;
    dirt_image *img = dirt_image_read(path, &ro, &err);
    if (!img) {
        snprintf(why, size, "%s: cannot read the environment map '%s': %s (see above)",
                 dirt_input_error_name(err), path, dirt_input_error_str(err));
        return NULL;
    }
    dirt_env *env = env_create(img->rgba, 4, img->width, img->height, opts);
    if (!env)
        snprintf(why, size, "INVALID: '%s': not a usable environment map (%dx%d; texels must be "
                 "finite and >= 0)", path, img->width, img->height);
    dirt_image_destroy(img);
    return env;
}

bool dirt_env_samples(const dirt_env *env)
{
    return env && env->total > 0.0f;
}

/* d rotated into the map's frame: R_y(-rotation) d. */
static dirt_vec3 to_map(const dirt_env *env, dirt_vec3 d)
{
    return v3(env->rot_cos * d.x - env->rot_sin * d.z, d.y, env->rot_sin * d.x + env->rot_cos * d.z);
}

/* sin(phi - phi_k) of the map-frame direction e: >= 0 when phi lies in
 * [phi_k, phi_k + pi). */
static float side(const dirt_env *env, dirt_vec3 e, int k)
{
    return e.x * env->col_cos[k] + e.z * env->col_sin[k];
}

void dirt_env_texel(const dirt_env *env, dirt_vec3 d, int *col, int *row)
{
    dirt_vec3 e = to_map(env, d);
    int w = env->width;
    float x = (atan2f(e.x, -e.z) + PI_F) * (1.0f / (2.0f * PI_F)) * (float)w;
    int i = (int)floorf(x);
    if (!(x >= 0.0f) || (e.x == 0.0f && e.z == 0.0f))
        i = 0; /* also NaN, and the poles (atan2(0, 0) is undefined in GLSL) */
    if (i > w - 1)
        i = w - 1;
    if (w >= 4 && !(e.x == 0.0f && e.z == 0.0f)) {
        /* The guess is at most a column off: move it until its edges hold phi. */
        for (int step = 0; step < 2; step++) {
            if (side(env, e, i) < 0.0f)
                i = i > 0 ? i - 1 : w - 1;
            else if (side(env, e, i + 1) >= 0.0f)
                i = i < w - 1 ? i + 1 : 0;
            else
                break;
        }
    }
    /* The first row j whose lower edge row_cos[j + 1] <= e.y. */
    int lo = 0, hi = env->height - 1;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (env->row_cos[mid + 1] <= e.y)
            hi = mid;
        else
            lo = mid + 1;
    }
    *col = i;
    *row = lo;
}

dirt_vec3 dirt_env_eval(const dirt_env *env, dirt_vec3 d)
{
    if (!env)
        return v3(0.0f, 0.0f, 0.0f);
    int i, j;
    dirt_env_texel(env, d, &i, &j);
    return v3_load(&env->rgb[3 * ((size_t)j * (size_t)env->width + (size_t)i)]);
}

/* Solid-angle pdf of texel k = j w + i. */
static float texel_pdf(const dirt_env *env, int i, int j)
{
    size_t k = (size_t)j * (size_t)env->width + (size_t)i;
    float w = env->cdf[k] - (k > 0 ? env->cdf[k - 1] : 0.0f);
    float band = env->row_cos[j] - env->row_cos[j + 1];
    float omega = (2.0f * PI_F / (float)env->width) * band;
    return omega > 0.0f ? w / (env->total * omega) : 0.0f;
}

float dirt_env_pdf(const dirt_env *env, dirt_vec3 d)
{
    if (!dirt_env_samples(env))
        return 0.0f;
    int i, j;
    dirt_env_texel(env, d, &i, &j);
    return texel_pdf(env, i, j);
}

bool dirt_env_sample(const dirt_env *env, float u_sel, float u1, float u2, dirt_vec3 *d,
                     float *pdf, dirt_vec3 *radiance)
{
    if (!dirt_env_samples(env))
        return false;
    size_t lo = dirt_cdf_find(env->cdf, (size_t)env->width * (size_t)env->height,
                              u_sel * env->total);
    int i = (int)(lo % (size_t)env->width), j = (int)(lo / (size_t)env->width);
    float p = texel_pdf(env, i, j);
    if (!(p > 0.0f))
        return false;
    float phi = 2.0f * PI_F * ((float)i + u1) / (float)env->width - PI_F;
    float z = env->row_cos[j] - u2 * (env->row_cos[j] - env->row_cos[j + 1]);
    float s = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    dirt_vec3 e = v3(s * sinf(phi), z, -s * cosf(phi));
    /* Back to the world: R_y(rotation) e. */
    *d = v3(env->rot_cos * e.x + env->rot_sin * e.z, e.y, -env->rot_sin * e.x + env->rot_cos * e.z);
    *pdf = p;
    *radiance = v3_load(&env->rgb[3 * lo]);
    return true;
}
