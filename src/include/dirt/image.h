/* DIRT engine: float images, EXR/PNG output and image metrics.
 *
 * A dirt_image holds linear float RGBA, interleaved, row 0 = top row, plus
 * any number of named extra planes ("albedo.R", "N.X", "Z", ...), each
 * width*height floats in the same row order. Fields are public for direct
 * pixel access; create/destroy/add_channel manage the memory.
 *
 * Every writer is atomic (see dirt/file.h): the file at `path` is replaced
 * only once the new one is complete; on failure nothing is left at `path`
 * (a file already there stays as it was) and no temporary file remains. */
#ifndef DIRT_IMAGE_H
#define DIRT_IMAGE_H

#include <stdbool.h>
#include <stdint.h>
#include <stddef.h>

#include "dirt/api.h"
#include "dirt/file.h"
#include "dirt/input.h"
#include "dirt/types.h" /* enum dirt_tonemap */

#ifdef __cplusplus
extern "C" {
#endif

/* Longest accepted extra-channel name, in bytes (the EXR limit). */
#define DIRT_IMAGE_MAX_CHANNEL_NAME 255
/* Largest accepted width or height (create and EXR read). */
#define DIRT_IMAGE_MAX_DIM 65536

typedef struct dirt_image_channel {
    char *name;  /* owned, NUL-terminated, unique within the image */
    float *data; /* owned, width*height floats, row 0 = top */
} dirt_image_channel;

typedef struct dirt_image {
    int width, height;
    float *rgba; /* owned, width*height*4 floats: R,G,B,A per pixel, linear */
    int channel_count;
    dirt_image_channel *channels; /* owned, in the order they were added */
} dirt_image;

/* Allocates a width x height image, RGBA all zero, no extra channels.
 * 1 <= width, height <= DIRT_IMAGE_MAX_DIM. NULL after logging on failure. */
DIRT_API dirt_image *dirt_image_create(int width, int height);

/* Frees the image and all its planes. Accepts NULL. */
DIRT_API void dirt_image_destroy(dirt_image *img);

/* Adds a zero-filled extra plane called `name` and returns it (owned by the
 * image, valid until destroy). Fails (NULL, logged) when the name is empty,
 * longer than DIRT_IMAGE_MAX_CHANNEL_NAME, already present, or one of the
 * RGBA names "R", "G", "B", "A", or when out of memory. Pointers returned
 * earlier for other channels stay valid. */
DIRT_API float *dirt_image_add_channel(dirt_image *img, const char *name);

/* The plane of the extra channel `name`, or NULL when there is none (not
 * logged: absence is a normal answer). RGBA is not found this way. */
DIRT_API float *dirt_image_find_channel(const dirt_image *img, const char *name);

/* ---- EXR ---------------------------------------------------------------- */

/* A text attribute of a file: its name and value (NUL-terminated,
 * borrowed). */
typedef struct dirt_image_attr {
    const char *name;
    const char *value;
} dirt_image_attr;

/* Zero-initialised = defaults: everything stored as 32-bit FLOAT, no
 * attributes beyond the required ones. */
typedef struct dirt_exr_options {
    bool half_rgba;  /* store R,G,B,A as 16-bit HALF (round to nearest even) */
    bool half_extra; /* store the extra channels as HALF */
    const dirt_image_attr *attrs; /* `num_attrs` string attributes for the header */
    size_t num_attrs;
} dirt_exr_options;

/* Writes a single-part scanline OpenEXR file, ZIP compression, channels
 * R,G,B,A plus every extra channel (sorted by name in the file as EXR
 * requires). Data window = display window = (0,0)-(w-1,h-1). Every
 * attribute of opts->attrs is a string attribute of the header (a name
 * the header already holds, such as "channels", is an error). `opts` may
 * be NULL for defaults. Atomic; false after logging on failure. */
DIRT_API bool dirt_image_write_exr(const dirt_image *img, const char *path,
                                   const dirt_exr_options *opts);

/* Default of dirt_image_read_opts.max_bytes: 2 GiB, what reading a
 * 16384 x 4096 RGB(A) image holds. */
#define DIRT_IMAGE_READ_DEFAULT_MAX_BYTES ((size_t)2 << 30)

/* Options of dirt_image_read. Zero-initialised = defaults. */
typedef struct dirt_image_read_opts {
    /* What the read may hold at once: the file's bytes where they are read
     * whole (.hdr), the decoder's buffers (a .hdr's float pixels, an EXR's
     * channels in their own type) and the image's planes, plus
     * extra_per_pixel bytes per pixel the caller will add while it holds
     * the image. Checked on the size the file declares, before any pixel is
     * decoded: more fails with TOO_LARGE. 0 = the default. */
    size_t max_bytes;
    size_t extra_per_pixel;
    /* A file without colour (no R, G, B and no Y channel) fails with
     * NO_COLOUR instead of reading as black. */
    bool need_colour;
} dirt_image_read_opts;

/* Reads an image file by its extension (any case): ".exr" as
 * dirt_image_read_exr, ".hdr" as dirt_image_read_hdr, with bounds: only a
 * regular file is read (a FIFO, device or directory fails at once with
 * NOT_REGULAR, without blocking), the memory its declared size needs is
 * checked against opts->max_bytes before anything is decoded (TOO_LARGE),
 * data that ends before what the header declares fails (TRUNCATED), as does
 * a malformed file (INVALID) or another extension (INVALID). NULL after
 * logging; the id in *err (may be NULL). `opts` may be NULL. */
DIRT_API dirt_image *dirt_image_read(const char *path, const dirt_image_read_opts *opts,
                                     enum dirt_input_error *err);

/* Reads part 0 of a scanline OpenEXR file (any compression; HALF, FLOAT or
 * UINT channels, all converted to float). Channels R, G, B, A go to rgba
 * (missing R/G/B read as 0, missing A as 1; a file with "Y" but no R, G or B
 * is read as grey); every other channel becomes an extra channel of the same
 * name. The image is the data window, its top row first. Subsampled
 * channels are skipped with a warning. NULL after logging on failure (file
 * missing or unreadable, tiled or deep file, too large). The bounds of
 * dirt_image_read with the default options. */
DIRT_API dirt_image *dirt_image_read_exr(const char *path);

/* Reads a Radiance RGBE (.hdr) file: linear RGB, alpha 1, the first row on
 * top. Its header is read here ("#?RADIANCE" or "#?RGBE", FORMAT=
 * 32-bit_rle_rgbe, "-Y H +X W") and its scanlines walked (flat or
 * run-length encoded) to check that the file holds every one before
 * stb_image decodes them: a file shorter than it declares fails
 * (TRUNCATED) instead of reading as black. NULL after logging on failure
 * (missing, unreadable or malformed file, too large). The bounds of
 * dirt_image_read with the default options. */
DIRT_API dirt_image *dirt_image_read_hdr(const char *path);

/* ---- PNG preview -------------------------------------------------------- */

/* enum dirt_tonemap (DIRT_TONEMAP_CLAMP: clamp to [0,1]; _REINHARD: x / (1 + x)
 * per channel; _ACES: Narkowicz's rational fit of the ACES curve) is in
 * dirt/types.h; the curves' constants are in glsl/common/display.h, shared
 * with the shaders. */

/* Zero-initialised = defaults: exposure 0, clamp, RGB without alpha. */
typedef struct dirt_png_options {
    float exposure;            /* stops: colour is multiplied by 2^exposure */
    enum dirt_tonemap tonemap; /* applied after exposure */
    bool alpha;                /* write RGBA (alpha clamped, not sRGB) */
} dirt_png_options;

/* Writes an 8-bit sRGB PNG preview: per RGB channel, scale by 2^exposure,
 * tonemap, clamp to [0,1] (NaN -> 0), apply the sRGB transfer function and
 * round to nearest 8-bit value. Extra channels are ignored. `opts` may be
 * NULL. Atomic; false after logging on failure. */
DIRT_API bool dirt_image_write_png(const dirt_image *img, const char *path,
                                   const dirt_png_options *opts);

/* Writes 8-bit RGBA pixels (row 0 = top, width * height * 4 bytes) as
 * they are (a window's screenshot). Atomic; false after logging. */
DIRT_API bool dirt_write_png_rgba8(const char *path, int width, int height, const uint8_t *rgba);

/* The 8-bit value the PNG writer stores for a linear value that has already
 * been exposed and tonemapped: round(255 * srgb(clamp(v, 0, 1))). */
DIRT_API unsigned char dirt_linear_to_srgb8(float v);

/* ---- by extension ------------------------------------------------------- */

typedef struct dirt_image_write_options {
    dirt_exr_options exr;
    dirt_png_options png;
} dirt_image_write_options;

/* Writes .exr or .png (extension matched case-insensitively) with the
 * matching options; `opts` may be NULL. Any other extension is an error
 * (false, logged, nothing written). */
DIRT_API bool dirt_image_write(const dirt_image *img, const char *path,
                               const dirt_image_write_options *opts);

/* ---- metrics (src/io/metrics.c) ----------------------------------------- */

/* Error of `img` against the reference `ref` over the R, G, B channels of
 * every pixel (alpha and extra channels ignored), accumulated in double:
 *   mse     = mean over pixels and RGB of (img - ref)^2
 *   rmse    = sqrt(mse)
 *   rel_mse = mean of (img - ref)^2 / (ref^2 + 1e-2)
 * Non-finite pixel values propagate into the results. */
typedef struct dirt_image_error {
    double mse, rmse, rel_mse;
} dirt_image_error;

#define DIRT_REL_MSE_EPSILON 1e-2

/* Fills `out` (all three metrics). False after logging when an argument is
 * NULL or the sizes differ. */
DIRT_API bool dirt_image_compare(const dirt_image *img, const dirt_image *ref,
                                 dirt_image_error *out);

/* Single metrics; NAN (after logging) when dirt_image_compare would fail. */
DIRT_API double dirt_image_mse(const dirt_image *img, const dirt_image *ref);
DIRT_API double dirt_image_rmse(const dirt_image *img, const dirt_image *ref);
DIRT_API double dirt_image_rel_mse(const dirt_image *img, const dirt_image *ref);

#ifdef __cplusplus
}
#endif
#endif
