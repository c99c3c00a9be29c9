/* Frame graph execute: allocation through the backend, barriers, pass
 * callbacks, timing and the run-time barrier validation. No GL here: the
 * backend does the GL work. */
#include "graph/graph_internal.h"

#include <stdlib.h>
#include <string.h>

/* ---- allocations --------------------------------------------------------- */

static bool same_desc(const fg_phys_desc *a, const fg_phys_desc *b)
{
    if (a->texture != b->texture || a->bytes != b->bytes)
        return false;
    if (!a->texture)
        return a->readback == b->readback;
    return a->format == b->format && a->array == b->array && a->width == b->width &&
           a->height == b->height && a->layers == b->layers && a->levels == b->levels;
}

static void forget_object(fg_graph *g, bool texture, uint32_t name)
{
    for (int i = 0; i < g->num_objs; i++) {
        if (g->objs[i].texture == texture && g->objs[i].name == name) {
            g->objs[i] = g->objs[--g->num_objs];
            return;
        }
    }
}

void fg_release_allocations(fg_graph *g)
{
    for (int i = 0; i < g->num_held; i++) {
        if (g->has_backend && g->held[i].name)
            g->backend.ops->destroy(g->backend.self, &g->held[i].desc, g->held[i].name);
        forget_object(g, g->held[i].desc.texture, g->held[i].name);
    }
    g->num_held = 0;
}

/* Gives every physical resource a GL object: reuses held ones with the same
 * descriptor, creates the others, destroys held ones nobody took. */
static bool realize(fg_graph *g)
{
    if (g->realized)
        return true;
    bool *taken = calloc((size_t)(g->num_held ? g->num_held : 1), sizeof(*taken));
    fg_phys *held = malloc((size_t)(g->num_phys ? g->num_phys : 1) * sizeof(*held));
    if (!taken || !held) {
        free(taken);
        free(held);
        DIRT_ERROR("frame graph: out of memory");
        return false;
    }
    bool ok = true;
    for (int k = 0; k < g->num_phys; k++) {
        fg_phys *ph = &g->phys[k];
        ph->name = 0;
        for (int i = 0; i < g->num_held; i++) {
            if (!taken[i] && same_desc(&g->held[i].desc, &ph->desc)) {
                taken[i] = true;
                ph->name = g->held[i].name;
                break;
            }
        }
    }
    /* destroy the leftovers first so their memory can be reused */
    for (int i = 0; i < g->num_held; i++) {
        if (!taken[i]) {
            g->backend.ops->destroy(g->backend.self, &g->held[i].desc, g->held[i].name);
            forget_object(g, g->held[i].desc.texture, g->held[i].name);
        }
    }
    g->num_held = 0;
    for (int k = 0; k < g->num_phys; k++) {
        fg_phys *ph = &g->phys[k];
        if (!ph->name) {
            ph->name = g->backend.ops->create(g->backend.self, &ph->desc);
            if (!ph->name) {
                DIRT_ERROR("frame graph: could not allocate '%s' (%zu bytes)", ph->label,
                           ph->desc.bytes);
                ok = false;
                continue;
            }
            forget_object(g, ph->desc.texture, ph->name); /* a recycled GL name */
        }
        held[g->num_held] = *ph;
        held[g->num_held].desc.label = NULL;
        g->num_held++;
    }
    free(g->held);
    g->held = held;
    free(taken);
    g->realized = ok;
    /* Reused objects (and imports) carry accesses of the previous schedule,
     * which the new schedule's steady-state barriers do not cover. */
    g->entry_barrier = ok;
    return ok;
}

/* ---- validation ---------------------------------------------------------- */

static fg_val_obj *val_obj(fg_graph *g, bool texture, uint32_t name)
{
    for (int i = 0; i < g->num_objs; i++) {
        if (g->objs[i].texture == texture && g->objs[i].name == name)
            return &g->objs[i];
    }
    if (!fg_grow((void **)&g->objs, &g->cap_objs, g->num_objs + 1, sizeof(*g->objs)))
        return NULL;
    fg_val_obj *o = &g->objs[g->num_objs++];
    *o = (fg_val_obj){.texture = texture, .name = name, .sw_pass = -1, .acc_pass = -1,
                      .sw_res = -1, .acc_res = -1};
    return o;
}

static void note_barrier(fg_graph *g, uint32_t bits)
{
    g->clock++;
    for (int i = 0; i < FG_NUM_BARRIER_BITS; i++) {
        if (bits & (1u << i))
            g->issued_at[i] = g->clock;
    }
}

static const char *res_label(const fg_graph *g, int res)
{
    return res >= 0 && res < g->num_res ? g->res[res].name : "?";
}

/* Checks the accesses of `p` against the barriers issued since the earlier
 * accesses of the same GL objects. Returns the number of violations. */
static int check_pass(fg_graph *g, const fg_pass *p, const fg_binding *b, int nb)
{
    int violations = 0;
    uint32_t reported_bits = 0;
    for (int i = 0; i < nb; i++) {
        int res = (int)b[i].res.id - 1;
        fg_val_obj *o = val_obj(g, b[i].texture, b[i].name);
        if (!o)
            return violations;
        uint32_t bit = fg_barrier_bit(b[i].access, b[i].texture);
        int bi = fg_barrier_index(bit);
        if (bi < 0 || (reported_bits & bit))
            continue;
        uint64_t issued = g->issued_at[bi];
        const char *an = fg_access_name(b[i].access);
        if (o->sw_time > issued) {
            const char *alias = o->sw_res != res ? " (same memory)" : "";
            DIRT_ERROR("frame graph validation: pass '%s' accesses '%s' (%s) after pass '%s' "
                       "wrote '%s'%s (%s) with no %s in between", p->name, res_label(g, res),
                       an, o->sw_pass >= 0 ? g->passes[o->sw_pass]->name : "?",
                       res_label(g, o->sw_res), alias, fg_access_name(o->sw_access),
                       fg_barrier_name(bit));
            violations++;
            reported_bits |= bit;
        } else if (fg_access_shader_write(b[i].access) && o->acc_time > issued) {
            const char *alias = o->acc_res != res ? " (same memory)" : "";
            DIRT_ERROR("frame graph validation: pass '%s' writes '%s' (%s) after pass '%s' "
                       "accessed '%s'%s (%s) with no %s in between (write after read)",
                       p->name, res_label(g, res), an,
                       o->acc_pass >= 0 ? g->passes[o->acc_pass]->name : "?",
                       res_label(g, o->acc_res), alias, fg_access_name(o->acc_access),
                       fg_barrier_name(bit));
            violations++;
            reported_bits |= bit;
        }
    }
    return violations;
}

static void note_accesses(fg_graph *g, const fg_pass *p, const fg_binding *b, int nb)
{
    g->clock++;
    for (int i = 0; i < nb; i++) {
        fg_val_obj *o = val_obj(g, b[i].texture, b[i].name);
        if (!o)
            return;
        int res = (int)b[i].res.id - 1;
        o->acc_time = g->clock;
        o->acc_pass = p->index;
        o->acc_res = res;
        o->acc_access = b[i].access;
        if (fg_access_shader_write(b[i].access)) {
            o->sw_time = g->clock;
            o->sw_pass = p->index;
            o->sw_res = res;
            o->sw_access = b[i].access;
        }
    }
}

/* ---- execute ------------------------------------------------------------- */

static uint32_t object_name(const fg_graph *g, const fg_resource *r)
{
    if (r->imported)
        return r->import_name;
    return r->physical >= 0 ? g->phys[r->physical].name : 0;
}

/* Bindings of pass `p`: one per declared access, in declaration order. */
static int build_bindings(fg_graph *g, const fg_pass *p)
{
    int n = 0;
    for (int i = 0; i < g->num_uses; i++) {
        const fg_use_rec *u = &g->uses[i];
        if (u->pass != p->index)
            continue;
        if (!fg_grow((void **)&g->scratch, &g->cap_scratch, n + 1, sizeof(*g->scratch)))
            return -1;
        const fg_resource *r = &g->res[u->res - 1];
        bool reads = false, writes = false;
        for (int li = 0; li < g->num_links; li++) {
            const fg_link *l = &g->links[li];
            if (l->pass == p->index && l->res == (int)u->res - 1) {
                for (int a = 1; a < FG_ACCESS_COUNT; a++) {
                    if (l->accesses & (1u << a)) {
                        reads |= fg_access_reads((fg_access)a);
                        writes |= fg_access_writes((fg_access)a);
                    }
                }
                break;
            }
        }
        g->scratch[n++] = (fg_binding){
            .res = (fg_res){u->res}, .access = u->access, .texture = r->texture,
            .name = object_name(g, r), .opts = u->opts, .format = r->tex.format,
            .array = r->tex.array, .width = r->width, .height = r->height,
            .layers = r->layers, .levels = r->levels, .bytes = r->bytes,
            .pass_reads = reads, .pass_writes = writes,
        };
    }
    return n;
}

/* Hands every transient whose first access in the execute order is at
 * `pos` to the backend's poison (once each). */
static void poison_transients(fg_graph *g, int pos, const fg_binding *b, int nb)
{
    for (int i = 0; i < nb; i++) {
        const fg_resource *r = &g->res[b[i].res.id - 1];
        if (r->imported || r->first != pos || !b[i].name)
            continue;
        bool seen = false;
        for (int j = 0; j < i && !seen; j++)
            seen = b[j].res.id == b[i].res.id;
        if (!seen)
            g->backend.ops->poison(g->backend.self, &b[i]);
    }
}

bool fg_execute(fg_graph *g, const fg_exec_opts *opts)
{
    if (!g)
        return false;
    fg_exec_opts o = opts ? *opts : (fg_exec_opts){0};
    if (!g->compiled) {
        DIRT_ERROR("frame graph: execute before a successful fg_compile (or the graph "
                   "changed since)");
        return false;
    }
    if (!g->has_backend) {
        DIRT_ERROR("frame graph: created without a GPU, it cannot execute");
        return false;
    }
    if (!realize(g))
        return false;
    if (o.debug_drop_barrier && !fg_pass_find(g, o.debug_drop_barrier))
        DIRT_WARN("frame graph: debug_drop_barrier names no pass ('%s')", o.debug_drop_barrier);
    g->executions++;
    for (int i = 0; i < g->num_passes; i++) {
        g->pstats[i].ms = -1;
        g->pstats[i].clock = DIRT_CLOCK_NONE;
    }

    if (g->entry_barrier) {
        g->backend.ops->barrier(g->backend.self, FG_BARRIER_ALL);
        note_barrier(g, FG_BARRIER_ALL);
        g->entry_barrier = false;
    }

    bool ok = true;
    uint64_t violations = 0;
    uint64_t errors_before = g->validation_errors; /* undeclared accesses count too */
    for (int pos = 0; pos < g->num_order && ok; pos++) {
        fg_pass *p = g->passes[g->order[pos]];
        int nb = build_bindings(g, p);
        if (nb < 0) {
            ok = false;
            break;
        }
        if (g->backend.ops->poison)
            poison_transients(g, pos, g->scratch, nb);
        uint32_t bits = p->barrier;
        if (bits && o.debug_drop_barrier && strcmp(o.debug_drop_barrier, p->name) == 0) {
            char s[256];
            DIRT_WARN("frame graph: test hook drops the barrier %s before pass '%s'",
                      fg_barrier_string(bits, s, sizeof(s)), p->name);
            bits = 0;
        }
        if (bits) {
            g->backend.ops->barrier(g->backend.self, bits);
            note_barrier(g, bits);
        }
        if (o.validate)
            violations += (uint64_t)check_pass(g, p, g->scratch, nb);
        fg_pass_info info = {
            .name = p->name, .index = p->index, .position = pos, .kind = p->kind,
            .bindings = g->scratch, .num_bindings = nb, .raster_width = p->raster_width,
            .raster_height = p->raster_height, .raster_layers = p->raster_layers,
            .timed = !o.no_timers, .async = !o.no_timers && o.async_timers,
        };
        if (!g->backend.ops->begin_pass(g->backend.self, &info)) {
            DIRT_ERROR("frame graph: pass '%s' could not start", p->name);
            ok = false;
            break;
        }
        fg_ctx ctx = {.g = g, .pass = p, .bindings = g->scratch, .num_bindings = nb};
        bool pass_ok = p->fn ? p->fn(&ctx, p->user) : true;
        double ms = -1;
        enum dirt_clock clock = DIRT_CLOCK_NONE;
        if (!g->backend.ops->end_pass(g->backend.self, &info, &ms, &clock))
            pass_ok = false;
        note_accesses(g, p, g->scratch, nb);
        if (ms < 0 || clock == DIRT_CLOCK_NONE) {
            ms = -1; /* one of the two alone is no measurement */
            clock = DIRT_CLOCK_NONE;
        }
        p->ms = ms;
        p->clock = clock;
        g->pstats[p->index].ms = ms;
        g->pstats[p->index].clock = clock;
        if (!pass_ok) {
            DIRT_ERROR("frame graph: pass '%s' failed", p->name);
            ok = false;
        }
    }
    if (violations) {
        g->validation_errors += violations;
        DIRT_ERROR("frame graph: %llu barrier validation error(s) in this execute",
                   (unsigned long long)violations);
    }
    if (g->validation_errors > errors_before)
        ok = false;
    return ok;
}

/* ---- pass context -------------------------------------------------------- */

static const fg_binding *ctx_find(const fg_ctx *ctx, fg_res r)
{
    if (!ctx)
        return NULL;
    for (int i = 0; i < ctx->num_bindings; i++) {
        if (ctx->bindings[i].res.id == r.id)
            return &ctx->bindings[i];
    }
    return NULL;
}

static const fg_binding *ctx_need(const fg_ctx *ctx, fg_res r, const char *what)
{
    const fg_binding *b = ctx_find(ctx, r);
    if (!b && ctx) {
        const fg_resource *res = fg_res_get(ctx->g, r);
        DIRT_ERROR("frame graph: pass '%s' calls %s on '%s', which it did not declare",
                   ctx->pass->name, what, res ? res->name : "an unknown resource");
        ctx->g->validation_errors++;
    }
    return b;
}

uint32_t fg_name(const fg_ctx *ctx, fg_res r)
{
    const fg_binding *b = ctx_need(ctx, r, "fg_name");
    return b ? b->name : 0;
}

bool fg_declares(const fg_ctx *ctx, fg_res r, fg_access a)
{
    if (!ctx)
        return false;
    for (int i = 0; i < ctx->num_bindings; i++) {
        if (ctx->bindings[i].res.id == r.id && ctx->bindings[i].access == a)
            return true;
    }
    return false;
}

const char *fg_pass_name(const fg_ctx *ctx)
{
    return ctx ? ctx->pass->name : "";
}

void fg_resolution(const fg_ctx *ctx, int *width, int *height)
{
    if (width)
        *width = ctx ? ctx->g->out_width : 0;
    if (height)
        *height = ctx ? ctx->g->out_height : 0;
}

size_t fg_buffer_size(const fg_ctx *ctx, fg_res r)
{
    const fg_binding *b = ctx_need(ctx, r, "fg_buffer_size");
    return b && !b->texture ? b->bytes : 0;
}

bool fg_texture_size(const fg_ctx *ctx, fg_res r, int *width, int *height, int *layers,
                     int *levels)
{
    const fg_binding *b = ctx_need(ctx, r, "fg_texture_size");
    if (!b || !b->texture)
        return false;
    if (width)
        *width = b->width;
    if (height)
        *height = b->height;
    if (layers)
        *layers = b->layers;
    if (levels)
        *levels = b->levels;
    return true;
}

fg_format fg_texture_format(const fg_ctx *ctx, fg_res r)
{
    const fg_binding *b = ctx_need(ctx, r, "fg_texture_format");
    return b && b->texture ? b->format : FG_FORMAT_NONE;
}

void fg_report_used(fg_ctx *ctx, fg_res r, size_t bytes)
{
    const fg_binding *b = ctx_need(ctx, r, "fg_report_used");
    if (!b)
        return;
    fg_resource *res = &ctx->g->res[r.id - 1];
    if (bytes > res->bytes)
        DIRT_WARN("frame graph: pass '%s' reports %zu bytes used in '%s', which has %zu",
                  ctx->pass->name, bytes, res->name, res->bytes);
    res->used_bytes = bytes;
    res->used_reported = true;
    if (ctx->g->rstats) {
        ctx->g->rstats[r.id - 1].used_bytes = bytes;
        ctx->g->rstats[r.id - 1].used_reported = true;
    }
}

/* ---- late times ---------------------------------------------------------- */

bool fg_drain_timers(fg_graph *g, double *late_ms, int count, enum dirt_clock *clock)
{
    if (clock)
        *clock = DIRT_CLOCK_NONE;
    for (int i = 0; late_ms && i < count; i++)
        late_ms[i] = 0;
    if (!g || !g->has_backend)
        return false;
    if (!g->backend.ops->drain)
        return true;
    enum dirt_clock seen = DIRT_CLOCK_NONE;
    for (int i = 0; i < g->num_passes; i++) {
        double ms = 0;
        enum dirt_clock c = DIRT_CLOCK_NONE;
        g->backend.ops->drain(g->backend.self, i, false, &ms, &c);
        if (c == DIRT_CLOCK_NONE || ms < 0)
            continue;
        if (seen != DIRT_CLOCK_NONE && c != seen) {
            DIRT_ERROR("frame graph: pass '%s' drained a time of another clock; left out",
                       g->passes[i]->name);
            continue;
        }
        seen = c;
        if (late_ms && i < count)
            late_ms[i] = ms;
    }
    if (clock)
        *clock = seen;
    return true;
}

void fg_discard_timers(fg_graph *g)
{
    if (!g || !g->has_backend || !g->backend.ops->drain)
        return;
    for (int i = 0; i < g->num_passes; i++) {
        double ms = 0;
        enum dirt_clock c = DIRT_CLOCK_NONE;
        g->backend.ops->drain(g->backend.self, i, true, &ms, &c);
    }
}
