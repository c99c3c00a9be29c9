/* The frame graph's OpenGL backend and the GL helpers for pass bodies.
 * The graph itself (src/graph/) is plain C; this layer sits above it and
 * hands it a backend. */
#ifndef DIRT_GL_GRAPH_GL_H
#define DIRT_GL_GRAPH_GL_H

#include <stdbool.h>
#include <stddef.h>

#include "dirt/gpu.h"
#include "graph/graph.h"

/* The OpenGL backend on `gpu`. False after logging. */
bool fg_gl_backend(dirt_gpu *gpu, fg_backend *out);

/* A graph executing on `gpu` through the OpenGL backend. NULL after logging. */
fg_graph *gl_graph_create(dirt_gpu *gpu);

/* Readback/clear helpers for pass bodies. They check that the pass declared
 * FG_TRANSFER_READ (read helpers) or FG_TRANSFER_WRITE (clear). */
bool fg_gl_read_buffer(const fg_ctx *ctx, fg_res r, size_t offset, size_t size, void *out);
/* Whole level `level` of a 2D texture (all layers of an array), tightly
 * packed in the format's natural client type; `size` is the capacity of out. */
bool fg_gl_read_texture(const fg_ctx *ctx, fg_res r, int level, void *out, size_t size);
/* Zero-fills a buffer or every level of a texture. */
bool fg_gl_clear(const fg_ctx *ctx, fg_res r);

#endif
