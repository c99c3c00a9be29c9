/* dirt_image: allocation, extra channels and format dispatch.
 * Contracts are documented in dirt/image.h. */
#include "dirt/image.h"
#include "io/read.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "dirt/log.h"

dirt_image *dirt_image_create(int width, int height)
{
    if (width < 1 || height < 1 || width > DIRT_IMAGE_MAX_DIM ||
        height > DIRT_IMAGE_MAX_DIM) {
        DIRT_ERROR("invalid image size %dx%d (each side 1..%d)", width, height,
                   DIRT_IMAGE_MAX_DIM);
        return NULL;
    }
    size_t count = (size_t)width * (size_t)height * 4;
    if (count > SIZE_MAX / sizeof(float)) {
        DIRT_ERROR("image %dx%d too large for this address space", width,
                   height);
        return NULL;
    }
    dirt_image *img = calloc(1, sizeof(*img));
    if (!img)
        goto oom;
    img->width = width;
    img->height = height;
    img->rgba = calloc(count, sizeof(float));
    if (!img->rgba)
        goto oom;
    return img;

oom:
    DIRT_ERROR("out of memory allocating a %dx%d image", width, height);
    free(img);
    return NULL;
}

void dirt_image_destroy(dirt_image *img)
{
    if (!img)
        return;
    for (int i = 0; i < img->channel_count; i++) {
        free(img->channels[i].name);
        free(img->channels[i].data);
    }
    free(img->channels);
    free(img->rgba);
    free(img);
}

float *dirt_image_find_channel(const dirt_image *img, const char *name)
{
    if (!img || !name)
        return NULL;
    for (int i = 0; i < img->channel_count; i++)
        if (strcmp(img->channels[i].name, name) == 0)
            return img->channels[i].data;
    return NULL;
}

float *dirt_image_add_channel(dirt_image *img, const char *name)
{
    char *copy = NULL;
    float *data = NULL;

    if (!img || !name || !*name) {
        DIRT_ERROR("add_channel: NULL image or empty channel name");
        return NULL;
    }
    size_t len = strlen(name);
    if (len > DIRT_IMAGE_MAX_CHANNEL_NAME) {
        DIRT_ERROR("add_channel: channel name of %zu bytes exceeds %d", len,
                   DIRT_IMAGE_MAX_CHANNEL_NAME);
        return NULL;
    }
    if (len == 1 && strchr("RGBA", name[0])) {
        DIRT_ERROR("add_channel: '%s' is stored in rgba, not an extra channel",
                   name);
        return NULL;
    }
    if (dirt_image_find_channel(img, name)) {
        DIRT_ERROR("add_channel: channel '%s' already exists", name);
        return NULL;
    }
    copy = malloc(len + 1);
    data = calloc((size_t)img->width * (size_t)img->height, sizeof(float));
    dirt_image_channel *grown =
        realloc(img->channels,
                ((size_t)img->channel_count + 1) * sizeof(*img->channels));
    if (grown)
        img->channels = grown; /* old block freed by realloc; keep the new */
    if (!copy || !data || !grown) {
        DIRT_ERROR("add_channel: out of memory for channel '%s'", name);
        goto error;
    }
    memcpy(copy, name, len + 1);
    img->channels[img->channel_count].name = copy;
    img->channels[img->channel_count].data = data;
    img->channel_count++;
    return data;

error:
    free(data);
    free(copy);
    return NULL;
}

/* True when the file name of `path` ends in `ext` (which includes the dot)
 * after at least one other character, ignoring case: "a.exr" matches,
 * ".exr" does not. */
static bool has_extension(const char *path, const char *ext)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    size_t n = strlen(base), e = strlen(ext);
    return n > e && strcasecmp(base + n - e, ext) == 0;
}

dirt_image_read_opts io_read_defaults(const dirt_image_read_opts *opts)
{
    dirt_image_read_opts o = opts ? *opts : (dirt_image_read_opts){0};
    if (o.max_bytes == 0)
        o.max_bytes = DIRT_IMAGE_READ_DEFAULT_MAX_BYTES;
    return o;
}

dirt_image *dirt_image_read(const char *path, const dirt_image_read_opts *opts,
                            enum dirt_input_error *err)
{
    enum dirt_input_error dummy;
    if (!err)
        err = &dummy;
    dirt_image_read_opts o = io_read_defaults(opts);
    if (path && has_extension(path, ".exr"))
        return io_read_exr(path, &o, err);
    if (path && has_extension(path, ".hdr"))
        return io_read_hdr(path, &o, err);
    *err = DIRT_INPUT_ERR_INVALID;
    DIRT_ERROR("cannot read '%s': an image to read must be .exr or .hdr", path ? path : "(null)");
    return NULL;
}

bool dirt_image_write(const dirt_image *img, const char *path,
                      const dirt_image_write_options *opts)
{
    if (!path) {
        DIRT_ERROR("image write: NULL path");
        return false;
    }
    if (has_extension(path, ".exr"))
        return dirt_image_write_exr(img, path, opts ? &opts->exr : NULL);
    if (has_extension(path, ".png"))
        return dirt_image_write_png(img, path, opts ? &opts->png : NULL);
    DIRT_ERROR("cannot write '%s': unsupported image format (use .exr or "
               ".png)", path);
    return false;
}
