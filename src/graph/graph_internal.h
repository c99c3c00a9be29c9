/* Frame graph internals shared by graph.c (declarations), compile.c,
 * exec.c and report.c. No GL here. */
#ifndef DIRT_GRAPH_INTERNAL_H
#define DIRT_GRAPH_INTERNAL_H

#include "graph/graph.h"

#include "dirt/log.h"

#define FG_NUM_BARRIER_BITS 16

/* One fg_use() call, kept in call order: the call order defines versions. */
typedef struct fg_use_rec {
    int pass;
    uint32_t res;           /* handle id as given (may be invalid) */
    fg_access access;
    fg_use_opts opts;
    int direction;          /* 0 fg_use, 1 fg_read, 2 fg_write */
} fg_use_rec;

/* Compiled: everything one pass does to one resource. */
typedef struct fg_link {
    int pass;
    int res;                /* resource index (id - 1) */
    uint32_t accesses;      /* bit (1 << fg_access) per declared access */
    fg_access write;        /* its write access, FG_ACCESS_NONE when it only reads */
    int input;              /* version it reads / overwrites (index into vers) */
    int output;             /* version it produces, -1 */
} fg_link;

/* Compiled: one content version of a resource. */
typedef struct fg_version {
    int res;
    int writer;             /* pass index, -1 for the content before the graph */
    int link;               /* writer's link, -1 */
} fg_version;

enum fg_edge_kind { FG_EDGE_RAW, FG_EDGE_WAW, FG_EDGE_WAR };

typedef struct fg_edge {
    int from, to;           /* pass indices: `to` runs after `from` */
    int res;
    enum fg_edge_kind kind;
} fg_edge;

typedef struct fg_resource {
    char *name;
    bool texture;
    bool imported;
    bool output;
    fg_tex_desc tex;
    fg_buf_desc buf;
    uint32_t import_name;
    size_t import_size;
    /* compiled */
    int width, height, layers, levels;
    size_t bytes;
    int first, last;        /* execution positions, -1 when unused by live passes */
    int physical;           /* -1 imported/culled */
    /* execute */
    size_t used_bytes;
    bool used_reported;
} fg_resource;

struct fg_pass {
    fg_graph *g;
    int index;
    char *name;
    fg_pass_kind kind;
    fg_execute_fn fn;
    void *user;
    bool keep;
    bool has_raster_size;
    fg_tex_desc raster;
    /* compiled */
    bool live;
    int position;
    uint32_t barrier;
    int raster_width, raster_height, raster_layers;
    double ms;              /* last execute; -1 when not measured */
    enum dirt_clock clock;
};

/* A physical allocation (compiled desc + the backend's name once realized). */
typedef struct fg_phys {
    fg_phys_desc desc;
    char label[128];
    uint32_t name;
    int last;               /* last execution position of its current occupant */
} fg_phys;

/* Validator record of one real GL object. */
typedef struct fg_val_obj {
    bool texture;
    uint32_t name;
    uint64_t sw_time, acc_time;     /* last incoherent shader write / any access */
    int sw_pass, acc_pass;
    int sw_res, acc_res;
    fg_access sw_access, acc_access;
} fg_val_obj;

struct fg_ctx {
    fg_graph *g;
    fg_pass *pass;
    const fg_binding *bindings;
    int num_bindings;
};

struct fg_graph {
    fg_backend backend;
    bool has_backend;
    int out_width, out_height;
    bool no_alias;
    bool shared_imports;    /* fg_set_shared_imports */

    fg_resource *res;
    int num_res, cap_res;
    fg_pass **passes;
    int num_passes, cap_passes;
    fg_use_rec *uses;
    int num_uses, cap_uses;

    int decl_errors;
    char decl_error[512];
    int num_errors;
    char error[512];

    /* compiled */
    bool compiled;
    fg_link *links;
    int num_links;
    fg_version *vers;
    int num_vers;
    fg_edge *edges;
    int num_edges;
    int *order;
    int num_order;
    fg_phys *phys;
    int num_phys;
    bool realized;
    bool entry_barrier;     /* first execute after a realization: FG_BARRIER_ALL */
    fg_pass_stats *pstats;
    fg_res_stats *rstats;

    /* execute: allocations held from the last realization */
    fg_phys *held;
    int num_held;
    fg_binding *scratch;
    int cap_scratch;

    /* validator */
    fg_val_obj *objs;
    int num_objs, cap_objs;
    uint64_t clock;
    uint64_t issued_at[FG_NUM_BARRIER_BITS];
    uint64_t validation_errors;
    uint64_t executions;
};

/* Logs an error with the caller's location; the first one of a compile is
 * kept for fg_last_error. */
#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
void fg_fail_(fg_graph *g, const char *file, int line, const char *fmt, ...);
#define FG_FAIL(g, ...) fg_fail_((g), __FILE__, __LINE__, __VA_ARGS__)

/* Grows *ptr (of *cap elements of `size`) to hold `need`; false on OOM. */
bool fg_grow(void **ptr, int *cap, int need, size_t size);

/* Resource from a handle, NULL when invalid. */
fg_resource *fg_res_get(const fg_graph *g, fg_res r);
fg_pass *fg_pass_find(const fg_graph *g, const char *name);
/* Index of the single bit `bit` (0..15), -1 otherwise. */
int fg_barrier_index(uint32_t bit);
/* Texture bytes for a resolved size. */
size_t fg_texture_bytes(fg_format f, int width, int height, int layers, int levels);
/* Drops compiled state (keeps realized allocations in g->held). */
void fg_invalidate(fg_graph *g);
/* Releases every allocation via the backend and forgets validator objects. */
void fg_release_allocations(fg_graph *g);

#endif
