/* Split arrays: arrays of records that may pass one shader storage block
 * (doc/architecture.md, "Arrays past one storage block").
 *
 * While an array fits dirt_gpu_caps.max_ssbo_size it is one buffer, bound
 * and read as one storage block exactly as before (layout.parts = 0: the
 * shaders are built as they always were). Past it, the array is cut into
 * parts of 2^shift records (gl_split_layout), each its own buffer at most
 * the texel-buffer limit (GL_MAX_TEXTURE_BUFFER_SIZE texels) and
 * DIRT_MAX_BLOCK_BYTES, read through a texel buffer per part: samplers for
 * arrays the CPU writes (texelFetch), images for arrays shaders write
 * (imageLoad, imageStore, imageAtomic*). The shaders that read an array are
 * built for its layout (gl_split_defines, gl_split_program_ensure;
 * glsl/common/constants.h, DIRT_SPLIT_EACH, and the arrays' includes:
 * common/vertices.glsl, common/depth.glsl, dirt/structure.glsl,
 * mmrt/arrays.glsl). */
#ifndef DIRT_GL_SPLIT_H
#define DIRT_GL_SPLIT_H

#include "common/constants.h"
#include "gl/gl.h"
#include "gl/glsl_source.h"
#include "graph/graph.h"

/* How an array that may pass one storage block is stored (arrays of
 * records: vertices, list nodes, ...; doc/architecture.md, "Arrays past one
 * storage block"). parts = 0: one buffer read as one shader storage block
 * (the array fits dirt_gpu_caps.max_ssbo_size). parts >= 1: `parts`
 * buffers of 2^shift records each (the last may hold fewer; at most
 * DIRT_SPLIT_MAX_PARTS of glsl/common/constants.h), read through texel
 * buffers (samplers for arrays the CPU writes, images for arrays
 * shaders write). Every shader that reads the array is built for it. */
typedef struct gl_split_layout {
    int parts;
    int shift;
} gl_split_layout;

/* What an array is. Static storage (the arrays keep a pointer). */
typedef struct gl_split_desc {
    const char *label;       /* the name in messages and buffer labels, plural
                                ("DIRT id nodes": "the DIRT id nodes need ...") */
    const char *advice;      /* what to change when it does not fit ("use larger
                                tiles (-S) or ..."), said by gl_split_plan */
    const char *define;      /* the shaders' name: DEFINE (parts), DEFINE_SHIFT */
    size_t record_bytes;     /* a whole number of texels */
    GLenum format;           /* the parts' texel format: GL_RGBA32F, GL_RGBA32UI,
                                GL_RG32UI or GL_R32UI */
    bool image;              /* parts bound to image units (shaders write them),
                                else to texture units */
    unsigned binding;        /* the storage block's DIRT_BIND_* while it fits one */
    unsigned unit;           /* first texture/image unit of the parts
                                (DIRT_UNIT_SPLIT_*, DIRT_IMAGE_SPLIT_*) */
    bool readback;           /* the CPU reads it back (GL_MAP_READ_BIT) */
} gl_split_desc;

/* An array: owned by one object, zero-initialised = empty (nothing
 * allocated; gl_split_bind binds nothing). */
typedef struct gl_split {
    const gl_split_desc *desc;
    gl_split_layout layout;
    size_t capacity;                    /* records */
    GLuint buf[DIRT_SPLIT_MAX_PARTS];   /* [0]: the one block; else part k */
    GLuint tex[DIRT_SPLIT_MAX_PARTS];   /* texel-buffer views of the parts */
    size_t part_bytes[DIRT_SPLIT_MAX_PARTS];
} gl_split;

/* The scene's arrays every technique and Shade read (common/vertices.glsl):
 * the vertices (dirt_gpu_vertex[3] per primitive) and the material of each
 * primitive. */
extern const gl_split_desc gl_split_vertices, gl_split_prim_material;
/* The depth bounds and their Hi-Z pyramid (common/depth.glsl) of DIRT's
 * tiles and MMRT's pixels. */
extern const gl_split_desc gl_split_depth;

/* Bytes of one texel of `format` (0 for others). */
size_t gl_split_texel_bytes(GLenum format);

/* The layout of `records` records of `d` on this GPU: one block when they
 * fit caps.max_ssbo_size, else the fewest parts of 2^shift records each
 * within the texel-buffer limit and DIRT_MAX_BLOCK_BYTES. False (logged
 * once: the array, its size and desc->advice) when that takes more than
 * DIRT_SPLIT_MAX_PARTS parts or more texture/image units than the GPU
 * has. Pure arithmetic on the caps: the same inputs give the same layout
 * everywhere (a technique and the integrator agree without talking). */
bool gl_split_plan(const dirt_gpu *gpu, const gl_split_desc *d, size_t records,
                   gl_split_layout *out);

/* Makes `s` (of array `d`) hold at least `records` records: kept when its
 * capacity suffices, else remade (content lost) for exactly max(records, 1)
 * records and their layout. False after logging (plan or allocation); `s`
 * is then empty. */
bool gl_split_ensure(dirt_gpu *gpu, gl_split *s, const gl_split_desc *d, size_t records);
void gl_split_release(gl_split *s);

/* Bytes allocated (all parts). */
size_t gl_split_bytes(const gl_split *s);
/* Records per part (the capacity when it is one block). */
size_t gl_split_part_records(const gl_split *s);

/* Writes / reads `count` records from record `first` (within the
 * capacity), part by part. */
bool gl_split_write(gl_split *s, size_t first, size_t count, const void *records);
bool gl_split_read(const gl_split *s, size_t first, size_t count, void *out);
/* Fills every part with one value (glClearNamedBufferData's arguments). */
void gl_split_clear(gl_split *s, GLenum internal, GLenum format, GLenum type, const void *value);

/* Binds the array for the shaders: the block at desc->binding, or part k's
 * texel buffer at desc->unit + k (texture unit, or image unit with
 * GL_READ_WRITE) and no buffer at desc->binding. */
void gl_split_bind(const gl_split *s);

/* The shaders' defines of a layout: DEFINE = parts and DEFINE_SHIFT =
 * shift, written into `out` (2 entries) with their values in `text`. */
typedef struct gl_split_defs {
    glsl_define def[2];
    char name[2][64];
    char value[2][16];
} gl_split_defs;
void gl_split_defines(const gl_split_desc *d, gl_split_layout layout, gl_split_defs *out);
/* The same as one key (programs are rebuilt when it changes). */
uint32_t gl_split_key(gl_split_layout layout);

/* A program built for the layouts of the split arrays its shaders read:
 * remade when one changes. Zero-initialised = not made. */
#define GL_SPLIT_PROGRAM_MAX_ARRAYS 12
typedef struct gl_split_program {
    GLuint id;
    gl_split_layout built[GL_SPLIT_PROGRAM_MAX_ARRAYS];
    size_t num_built;
} gl_split_program;

/* Makes p's program the one for arrays descs[i] in layouts[i] (i < n, n
 * at most GL_SPLIT_PROGRAM_MAX_ARRAYS): kept when it was built for them,
 * else compiled and linked from `paths` (gl_program_create) with `defines`
 * and the arrays' defines. False after logging; p is then not made. */
bool gl_split_program_ensure(gl_split_program *p, const char *label, const char *const *paths,
                      const glsl_define *defines, size_t num_defines,
                      const gl_split_desc *const *descs, const gl_split_layout *layouts,
                      size_t n);
/* gl_split_program_ensure for the arrays arr[i] (described by descs[i],
 * i < n) whose bit 1 << i is set in `mask`, in that order, then `extra`
 * when not NULL: how a module builds a program for the arrays it reads. */
bool gl_split_program_select(gl_split_program *p, const char *label, const char *const *paths,
                             const glsl_define *defines, size_t num_defines,
                             const gl_split_desc *const *descs, gl_split *const *arr, size_t n,
                             unsigned mask, const gl_split *extra);
void gl_split_program_destroy(gl_split_program *p);

/* Frame-graph resources of the parts (one imported buffer each, named after
 * `name` and the part). `r` has DIRT_SPLIT_MAX_PARTS entries; unused ones
 * are {0}. The parts count must stay the same for the graph's life
 * (gl_split_key); gl_split_set_imports points them at regrown buffers. */
void gl_split_import(fg_graph *g, const char *name, const gl_split *s, fg_res *r);
void gl_split_set_imports(fg_graph *g, const gl_split *s, const fg_res *r);
/* Declares a pass's access to the array: with one block, `access`
 * (FG_SSBO_READ / FG_SSBO_WRITE) bound by the graph at desc->binding; when
 * split, the texel buffers' access (samplers: FG_SAMPLED; images:
 * FG_IMAGE_LOAD for reads, FG_IMAGE_STORE for writes) on every part, bound
 * by the pass body (gl_split_bind). FG_TRANSFER_READ / _WRITE (clears,
 * readbacks): on every part, unbound. */
void gl_split_use(fg_pass *p, const gl_split *s, const fg_res *r, fg_access access);

/* The glMemoryBarrier bit a hand-written barrier issues for shaders'
 * accesses of the array after other shaders wrote it (the bit of the
 * accesses gl_split_use declares): GL_SHADER_STORAGE_BARRIER_BIT while it
 * is one block (or empty), GL_SHADER_IMAGE_ACCESS_BARRIER_BIT for split
 * image parts, GL_TEXTURE_FETCH_BARRIER_BIT for split sampled parts. */
GLbitfield gl_split_barrier(const gl_split *s);

#endif
