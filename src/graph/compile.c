/* Frame graph compile: validation, versions and dependencies, culling,
 * order, lifetimes, aliasing and barrier derivation. Pure CPU. */
#include "graph/graph_internal.h"

#include <stdlib.h>
#include <string.h>

#define ALL_BITS ((1u << FG_NUM_BARRIER_BITS) - 1u)

void fg_invalidate(fg_graph *g)
{
    if (!g)
        return;
    g->compiled = false;
    free(g->links);
    free(g->vers);
    free(g->edges);
    free(g->order);
    free(g->phys);
    free(g->pstats);
    free(g->rstats);
    g->links = NULL;
    g->vers = NULL;
    g->edges = NULL;
    g->order = NULL;
    g->phys = NULL;
    g->pstats = NULL;
    g->rstats = NULL;
    g->num_links = g->num_vers = g->num_edges = g->num_order = g->num_phys = 0;
    g->realized = false;
    for (int i = 0; i < g->num_passes; i++) {
        g->passes[i]->live = false;
        g->passes[i]->position = -1;
        g->passes[i]->barrier = 0;
    }
    for (int i = 0; i < g->num_res; i++) {
        g->res[i].first = g->res[i].last = -1;
        g->res[i].physical = -1;
    }
}

static int ceil_div(int a, int b)
{
    return (a + b - 1) / b;
}

/* Width/height/layers from the size fields of a texture descriptor. */
static bool resolve_extent(fg_graph *g, const char *what, const char *name,
                           const fg_tex_desc *d, int *w, int *h, int *layers)
{
    if (d->width < 0 || d->height < 0 || d->div < 0 || d->layers < 0) {
        FG_FAIL(g, "%s '%s': negative size, div or layers", what, name);
        return false;
    }
    if ((d->width > 0) != (d->height > 0)) {
        FG_FAIL(g, "%s '%s': give both width and height, or neither (relative size)", what,
                name);
        return false;
    }
    if (d->width > 0) {
        *w = d->width;
        *h = d->height;
    } else {
        if (g->out_width <= 0 || g->out_height <= 0) {
            FG_FAIL(g, "%s '%s' is sized relative to the output resolution, but none is "
                    "set (fg_set_resolution)", what, name);
            return false;
        }
        int div = d->div ? d->div : 1;
        *w = ceil_div(g->out_width, div);
        *h = ceil_div(g->out_height, div);
    }
    *layers = d->layers ? d->layers : 1;
    return true;
}

static int full_levels(int w, int h)
{
    int n = 1;
    for (int s = w > h ? w : h; s > 1; s >>= 1)
        n++;
    return n;
}

static bool resolve_resource(fg_graph *g, fg_resource *r)
{
    if (r->texture) {
        const fg_tex_desc *d = &r->tex;
        const char *what = r->imported ? "imported texture" : "texture";
        if (!resolve_extent(g, what, r->name, d, &r->width, &r->height, &r->layers))
            return false;
        if (!d->array && r->layers > 1) {
            FG_FAIL(g, "%s '%s': %d layers need .array = true", what, r->name, r->layers);
            return false;
        }
        int full = full_levels(r->width, r->height);
        if (d->levels == FG_MIPS_FULL)
            r->levels = full;
        else if (d->levels < 0 || d->levels > full) {
            FG_FAIL(g, "%s '%s': %d mip levels (a %dx%d texture has at most %d)", what,
                    r->name, d->levels, r->width, r->height, full);
            return false;
        } else
            r->levels = d->levels ? d->levels : 1;
        r->bytes = fg_texture_bytes(d->format, r->width, r->height, r->layers, r->levels);
        return true;
    }
    if (r->imported) {
        r->bytes = r->import_size;
        return true;
    }
    const fg_buf_desc *d = &r->buf;
    if (d->div < 0 || d->layers < 0) {
        FG_FAIL(g, "buffer '%s': negative div or layers", r->name);
        return false;
    }
    size_t total = d->bytes;
    if (d->per_pixel) {
        if (g->out_width <= 0 || g->out_height <= 0) {
            FG_FAIL(g, "buffer '%s' is sized per pixel of the output resolution, but none is "
                    "set (fg_set_resolution)", r->name);
            return false;
        }
        int div = d->div ? d->div : 1;
        size_t px = (size_t)ceil_div(g->out_width, div) * (size_t)ceil_div(g->out_height, div) *
                    (size_t)(d->layers ? d->layers : 1);
        if (px && d->per_pixel > (SIZE_MAX - total) / px) {
            FG_FAIL(g, "buffer '%s': size overflows", r->name);
            return false;
        }
        total += px * d->per_pixel;
    }
    if (total == 0) {
        FG_FAIL(g, "buffer '%s' has size 0", r->name);
        return false;
    }
    r->bytes = total;
    return true;
}

static bool is_image_access(fg_access a)
{
    return a == FG_IMAGE_LOAD || a == FG_IMAGE_STORE || a == FG_IMAGE_ATOMIC;
}

/* Checks one use on its own; false (after logging) when it is unusable. */
static bool check_use(fg_graph *g, const fg_use_rec *u)
{
    const fg_pass *p = g->passes[u->pass];
    fg_resource *r = fg_res_get(g, (fg_res){u->res});
    if (!r) {
        if (u->res == 0)
            FG_FAIL(g, "pass '%s' uses an invalid resource (a failed declaration)", p->name);
        else
            FG_FAIL(g, "pass '%s' uses unknown resource #%u", p->name, u->res);
        return false;
    }
    if (u->access <= FG_ACCESS_NONE || u->access >= FG_ACCESS_COUNT) {
        FG_FAIL(g, "pass '%s': invalid access %d on '%s'", p->name, (int)u->access, r->name);
        return false;
    }
    const char *an = fg_access_name(u->access);
    if (u->direction == 1 && fg_access_writes(u->access)) {
        FG_FAIL(g, "pass '%s': fg_read of '%s' with the writing access '%s' (use fg_write)",
                p->name, r->name, an);
        return false;
    }
    if (u->direction == 2 && !fg_access_writes(u->access)) {
        FG_FAIL(g, "pass '%s': fg_write of '%s' with the read-only access '%s' (use fg_read)",
                p->name, r->name, an);
        return false;
    }
    bool tex_ok = u->access == FG_SAMPLED || is_image_access(u->access) ||
                  u->access == FG_COLOR || u->access == FG_DEPTH ||
                  u->access == FG_TRANSFER_READ || u->access == FG_TRANSFER_WRITE;
    /* A buffer read through a texel buffer (sampled, or as an image) is
     * bound by the pass itself: the graph has no texture of it. */
    bool texel_buffer = (u->access == FG_SAMPLED || is_image_access(u->access)) &&
                        !u->opts.bind;
    bool buf_ok = texel_buffer || !(u->access == FG_SAMPLED || is_image_access(u->access) ||
                                    u->access == FG_COLOR || u->access == FG_DEPTH);
    if (r->texture ? !tex_ok : !buf_ok) {
        FG_FAIL(g, "pass '%s': access '%s' needs a %s, but '%s' is a %s", p->name, an,
                r->texture ? "buffer" : "texture", r->name, r->texture ? "texture" : "buffer");
        return false;
    }
    if ((u->access == FG_COLOR || u->access == FG_DEPTH) && p->kind != FG_RASTER) {
        FG_FAIL(g, "pass '%s' is a compute pass and cannot use '%s' as a %s attachment",
                p->name, r->name, an);
        return false;
    }
    if (r->texture) {
        bool depth = fg_format_is_depth(r->tex.format);
        if (depth && (is_image_access(u->access) || u->access == FG_COLOR)) {
            FG_FAIL(g, "pass '%s': depth texture '%s' cannot be used as %s", p->name, r->name,
                    an);
            return false;
        }
        if (!depth && u->access == FG_DEPTH) {
            FG_FAIL(g, "pass '%s': '%s' (%s) is not a depth format for a depth attachment",
                    p->name, r->name, fg_format_name(r->tex.format));
            return false;
        }
    }
    if (u->opts.level < 0) {
        FG_FAIL(g, "pass '%s': negative level for '%s'", p->name, r->name);
        return false;
    }
    return true;
}

static fg_access first_read(uint32_t mask)
{
    for (int a = 1; a < FG_ACCESS_COUNT; a++) {
        if ((mask & (1u << a)) && fg_access_reads((fg_access)a))
            return (fg_access)a;
    }
    return FG_ACCESS_NONE;
}

static bool link_reads(const fg_link *l)
{
    return first_read(l->accesses) != FG_ACCESS_NONE;
}

static bool add_edge(fg_graph *g, int *cap, int from, int to, int res, enum fg_edge_kind kind)
{
    if (from == to || from < 0)
        return true;
    if (!fg_grow((void **)&g->edges, cap, g->num_edges + 1, sizeof(*g->edges)))
        return false;
    g->edges[g->num_edges++] = (fg_edge){from, to, res, kind};
    return true;
}

/* Builds links (one per pass and resource) and versions by replaying the
 * uses in call order. */
static bool build_links(fg_graph *g, const bool *bad)
{
    int np = g->num_passes, nr = g->num_res;
    int cap_links = 0, cap_vers = 0;
    int *link_of = NULL, *cur = NULL;
    bool ok = false;
    if (np && nr) {
        link_of = malloc((size_t)np * (size_t)nr * sizeof(*link_of));
        if (!link_of)
            goto oom;
        for (size_t i = 0; i < (size_t)np * (size_t)nr; i++)
            link_of[i] = -1;
    }
    cur = malloc((size_t)(nr ? nr : 1) * sizeof(*cur));
    if (!cur || !fg_grow((void **)&g->vers, &cap_vers, nr ? nr : 1, sizeof(*g->vers)))
        goto oom;
    for (int r = 0; r < nr; r++) {
        g->vers[r] = (fg_version){r, -1, -1};
        cur[r] = r;
    }
    g->num_vers = nr;
    for (int i = 0; i < g->num_uses; i++) {
        if (bad[i])
            continue;
        const fg_use_rec *u = &g->uses[i];
        int r = (int)u->res - 1;
        size_t key = (size_t)u->pass * (size_t)nr + (size_t)r;
        int li = link_of[key];
        if (li < 0) {
            if (!fg_grow((void **)&g->links, &cap_links, g->num_links + 1, sizeof(*g->links)))
                goto oom;
            li = g->num_links++;
            g->links[li] = (fg_link){.pass = u->pass, .res = r, .write = FG_ACCESS_NONE,
                                     .input = cur[r], .output = -1};
            link_of[key] = li;
        }
        fg_link *l = &g->links[li];
        const char *pn = g->passes[u->pass]->name, *rn = g->res[r].name;
        if (fg_access_writes(u->access)) {
            if (l->write != FG_ACCESS_NONE && l->write != u->access) {
                FG_FAIL(g, "pass '%s' writes '%s' with two different accesses (%s and %s)",
                        pn, rn, fg_access_name(l->write), fg_access_name(u->access));
                continue;
            }
            if (l->write == FG_ACCESS_NONE) {
                if (cur[r] != l->input) {
                    int other = g->vers[cur[r]].writer;
                    FG_FAIL(g, "dependency cycle: pass '%s' reads '%s' before pass '%s' "
                            "writes it and writes it afterwards (declare a pass's accesses "
                            "to one resource together)", pn, rn,
                            other >= 0 ? g->passes[other]->name : "?");
                    continue;
                }
                if (!fg_grow((void **)&g->vers, &cap_vers, g->num_vers + 1, sizeof(*g->vers)))
                    goto oom;
                l = &g->links[li];
                g->vers[g->num_vers] = (fg_version){r, u->pass, li};
                l->output = g->num_vers++;
                cur[r] = l->output;
                l->write = u->access;
            }
        }
        l->accesses |= 1u << u->access;
    }
    ok = true;
    goto done;
oom:
    FG_FAIL(g, "out of memory");
done:
    free(link_of);
    free(cur);
    return ok;
}

static bool build_edges(fg_graph *g)
{
    int cap = 0;
    int nv = g->num_vers;
    int *head = malloc((size_t)(nv ? nv : 1) * sizeof(*head));
    int *next = malloc((size_t)(g->num_links ? g->num_links : 1) * sizeof(*next));
    int *writer_of_input = malloc((size_t)(nv ? nv : 1) * sizeof(*writer_of_input));
    bool ok = false;
    if (!head || !next || !writer_of_input) {
        FG_FAIL(g, "out of memory");
        goto done;
    }
    for (int v = 0; v < nv; v++)
        head[v] = writer_of_input[v] = -1;
    /* readers of each version, in link order */
    for (int li = g->num_links - 1; li >= 0; li--) {
        const fg_link *l = &g->links[li];
        if (link_reads(l)) {
            next[li] = head[l->input];
            head[l->input] = li;
        }
        if (l->write != FG_ACCESS_NONE)
            writer_of_input[l->input] = li;
    }
    for (int li = 0; li < g->num_links; li++) {
        const fg_link *l = &g->links[li];
        int w = g->vers[l->input].writer;
        if (link_reads(l)) {
            if (!add_edge(g, &cap, w, l->pass, l->res, FG_EDGE_RAW))
                goto done;
        } else if (l->write != FG_ACCESS_NONE) {
            if (!add_edge(g, &cap, w, l->pass, l->res, FG_EDGE_WAW))
                goto done;
        }
    }
    /* write after read: the next writer of a version runs after its readers */
    for (int v = 0; v < nv; v++) {
        int wl = writer_of_input[v];
        if (wl < 0)
            continue;
        for (int rl = head[v]; rl >= 0; rl = next[rl]) {
            if (!add_edge(g, &cap, g->links[rl].pass, g->links[wl].pass, g->links[wl].res,
                          FG_EDGE_WAR))
                goto done;
        }
    }
    ok = true;
done:
    if (!ok && g->num_errors == 0)
        FG_FAIL(g, "out of memory");
    free(head);
    free(next);
    free(writer_of_input);
    return ok;
}

static void check_reads(fg_graph *g)
{
    for (int li = 0; li < g->num_links; li++) {
        const fg_link *l = &g->links[li];
        fg_access a = first_read(l->accesses);
        if (a == FG_ACCESS_NONE || g->vers[l->input].writer >= 0 || g->res[l->res].imported)
            continue;
        FG_FAIL(g, "pass '%s' reads '%s' (%s) but no pass writes it before (declare its "
                "writer first, or import it)", g->passes[l->pass]->name, g->res[l->res].name,
                fg_access_name(a));
    }
}

/* Framebuffer of each raster pass: attachments agree in size. */
static void check_raster(fg_graph *g, const bool *bad)
{
    for (int pi = 0; pi < g->num_passes; pi++) {
        fg_pass *p = g->passes[pi];
        if (p->kind != FG_RASTER)
            continue;
        int w = -1, h = -1, layers = 1, depth_res = -1;
        int first_res = -1;
        unsigned color_slots = 0;
        for (int i = 0; i < g->num_uses; i++) {
            const fg_use_rec *u = &g->uses[i];
            if (bad[i] || u->pass != pi || (u->access != FG_COLOR && u->access != FG_DEPTH))
                continue;
            const fg_resource *r = &g->res[u->res - 1];
            if (u->opts.level >= r->levels) {
                FG_FAIL(g, "pass '%s': attachment '%s' level %d, it has %d", p->name, r->name,
                        u->opts.level, r->levels);
                continue;
            }
            int lw = r->width >> u->opts.level, lh = r->height >> u->opts.level;
            lw = lw > 0 ? lw : 1;
            lh = lh > 0 ? lh : 1;
            int ll = r->tex.array ? r->layers : 1;
            if (first_res < 0) {
                first_res = (int)u->res - 1;
                w = lw;
                h = lh;
                layers = ll;
            } else if (lw != w || lh != h || ll != layers) {
                FG_FAIL(g, "raster pass '%s': attachment '%s' is %dx%dx%d but '%s' is "
                        "%dx%dx%d", p->name, r->name, lw, lh, ll, g->res[first_res].name, w,
                        h, layers);
            }
            if (u->access == FG_DEPTH) {
                if (depth_res >= 0 && depth_res != (int)u->res - 1)
                    FG_FAIL(g, "raster pass '%s' has two depth attachments ('%s', '%s')",
                            p->name, g->res[depth_res].name, r->name);
                depth_res = (int)u->res - 1;
            } else {
                if (u->opts.binding >= 8) {
                    FG_FAIL(g, "raster pass '%s': draw buffer %u of '%s' is out of range "
                            "(0..7)", p->name, u->opts.binding, r->name);
                    continue;
                }
                if (color_slots & (1u << u->opts.binding))
                    FG_FAIL(g, "raster pass '%s': two colour attachments at draw buffer %u",
                            p->name, u->opts.binding);
                color_slots |= 1u << u->opts.binding;
            }
        }
        if (first_res >= 0) {
            p->raster_width = w;
            p->raster_height = h;
            p->raster_layers = layers;
        } else if (p->has_raster_size) {
            resolve_extent(g, "raster pass", p->name, &p->raster, &p->raster_width,
                           &p->raster_height, &p->raster_layers);
        } else if (g->out_width > 0 && g->out_height > 0) {
            p->raster_width = g->out_width;
            p->raster_height = g->out_height;
            p->raster_layers = 1;
        } else {
            FG_FAIL(g, "raster pass '%s' has no attachments, no raster size and there is no "
                    "output resolution", p->name);
        }
    }
}

/* Stable topological order (smallest declaration index first among the
 * ready passes) of the passes with include[p]. Returns the count ordered;
 * order[] receives pass indices. */
static int topo_order(const fg_graph *g, const bool *include, int *order, int *indeg)
{
    int np = g->num_passes, n = 0, total = 0;
    for (int p = 0; p < np; p++) {
        indeg[p] = 0;
        total += include[p];
    }
    for (int e = 0; e < g->num_edges; e++) {
        const fg_edge *ed = &g->edges[e];
        if (include[ed->from] && include[ed->to])
            indeg[ed->to]++;
    }
    bool *done = calloc((size_t)(np ? np : 1), sizeof(*done));
    if (!done)
        return -1;
    while (n < total) {
        int pick = -1;
        for (int p = 0; p < np; p++) {
            if (include[p] && !done[p] && indeg[p] == 0) {
                pick = p;
                break;
            }
        }
        if (pick < 0)
            break;
        done[pick] = true;
        order[n++] = pick;
        for (int e = 0; e < g->num_edges; e++) {
            const fg_edge *ed = &g->edges[e];
            if (ed->from == pick && include[ed->to])
                indeg[ed->to]--;
        }
    }
    free(done);
    return n;
}

static const char *edge_kind_name(enum fg_edge_kind k)
{
    return k == FG_EDGE_RAW ? "reads" : k == FG_EDGE_WAW ? "overwrites" : "must not clobber";
}

/* After a stalled topological sort: report one cycle among the passes left
 * with indeg > 0. */
static void report_cycle(fg_graph *g, const int *indeg)
{
    int np = g->num_passes;
    int *pred_edge = malloc((size_t)np * sizeof(*pred_edge));
    int *seen = malloc((size_t)np * sizeof(*seen));
    if (!pred_edge || !seen) {
        FG_FAIL(g, "dependency cycle (out of memory describing it)");
        goto done;
    }
    int start = -1;
    for (int p = 0; p < np && start < 0; p++) {
        if (indeg[p] > 0)
            start = p;
    }
    for (int p = 0; p < np; p++)
        seen[p] = -1;
    /* walk predecessors inside the stuck set until a pass repeats */
    int x = start, step = 0;
    while (x >= 0 && seen[x] < 0) {
        seen[x] = step++;
        int pe = -1;
        for (int e = 0; e < g->num_edges; e++) {
            if (g->edges[e].to == x && indeg[g->edges[e].from] > 0) {
                pe = e;
                break;
            }
        }
        pred_edge[x] = pe;
        x = pe >= 0 ? g->edges[pe].from : -1;
    }
    if (x < 0) {
        FG_FAIL(g, "dependency cycle among the passes");
        goto done;
    }
    /* x is on the cycle; follow predecessors from x back to x, then print in
     * execution direction */
    char msg[400];
    size_t len = 0;
    int cyc[64], nc = 0;
    int y = x;
    do {
        cyc[nc++] = pred_edge[y];
        y = g->edges[pred_edge[y]].from;
    } while (y != x && nc < 64);
    len += (size_t)snprintf(msg, sizeof(msg), "%s", g->passes[x]->name);
    for (int i = nc - 1; i >= 0 && len < sizeof(msg); i--) {
        /* cyc[nc-1] leads out of ..., walk forward: edge from -> to */
        const fg_edge *e = &g->edges[cyc[i]];
        len += (size_t)snprintf(msg + len, sizeof(msg) - len, " -> %s (%s '%s')",
                                g->passes[e->to]->name, edge_kind_name(e->kind),
                                g->res[e->res].name);
    }
    FG_FAIL(g, "dependency cycle: %s", msg);
done:
    free(pred_edge);
    free(seen);
}

static void mark_live(fg_graph *g)
{
    for (int li = 0; li < g->num_links; li++) {
        const fg_link *l = &g->links[li];
        const fg_resource *r = &g->res[l->res];
        if (l->write != FG_ACCESS_NONE && (r->output || r->imported))
            g->passes[l->pass]->live = true;
    }
    for (int p = 0; p < g->num_passes; p++) {
        if (g->passes[p]->keep)
            g->passes[p]->live = true;
    }
    bool changed = true;
    while (changed) {
        changed = false;
        for (int e = 0; e < g->num_edges; e++) {
            const fg_edge *ed = &g->edges[e];
            if (ed->kind != FG_EDGE_WAR && g->passes[ed->to]->live &&
                !g->passes[ed->from]->live) {
                g->passes[ed->from]->live = true;
                changed = true;
            }
        }
    }
}

static bool phys_compatible(const fg_phys *ph, const fg_resource *r)
{
    if (ph->desc.texture != r->texture)
        return false;
    if (!r->texture)
        return ph->desc.readback == r->buf.readback;
    return ph->desc.format == r->tex.format && ph->desc.array == r->tex.array &&
           ph->desc.width == r->width && ph->desc.height == r->height &&
           ph->desc.layers == r->layers && ph->desc.levels == r->levels;
}

static void phys_add_label(fg_phys *ph, const char *name)
{
    size_t len = strlen(ph->label);
    snprintf(ph->label + len, sizeof(ph->label) - len, "%s%s", len ? "+" : "", name);
}

static bool assign_physical(fg_graph *g)
{
    int nr = g->num_res, cap = 0, n = 0;
    int *idx = malloc((size_t)(nr ? nr : 1) * sizeof(*idx));
    if (!idx) {
        FG_FAIL(g, "out of memory");
        return false;
    }
    for (int r = 0; r < nr; r++) {
        if (!g->res[r].imported && g->res[r].first >= 0)
            idx[n++] = r;
    }
    /* by first use, then declaration (insertion sort: stable, n is small) */
    for (int i = 1; i < n; i++) {
        int v = idx[i], j = i - 1;
        while (j >= 0 && g->res[idx[j]].first > g->res[v].first) {
            idx[j + 1] = idx[j];
            j--;
        }
        idx[j + 1] = v;
    }
    for (int i = 0; i < n; i++) {
        fg_resource *r = &g->res[idx[i]];
        int pick = -1;
        if (!g->no_alias) {
            for (int k = 0; k < g->num_phys; k++) {
                const fg_phys *ph = &g->phys[k];
                if (ph->last >= r->first || !phys_compatible(ph, r))
                    continue;
                if (r->texture) {
                    pick = k;
                    break;
                }
                /* buffers: best fit among those large enough, else the largest */
                if (pick < 0) {
                    pick = k;
                    continue;
                }
                size_t have = g->phys[pick].desc.bytes, cand = ph->desc.bytes;
                bool have_fits = have >= r->bytes, cand_fits = cand >= r->bytes;
                if ((cand_fits && (!have_fits || cand < have)) ||
                    (!cand_fits && !have_fits && cand > have))
                    pick = k;
            }
        }
        if (pick < 0) {
            if (!fg_grow((void **)&g->phys, &cap, g->num_phys + 1, sizeof(*g->phys))) {
                free(idx);
                FG_FAIL(g, "out of memory");
                return false;
            }
            pick = g->num_phys++;
            fg_phys *ph = &g->phys[pick];
            *ph = (fg_phys){0};
            ph->desc.texture = r->texture;
            if (r->texture) {
                ph->desc.format = r->tex.format;
                ph->desc.array = r->tex.array;
                ph->desc.width = r->width;
                ph->desc.height = r->height;
                ph->desc.layers = r->layers;
                ph->desc.levels = r->levels;
            } else {
                ph->desc.readback = r->buf.readback;
            }
        }
        fg_phys *ph = &g->phys[pick];
        if (r->bytes > ph->desc.bytes)
            ph->desc.bytes = r->bytes;
        ph->last = r->last;
        phys_add_label(ph, r->name);
        r->physical = pick;
    }
    for (int k = 0; k < g->num_phys; k++)
        g->phys[k].desc.label = g->phys[k].label;
    free(idx);
    return true;
}

/* Barrier bits per pass: simulate the order twice over the real memory
 * objects (physical allocations and imports), tracking per object which bits
 * still have an unflushed shader write / unordered access behind them. The
 * second round starts from the end state of the first, so hazards carried
 * from one execute into the next (loop-carried) are covered; with shared
 * imports every import starts it as written and accessed outside. */
static bool derive_barriers(fg_graph *g, const int *plink, const int *plink_start)
{
    int nobj = g->num_phys + g->num_res;
    uint32_t *sw_pend = calloc((size_t)(nobj ? nobj : 1), sizeof(*sw_pend));
    uint32_t *acc_pend = calloc((size_t)(nobj ? nobj : 1), sizeof(*acc_pend));
    if (!sw_pend || !acc_pend) {
        free(sw_pend);
        free(acc_pend);
        FG_FAIL(g, "out of memory");
        return false;
    }
    for (int round = 0; round < 2; round++) {
        for (int r = 0; round == 1 && g->shared_imports && r < g->num_res; r++) {
            if (g->res[r].imported) {
                sw_pend[g->num_phys + r] = ALL_BITS;
                acc_pend[g->num_phys + r] = ALL_BITS;
            }
        }
        for (int pos = 0; pos < g->num_order; pos++) {
            fg_pass *p = g->passes[g->order[pos]];
            uint32_t need = 0;
            for (int k = plink_start[p->index]; k < plink_start[p->index + 1]; k++) {
                const fg_link *l = &g->links[plink[k]];
                const fg_resource *r = &g->res[l->res];
                int o = r->imported ? g->num_phys + l->res : r->physical;
                for (int a = 1; a < FG_ACCESS_COUNT; a++) {
                    if (!(l->accesses & (1u << a)))
                        continue;
                    uint32_t bit = fg_barrier_bit((fg_access)a, r->texture);
                    if (sw_pend[o] & bit)
                        need |= bit;
                    if (fg_access_shader_write((fg_access)a) && (acc_pend[o] & bit))
                        need |= bit;
                }
            }
            p->barrier = need;
            for (int o = 0; o < nobj; o++) {
                sw_pend[o] &= ~need;
                acc_pend[o] &= ~need;
            }
            for (int k = plink_start[p->index]; k < plink_start[p->index + 1]; k++) {
                const fg_link *l = &g->links[plink[k]];
                const fg_resource *r = &g->res[l->res];
                int o = r->imported ? g->num_phys + l->res : r->physical;
                for (int a = 1; a < FG_ACCESS_COUNT; a++) {
                    if (!(l->accesses & (1u << a)))
                        continue;
                    acc_pend[o] = ALL_BITS;
                    if (fg_access_shader_write((fg_access)a))
                        sw_pend[o] = ALL_BITS;
                }
            }
        }
    }
    free(sw_pend);
    free(acc_pend);
    return true;
}

static bool build_stats(fg_graph *g)
{
    g->pstats = calloc((size_t)(g->num_passes ? g->num_passes : 1), sizeof(*g->pstats));
    g->rstats = calloc((size_t)(g->num_res ? g->num_res : 1), sizeof(*g->rstats));
    if (!g->pstats || !g->rstats) {
        FG_FAIL(g, "out of memory");
        return false;
    }
    for (int i = 0; i < g->num_passes; i++) {
        const fg_pass *p = g->passes[i];
        g->pstats[i] = (fg_pass_stats){
            .name = p->name, .kind = p->kind, .culled = !p->live, .position = p->position,
            .barrier = p->barrier, .ms = -1, .clock = DIRT_CLOCK_NONE,
        };
    }
    for (int i = 0; i < g->num_res; i++) {
        const fg_resource *r = &g->res[i];
        g->rstats[i] = (fg_res_stats){
            .name = r->name, .texture = r->texture, .imported = r->imported,
            .output = r->output, .culled = r->first < 0, .physical = r->physical,
            .first = r->first, .last = r->last, .bytes = r->bytes,
            .used_bytes = r->used_bytes, .used_reported = r->used_reported,
        };
    }
    return true;
}

bool fg_compile(fg_graph *g)
{
    if (!g)
        return false;
    fg_invalidate(g);
    g->num_errors = 0;
    g->error[0] = '\0';
    if (g->decl_errors) {
        g->num_errors = g->decl_errors;
        snprintf(g->error, sizeof(g->error), "%s", g->decl_error);
        DIRT_ERROR("frame graph: %d declaration error(s), first: %s", g->decl_errors,
                   g->decl_error);
    }
    int np = g->num_passes;
    bool *bad = calloc((size_t)(g->num_uses ? g->num_uses : 1), sizeof(*bad));
    bool *include = calloc((size_t)(np ? np : 1), sizeof(*include));
    int *indeg = malloc((size_t)(np ? np : 1) * sizeof(*indeg));
    int *order = malloc((size_t)(np ? np : 1) * sizeof(*order));
    int *plink = malloc((size_t)(g->num_uses ? g->num_uses : 1) * sizeof(*plink));
    int *plink_start = calloc((size_t)np + 1, sizeof(*plink_start));
    if (!bad || !include || !indeg || !order || !plink || !plink_start) {
        FG_FAIL(g, "out of memory");
        goto error;
    }
    for (int r = 0; r < g->num_res; r++)
        resolve_resource(g, &g->res[r]);
    for (int i = 0; i < g->num_uses; i++)
        bad[i] = !check_use(g, &g->uses[i]);
    if (!build_links(g, bad) || !build_edges(g))
        goto error;
    check_reads(g);
    check_raster(g, bad);

    for (int p = 0; p < np; p++)
        include[p] = true;
    int n = topo_order(g, include, order, indeg);
    if (n < 0) {
        FG_FAIL(g, "out of memory");
        goto error;
    }
    if (n < np)
        report_cycle(g, indeg);
    if (g->num_errors)
        goto error;

    mark_live(g);
    for (int p = 0; p < np; p++)
        include[p] = g->passes[p]->live;
    n = topo_order(g, include, order, indeg);
    if (n < 0) {
        FG_FAIL(g, "out of memory");
        goto error;
    }
    g->order = order;
    order = NULL;
    g->num_order = n;
    for (int pos = 0; pos < n; pos++)
        g->passes[g->order[pos]]->position = pos;

    /* links grouped by pass (counting sort keeps link order inside a pass) */
    for (int li = 0; li < g->num_links; li++)
        plink_start[g->links[li].pass + 1]++;
    for (int p = 0; p < np; p++)
        plink_start[p + 1] += plink_start[p];
    for (int p = 0; p < np; p++)
        indeg[p] = plink_start[p];
    for (int li = 0; li < g->num_links; li++)
        plink[indeg[g->links[li].pass]++] = li;

    /* lifetimes over the live passes */
    for (int li = 0; li < g->num_links; li++) {
        const fg_link *l = &g->links[li];
        const fg_pass *p = g->passes[l->pass];
        if (!p->live)
            continue;
        fg_resource *r = &g->res[l->res];
        if (r->first < 0 || p->position < r->first)
            r->first = p->position;
        if (p->position > r->last)
            r->last = p->position;
    }
    if (!assign_physical(g) || !derive_barriers(g, plink, plink_start) || !build_stats(g))
        goto error;
    g->compiled = true;
    free(bad);
    free(include);
    free(indeg);
    free(order);
    free(plink);
    free(plink_start);
    return true;
error:
    free(bad);
    free(include);
    free(indeg);
    free(order);
    free(plink);
    free(plink_start);
    int errors = g->num_errors;
    char first[sizeof(g->error)];
    memcpy(first, g->error, sizeof(first));
    fg_invalidate(g);
    g->num_errors = errors;
    memcpy(g->error, first, sizeof(first));
    return false;
}

/* ---- queries ------------------------------------------------------------- */

int fg_num_passes(const fg_graph *g)
{
    return g ? g->num_passes : 0;
}

int fg_num_ordered(const fg_graph *g)
{
    return g && g->compiled ? g->num_order : 0;
}

int fg_order(const fg_graph *g, int pos)
{
    if (!g || !g->compiled || pos < 0 || pos >= g->num_order)
        return -1;
    return g->order[pos];
}

int fg_position(const fg_graph *g, const char *name)
{
    const fg_pass *p = fg_pass_find(g, name);
    return p && g->compiled ? p->position : -1;
}

bool fg_culled(const fg_graph *g, const char *name)
{
    const fg_pass *p = fg_pass_find(g, name);
    return p && g->compiled && !p->live;
}

uint32_t fg_pass_barrier(const fg_graph *g, const char *name)
{
    const fg_pass *p = fg_pass_find(g, name);
    return p && g->compiled ? p->barrier : 0;
}

bool fg_lifetime(const fg_graph *g, fg_res r, int *first, int *last)
{
    const fg_resource *res = fg_res_get(g, r);
    if (!res || !g->compiled)
        return false;
    if (first)
        *first = res->first;
    if (last)
        *last = res->last;
    return res->first >= 0;
}

int fg_physical(const fg_graph *g, fg_res r)
{
    const fg_resource *res = fg_res_get(g, r);
    return res && g->compiled ? res->physical : -1;
}

int fg_num_physical(const fg_graph *g)
{
    return g && g->compiled ? g->num_phys : 0;
}

size_t fg_bytes(const fg_graph *g, fg_res r)
{
    const fg_resource *res = fg_res_get(g, r);
    return res && g->compiled ? res->bytes : 0;
}
