/* OpenEXR read/write through the OpenEXRCore C API.
 * Contracts are documented in dirt/image.h.
 *
 * Writing encodes straight from the image (interleaved RGBA, planar extras)
 * through a custom write callback onto an atomic temp file. Reading decodes
 * every wanted channel in its own pixel type into a separate planar buffer
 * and converts to float here: OpenEXRCore 3.1.5 mis-orders channels when
 * asked to decode HALF straight into interleaved float RGBA. */
#include "dirt/image.h"

#include <errno.h>
#include <openexr.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

#include "dirt/log.h"
#include "io/atomic_file.h"
#include "io/read.h"

/* Routes OpenEXRCore's messages to the engine log. It may be called with
 * the context's lock held (an error inside exr_add_channel, say), so it
 * asks the context nothing (exr_get_file_name would wait for that lock
 * for ever); the caller's message that follows names the file. */
static void log_exr_error(exr_const_context_t ctxt, exr_result_t code,
                          const char *msg)
{
    (void)ctxt;
    DIRT_ERROR("OpenEXR: %s: %s", exr_get_error_code_as_string(code),
               msg ? msg : "");
}

/* pwrite-like callback onto the atomic file's stdio stream (user data).
 * The library writes from one thread here (no concurrent chunk writes). */
static int64_t write_to_stream(exr_const_context_t ctxt, void *user,
                               const void *buffer, uint64_t sz,
                               uint64_t offset,
                               exr_stream_error_func_ptr_t error_cb)
{
    FILE *fp = user;
    if (offset > (uint64_t)INT64_MAX ||
        fseeko(fp, (off_t)offset, SEEK_SET) != 0) {
        error_cb(ctxt, EXR_ERR_WRITE_IO, "seek to %llu failed: %s",
                 (unsigned long long)offset, strerror(errno));
        return -1;
    }
    if (sz && fwrite(buffer, 1, (size_t)sz, fp) != (size_t)sz) {
        error_cb(ctxt, EXR_ERR_WRITE_IO, "write of %llu bytes failed: %s",
                 (unsigned long long)sz, strerror(errno));
        return -1;
    }
    return (int64_t)sz;
}

/* Logs a failed OpenEXRCore call `what` for `path`; returns false. */
static bool exr_failed(const char *path, const char *what, exr_result_t rv)
{
    DIRT_ERROR("EXR '%s': %s failed: %s", path, what,
               exr_get_default_error_message(rv));
    return false;
}

#define EXR_TRY(call, what)                                                   \
    do {                                                                      \
        exr_result_t rv_ = (call);                                            \
        if (rv_ != EXR_ERR_SUCCESS) {                                         \
            exr_failed(path, (what), rv_);                                    \
            goto error;                                                       \
        }                                                                     \
    } while (0)

/* Where the float data of channel `name` lives in `img`: base pointer for
 * row 0 and the distance between pixels, in floats. False if none. */
static bool source_of(const dirt_image *img, const char *name,
                      const float **base, int *pixel_stride)
{
    static const char rgba_names[4] = {'R', 'G', 'B', 'A'};
    if (name[0] && !name[1]) {
        for (int c = 0; c < 4; c++) {
            if (name[0] == rgba_names[c]) {
                *base = img->rgba + c;
                *pixel_stride = 4;
                return true;
            }
        }
    }
    const float *plane = dirt_image_find_channel(img, name);
    if (!plane)
        return false;
    *base = plane;
    *pixel_stride = 1;
    return true;
}

bool dirt_image_write_exr(const dirt_image *img, const char *path,
                          const dirt_exr_options *opts)
{
    dirt_atomic_file *af = NULL;
    exr_context_t ctx = NULL;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool enc_ready = false;

    if (!img || !img->rgba || !path) {
        DIRT_ERROR("EXR write: NULL image or path");
        return false;
    }
    dirt_exr_options o = {0};
    if (opts)
        o = *opts;
    const int w = img->width, h = img->height;

    af = dirt_atomic_open(path);
    if (!af)
        return false;

    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = log_exr_error;
    init.user_data = dirt_atomic_stream(af);
    init.write_fn = write_to_stream;
    EXR_TRY(exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init),
            "exr_start_write");

    int part = 0;
    EXR_TRY(exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part),
            "exr_add_part");
    EXR_TRY(exr_initialize_required_attr_simple(ctx, part, w, h,
                                                EXR_COMPRESSION_ZIP),
            "exr_initialize_required_attr_simple");

    /* The library keeps the channel list sorted by name as EXR requires. */
    const exr_pixel_type_t rgba_type =
        o.half_rgba ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
    const exr_pixel_type_t extra_type =
        o.half_extra ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT;
    static const char *const rgba_names[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < 4; c++)
        EXR_TRY(exr_add_channel(ctx, part, rgba_names[c], rgba_type,
                                EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1),
                "exr_add_channel");
    for (int i = 0; i < img->channel_count; i++)
        EXR_TRY(exr_add_channel(ctx, part, img->channels[i].name, extra_type,
                                EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1),
                "exr_add_channel");
    /* After the required attributes: a name among them is refused. */
    for (size_t i = 0; i < o.num_attrs; i++) {
        const dirt_image_attr *a = &o.attrs[i];
        if (!a->name || !a->name[0] || !a->value) {
            DIRT_ERROR("EXR '%s': attribute %zu without a name or value", path, i);
            goto error;
        }
        EXR_TRY(exr_attr_set_string(ctx, part, a->name, a->value), "exr_attr_set_string");
    }
    EXR_TRY(exr_write_header(ctx), "exr_write_header");

    int32_t lines = 0;
    EXR_TRY(exr_get_scanlines_per_chunk(ctx, part, &lines),
            "exr_get_scanlines_per_chunk");
    if (lines < 1) {
        DIRT_ERROR("EXR '%s': invalid scanlines per chunk %d", path,
                   (int)lines);
        goto error;
    }
    for (int y = 0; y < h; y += lines) {
        exr_chunk_info_t ci;
        EXR_TRY(exr_write_scanline_chunk_info(ctx, part, y, &ci),
                "exr_write_scanline_chunk_info");
        if (!enc_ready) {
            EXR_TRY(exr_encoding_initialize(ctx, part, &ci, &enc),
                    "exr_encoding_initialize");
            enc_ready = true;
        } else {
            EXR_TRY(exr_encoding_update(ctx, part, &ci, &enc),
                    "exr_encoding_update");
        }
        for (int c = 0; c < enc.channel_count; c++) {
            exr_coding_channel_info_t *ch = &enc.channels[c];
            const float *base;
            int stride;
            if (!source_of(img, ch->channel_name, &base, &stride)) {
                DIRT_ERROR("EXR '%s': no data for channel '%s'", path,
                           ch->channel_name);
                goto error;
            }
            ch->user_bytes_per_element = (int16_t)sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_pixel_stride = stride * (int32_t)sizeof(float);
            ch->user_line_stride = ch->user_pixel_stride * w;
            ch->encode_from_ptr =
                (const uint8_t *)(base + (size_t)ci.start_y * (size_t)w *
                                             (size_t)stride);
        }
        if (y == 0)
            EXR_TRY(exr_encoding_choose_default_routines(ctx, part, &enc),
                    "exr_encoding_choose_default_routines");
        EXR_TRY(exr_encoding_run(ctx, part, &enc), "exr_encoding_run");
    }

    EXR_TRY(exr_encoding_destroy(ctx, &enc), "exr_encoding_destroy");
    enc_ready = false;
    /* exr_finish writes the chunk offset table: its result matters. */
    exr_result_t rv = exr_finish(&ctx);
    ctx = NULL;
    if (rv != EXR_ERR_SUCCESS) {
        exr_failed(path, "exr_finish", rv);
        goto error;
    }
    return dirt_atomic_commit(af);

error:
    if (enc_ready)
        exr_encoding_destroy(ctx, &enc);
    if (ctx)
        exr_finish(&ctx);
    dirt_atomic_abort(af);
    return false;
}

/* IEEE binary16 -> binary32, exact for every input (NaN payloads kept). */
static float half_to_float(uint16_t hv)
{
    const uint32_t sign = (uint32_t)(hv & 0x8000u) << 16;
    const uint32_t exp = (hv >> 10) & 0x1fu;
    const uint32_t man = hv & 0x3ffu;
    uint32_t bits;
    if (exp == 0) {
        /* zero or subnormal: man * 2^-24, exact in float */
        float f = (float)man * 0x1p-24f;
        return sign ? -f : f;
    }
    if (exp == 31)
        bits = sign | 0x7f800000u | (man << 13);
    else
        bits = sign | ((exp + 112u) << 23) | (man << 13);
    float f;
    memcpy(&f, &bits, sizeof(f));
    return f;
}

/* One channel of the file being read. */
typedef struct read_plan {
    const char *name;    /* owned by the context's channel list */
    exr_pixel_type_t type;
    int bytes;           /* bytes per element of `type` */
    uint8_t *raw;        /* planar native-type buffer, NULL = skipped */
    float *dst;          /* destination for pixel 0 */
    int dst_stride;      /* in floats */
} read_plan;

/* Converts a decoded planar buffer into its destination. */
static void convert_plane(const read_plan *p, size_t count)
{
    for (size_t i = 0; i < count; i++) {
        float v;
        if (p->type == EXR_PIXEL_HALF) {
            uint16_t hv;
            memcpy(&hv, p->raw + i * 2, 2);
            v = half_to_float(hv);
        } else if (p->type == EXR_PIXEL_UINT) {
            uint32_t u;
            memcpy(&u, p->raw + i * 4, 4);
            v = (float)u;
        } else {
            memcpy(&v, p->raw + i * 4, 4);
        }
        p->dst[i * (size_t)p->dst_stride] = v;
    }
}

/* Decodes every chunk of scanline part 0 into the plans' raw buffers. */
static bool decode_chunks(exr_context_t ctx, const char *path,
                          const exr_attr_box2i_t *dw, int w, int h,
                          read_plan *plans, int nplans)
{
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    bool dec_ready = false;
    int32_t nchunks = 0, lines = 0;

    EXR_TRY(exr_get_chunk_count(ctx, 0, &nchunks), "exr_get_chunk_count");
    EXR_TRY(exr_get_scanlines_per_chunk(ctx, 0, &lines),
            "exr_get_scanlines_per_chunk");
    if (lines < 1) {
        DIRT_ERROR("EXR '%s': invalid scanlines per chunk %d", path,
                   (int)lines);
        goto error;
    }
    for (int32_t k = 0; k < nchunks; k++) {
        exr_chunk_info_t ci;
        int y = dw->min.y + k * lines;
        EXR_TRY(exr_read_scanline_chunk_info(ctx, 0, y, &ci),
                "exr_read_scanline_chunk_info");
        int row = ci.start_y - dw->min.y;
        if (row < 0 || ci.height < 0 || row + ci.height > h) {
            DIRT_ERROR("EXR '%s': chunk %d rows %d..%d outside the data "
                       "window", path, (int)k, ci.start_y,
                       ci.start_y + ci.height - 1);
            goto error;
        }
        if (!dec_ready) {
            EXR_TRY(exr_decoding_initialize(ctx, 0, &ci, &dec),
                    "exr_decoding_initialize");
            dec_ready = true;
        } else {
            EXR_TRY(exr_decoding_update(ctx, 0, &ci, &dec),
                    "exr_decoding_update");
        }
        for (int c = 0; c < dec.channel_count; c++) {
            exr_coding_channel_info_t *ch = &dec.channels[c];
            const read_plan *p = NULL;
            for (int i = 0; i < nplans && !p; i++)
                if (strcmp(plans[i].name, ch->channel_name) == 0)
                    p = &plans[i];
            if (!p || !p->raw) {
                ch->decode_to_ptr = NULL; /* skipped by the decoder */
                continue;
            }
            if (ch->width != w || ch->height != ci.height) {
                DIRT_ERROR("EXR '%s': channel '%s' chunk is %dx%d, expected "
                           "%dx%d", path, p->name, ch->width, ch->height, w,
                           ci.height);
                goto error;
            }
            ch->user_bytes_per_element = (int16_t)p->bytes;
            ch->user_data_type = (uint16_t)p->type;
            ch->user_pixel_stride = p->bytes;
            ch->user_line_stride = p->bytes * w;
            ch->decode_to_ptr =
                p->raw + (size_t)row * (size_t)w * (size_t)p->bytes;
        }
        if (k == 0)
            EXR_TRY(exr_decoding_choose_default_routines(ctx, 0, &dec),
                    "exr_decoding_choose_default_routines");
        EXR_TRY(exr_decoding_run(ctx, 0, &dec), "exr_decoding_run");
    }
    EXR_TRY(exr_decoding_destroy(ctx, &dec), "exr_decoding_destroy");
    return true;

error:
    if (dec_ready)
        exr_decoding_destroy(ctx, &dec);
    return false;
}

/* The file being read: its descriptor (dirt_input_open) and size, and
 * whether a read ran past its end. */
typedef struct exr_source {
    int fd;
    int64_t size;
    bool chunks;        /* reading the pixel chunks (after the header) */
    bool short_read;    /* a read of a chunk ran past the file's end */
    exr_result_t last;  /* the last error OpenEXRCore reported */
} exr_source;

static int64_t read_source(exr_const_context_t ctxt, void *user, void *buffer, uint64_t sz,
                           uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
    exr_source *src = user;
    uint8_t *b = buffer;
    uint64_t got = 0;
    while (got < sz) {
        ssize_t r = pread(src->fd, b + got, (size_t)(sz - got), (off_t)(offset + got));
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0) {
            error_cb(ctxt, EXR_ERR_READ_IO, "read of %llu bytes at %llu failed: %s",
                     (unsigned long long)sz, (unsigned long long)offset, strerror(errno));
            return -1;
        }
        if (r == 0)
            break;
        got += (uint64_t)r;
    }
    if (got < sz && src->chunks)
        src->short_read = true;
    return (int64_t)got;
}

/* log_exr_error for a read: the code is also kept in its exr_source. */
static void log_exr_read_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *user = NULL;
    if (ctxt && exr_get_user_data(ctxt, &user) == EXR_ERR_SUCCESS && user)
        ((exr_source *)user)->last = code;
    log_exr_error(ctxt, code, msg);
}

static int64_t size_of_source(exr_const_context_t ctxt, void *user)
{
    (void)ctxt;
    return ((exr_source *)user)->size;
}

/* The planes of a w x h image with `extra` extra channels, the raw
 * buffers of the channels read (`raw_bytes` per pixel in all) and the
 * caller's extra_per_pixel: what the read holds at once. Saturates. */
static size_t read_need(size_t w, size_t h, size_t per_pixel)
{
    size_t px = w * h;
    return per_pixel && px > SIZE_MAX / per_pixel ? SIZE_MAX : px * per_pixel;
}

dirt_image *io_read_exr(const char *path, const dirt_image_read_opts *o, enum dirt_input_error *err)
{
    exr_context_t ctx = NULL;
    dirt_image *img = NULL;
    read_plan *plans = NULL;
    int nplans = 0;
    exr_source src = {.fd = -1};
    *err = DIRT_INPUT_ERR_INVALID;

    if (!path) {
        DIRT_ERROR("EXR read: NULL path");
        return NULL;
    }
    size_t file_size = 0;
    src.fd = dirt_input_open(path, 0, &file_size, err);
    if (src.fd < 0) {
        DIRT_ERROR("EXR '%s': %s%s%s", path, dirt_input_error_str(*err),
                   *err == DIRT_INPUT_ERR_IO ? ": " : "",
                   *err == DIRT_INPUT_ERR_IO ? strerror(errno) : "");
        return NULL;
    }
    *err = DIRT_INPUT_ERR_INVALID;
    src.size = (int64_t)file_size;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = log_exr_read_error;
    init.user_data = &src;
    init.read_fn = read_source;
    init.size_fn = size_of_source;
    EXR_TRY(exr_start_read(&ctx, path, &init), "opening for read");

    int parts = 0;
    EXR_TRY(exr_get_count(ctx, &parts), "exr_get_count");
    if (parts > 1)
        DIRT_WARN("EXR '%s': %d parts, reading only the first", path, parts);
    exr_storage_t storage;
    EXR_TRY(exr_get_storage(ctx, 0, &storage), "exr_get_storage");
    if (storage != EXR_STORAGE_SCANLINE) {
        DIRT_ERROR("EXR '%s': only scanline images are supported (storage "
                   "type %d: tiled or deep)", path, (int)storage);
        goto error;
    }
    exr_attr_box2i_t dw;
    EXR_TRY(exr_get_data_window(ctx, 0, &dw), "exr_get_data_window");
    int64_t w64 = (int64_t)dw.max.x - dw.min.x + 1;
    int64_t h64 = (int64_t)dw.max.y - dw.min.y + 1;
    if (w64 < 1 || h64 < 1 || w64 > DIRT_IMAGE_MAX_DIM ||
        h64 > DIRT_IMAGE_MAX_DIM) {
        DIRT_ERROR("EXR '%s': unsupported data window %lldx%lld", path,
                   (long long)w64, (long long)h64);
        if (w64 > DIRT_IMAGE_MAX_DIM || h64 > DIRT_IMAGE_MAX_DIM)
            *err = DIRT_INPUT_ERR_TOO_LARGE;
        goto error;
    }
    const int w = (int)w64, h = (int)h64;
    const size_t count = (size_t)w * (size_t)h;

    const exr_attr_chlist_t *chl = NULL;
    EXR_TRY(exr_get_channels(ctx, 0, &chl), "exr_get_channels");
    bool has_rgb = false, has_alpha = false, has_y = false;
    /* Per pixel: RGBA floats, a float per extra channel, each channel's
     * raw buffer. */
    size_t per_pixel = 16 + o->extra_per_pixel;
    for (int i = 0; i < chl->num_channels; i++) {
        const char *n = chl->entries[i].name.str;
        bool rgba = n[0] && !n[1] && strchr("RGBA", n[0]);
        if (!strcmp(n, "R") || !strcmp(n, "G") || !strcmp(n, "B"))
            has_rgb = true;
        if (!strcmp(n, "A"))
            has_alpha = true;
        if (!strcmp(n, "Y"))
            has_y = true;
        per_pixel += (rgba ? 0 : 4) + (chl->entries[i].pixel_type == EXR_PIXEL_HALF ? 2 : 4);
    }
    if (o->need_colour && !has_rgb && !has_y) {
        DIRT_ERROR("EXR '%s': no colour channel (R, G, B or Y) among its %d channels", path,
                   chl->num_channels);
        *err = DIRT_INPUT_ERR_NO_COLOUR;
        goto error;
    }
    size_t need = read_need((size_t)w, (size_t)h, per_pixel);
    if (need > o->max_bytes) {
        DIRT_ERROR("EXR '%s': %d x %d pixels of %d channels need %zu MiB to read, more than the "
                   "limit of %zu MiB", path, w, h, chl->num_channels, need >> 20,
                   o->max_bytes >> 20);
        *err = DIRT_INPUT_ERR_TOO_LARGE;
        goto error;
    }
    img = dirt_image_create(w, h);
    if (!img)
        goto error;
    plans = calloc(chl->num_channels ? (size_t)chl->num_channels : 1,
                   sizeof(*plans));
    if (!plans) {
        DIRT_ERROR("EXR '%s': out of memory", path);
        goto error;
    }

    bool grey = false; /* "Y" read into R, G and B */
    for (int i = 0; i < chl->num_channels; i++) {
        const exr_attr_chlist_entry_t *e = &chl->entries[i];
        read_plan *p = &plans[nplans++];
        p->name = e->name.str;
        p->type = e->pixel_type;
        p->bytes = e->pixel_type == EXR_PIXEL_HALF ? 2 : 4;
        if (e->x_sampling != 1 || e->y_sampling != 1) {
            DIRT_WARN("EXR '%s': skipping subsampled channel '%s'", path,
                      p->name);
            continue;
        }
        if (e->pixel_type != EXR_PIXEL_HALF &&
            e->pixel_type != EXR_PIXEL_FLOAT &&
            e->pixel_type != EXR_PIXEL_UINT) {
            DIRT_WARN("EXR '%s': skipping channel '%s' of unknown type %d",
                      path, p->name, (int)e->pixel_type);
            continue;
        }
        const char *rgba = "RGBA";
        const char *hit = p->name[0] && !p->name[1] ? strchr(rgba, p->name[0])
                                                    : NULL;
        if (hit) {
            p->dst = img->rgba + (hit - rgba);
            p->dst_stride = 4;
        } else if (!has_rgb && !strcmp(p->name, "Y")) {
            p->dst = img->rgba;
            p->dst_stride = 4;
            grey = true;
        } else {
            p->dst = dirt_image_add_channel(img, p->name);
            if (!p->dst)
                goto error;
            p->dst_stride = 1;
        }
        p->raw = malloc(count * (size_t)p->bytes);
        if (!p->raw) {
            DIRT_ERROR("EXR '%s': out of memory for channel '%s'", path,
                       p->name);
            goto error;
        }
    }

    bool any = false;
    for (int i = 0; i < nplans; i++)
        any = any || plans[i].raw;
    src.chunks = true;
    if (any && !decode_chunks(ctx, path, &dw, w, h, plans, nplans))
        goto error;

    for (int i = 0; i < nplans; i++)
        if (plans[i].raw)
            convert_plane(&plans[i], count);
    for (size_t i = 0; i < count; i++) {
        float *px = img->rgba + i * 4;
        if (grey)
            px[1] = px[2] = px[0];
        if (!has_alpha)
            px[3] = 1.0f;
    }

    for (int i = 0; i < nplans; i++)
        free(plans[i].raw);
    free(plans);
    exr_finish(&ctx);
    close(src.fd);
    *err = DIRT_INPUT_ERR_OK;
    return img;

error:
    /* A chunk past the file's end (a short read, or a chunk leader or
     * table that does not fit the file) is a truncated file. */
    if (*err == DIRT_INPUT_ERR_INVALID && src.chunks &&
        (src.short_read || src.last == EXR_ERR_BAD_CHUNK_LEADER ||
         src.last == EXR_ERR_READ_IO)) {
        *err = DIRT_INPUT_ERR_TRUNCATED;
        DIRT_ERROR("EXR '%s': the file ends before the data it declares (or a chunk is "
                   "corrupt)", path);
    }
    for (int i = 0; i < nplans; i++)
        free(plans[i].raw);
    free(plans);
    dirt_image_destroy(img);
    if (ctx)
        exr_finish(&ctx);
    if (src.fd >= 0)
        close(src.fd);
    return NULL;
}

dirt_image *dirt_image_read_exr(const char *path)
{
    dirt_image_read_opts o = io_read_defaults(NULL);
    enum dirt_input_error err;
    return io_read_exr(path, &o, &err);
}
