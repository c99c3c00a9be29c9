/* DIRT engine: environment lights for the session (dirt_session_opts.env).
 *
 * An environment is an equirectangular map of the radiance arriving from
 * every direction, importance-sampled by the path tracers
 * (doc/light-transport.md, "Environment"); a constant background is its
 * 1 x 1 case. The caller owns a map: it must outlive every session that
 * uses it. */
#ifndef DIRT_ENV_H
#define DIRT_ENV_H

#include <stddef.h>

#include "dirt/api.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dirt_env dirt_env;

/* Default of dirt_env_opts.max_bytes: 2 GiB, what loading an 8192 x 4096
 * map holds with room to spare (32 bytes per texel: the image read and
 * the map's tables). */
#define DIRT_ENV_DEFAULT_MAX_BYTES ((size_t)2 << 30)

/* Zero-initialised = intensity 1, no rotation, the default budget. */
typedef struct dirt_env_opts {
    float intensity;  /* radiance scale; 0 = 1 */
    float rotation;   /* degrees about +Y (the map turns counter-clockwise
                         seen from above) */
    size_t max_bytes; /* dirt_env_load: what loading a map file may hold (its
                         decoded image and the map's tables, dirt_image_read's
                         bound); 0 = DIRT_ENV_DEFAULT_MAX_BYTES */
} dirt_env_opts;

/* A map of width x height texels from `rgb` (row-major, 3 floats per texel,
 * copied; each finite and >= 0, else an error). NULL after logging on bad
 * input or out-of-memory. */
DIRT_API dirt_env *dirt_env_create(const float *rgb, int width, int height, const dirt_env_opts *opts);
/* The constant environment `rgb` (1 x 1). */
DIRT_API dirt_env *dirt_env_constant(const float rgb[3]);
/* Reads an equirectangular map from an OpenEXR (.exr) or Radiance (.hdr)
 * file through dirt_image_read (a regular file only; its declared size
 * checked against opts->max_bytes before decoding; a file shorter than it
 * declares, or an EXR without colour channels, refused); "sky" is the
 * built-in procedural sky (dirt_env_sky). NULL after logging (missing,
 * unreadable or malformed file, negative or non-finite texels); `why` (may
 * be NULL) receives the reason in one line that starts with its id of
 * dirt/input.h ("NOT_REGULAR: ...", "TRUNCATED: ...", "INVALID: ..."). */
DIRT_API dirt_env *dirt_env_load(const char *path, const dirt_env_opts *opts, char *why, size_t size);
/* The built-in sky (512 x 256 texels, each the value at its centre): a
 * horizon-to-zenith blue gradient over a dim ground and a sun of radiance
 * 400 and 2 degrees radius, 40 degrees high (doc/light-transport.md). */
DIRT_API dirt_env *dirt_env_sky(const dirt_env_opts *opts);
/* Accepts NULL. */
DIRT_API void dirt_env_destroy(dirt_env *env);

#ifdef __cplusplus
}
#endif
#endif
