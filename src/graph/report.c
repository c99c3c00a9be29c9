/* Frame graph stats and GraphViz export. */
#include "graph/graph_internal.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

bool fg_get_stats(const fg_graph *g, fg_stats *s)
{
    if (!g || !s || !g->compiled)
        return false;
    *s = (fg_stats){
        .num_passes = g->num_passes, .passes = g->pstats,
        .num_resources = g->num_res, .resources = g->rstats,
        .num_physical = g->num_phys, .executions = g->executions,
        .validation_errors = g->validation_errors,
    };
    for (int i = 0; i < g->num_res; i++) {
        const fg_resource *r = &g->res[i];
        if (r->imported)
            s->imported_bytes += r->bytes;
        else if (r->first >= 0)
            s->transient_bytes += r->bytes;
        if (r->used_reported)
            s->used_bytes += r->used_bytes;
    }
    for (int k = 0; k < g->num_phys; k++)
        s->allocated_bytes += g->phys[k].desc.bytes;
    for (int pos = 0; pos < g->num_order; pos++) {
        size_t live = 0;
        for (int i = 0; i < g->num_res; i++) {
            const fg_resource *r = &g->res[i];
            if (!r->imported && r->first >= 0 && r->first <= pos && pos <= r->last)
                live += r->bytes;
        }
        if (live > s->live_peak_bytes)
            s->live_peak_bytes = live;
    }
    s->peak_bytes = s->allocated_bytes + s->imported_bytes;
    s->peak_bytes_no_alias = s->transient_bytes + s->imported_bytes;
    s->ms = -1;
    s->clock = DIRT_CLOCK_NONE;
    bool mixed = false;
    for (int i = 0; i < g->num_passes; i++) {
        const fg_pass_stats *p = &g->pstats[i];
        if (p->clock == DIRT_CLOCK_NONE)
            continue;
        if (s->clock == DIRT_CLOCK_NONE) {
            s->clock = p->clock;
            s->ms = 0;
        }
        mixed |= p->clock != s->clock;
        s->ms += p->ms;
    }
    if (mixed) {
        s->ms = -1;
        s->clock = DIRT_CLOCK_NONE;
    }
    return true;
}

/* "gpu", "cpu", "none" (also for values out of range). */
static const char *clock_name(enum dirt_clock c)
{
    return (unsigned)c < sizeof(dirt_clock_names) / sizeof(dirt_clock_names[0])
               ? dirt_clock_names[c]
               : dirt_clock_names[DIRT_CLOCK_NONE];
}

static double mib(size_t b)
{
    return (double)b / (1024.0 * 1024.0);
}

void fg_print_stats(const fg_graph *g, FILE *f)
{
    fg_stats s;
    if (!f)
        return;
    if (!fg_get_stats(g, &s)) {
        fprintf(f, "frame graph: not compiled\n");
        return;
    }
    fprintf(f, "frame graph: %d passes (%d culled), %d resources, %d allocations\n",
            s.num_passes, s.num_passes - g->num_order, s.num_resources, s.num_physical);
    fprintf(f, "  %-4s %-24s %-8s %-36s %10s %-5s\n", "pos", "pass", "kind", "barrier", "ms",
            "clock");
    for (int pos = 0; pos < g->num_order; pos++) {
        const fg_pass_stats *p = &s.passes[g->order[pos]];
        char bits[256];
        fprintf(f, "  %-4d %-24s %-8s %-36s %10.3f %-5s\n", pos, p->name,
                p->kind == FG_RASTER ? "raster" : "compute",
                fg_barrier_string(p->barrier, bits, sizeof(bits)), p->ms,
                clock_name(p->clock));
    }
    fprintf(f, "  %-24s %-8s %12s %12s %5s %9s\n", "resource", "kind", "MiB", "used MiB",
            "phys", "life");
    for (int i = 0; i < s.num_resources; i++) {
        const fg_res_stats *r = &s.resources[i];
        char life[32] = "-", used[32] = "-";
        if (r->first >= 0)
            snprintf(life, sizeof(life), "%d..%d", r->first, r->last);
        if (r->used_reported)
            snprintf(used, sizeof(used), "%.3f", mib(r->used_bytes));
        fprintf(f, "  %-24s %-8s %12.3f %12s %5d %9s%s\n", r->name,
                r->texture ? "texture" : "buffer", mib(r->bytes), used, r->physical, life,
                r->imported ? " imported" : r->culled ? " culled" : "");
    }
    fprintf(f, "  transient %.3f MiB, allocated %.3f MiB (aliasing saves %.3f MiB), live "
            "peak %.3f MiB, imported %.3f MiB, used %.3f MiB\n", mib(s.transient_bytes),
            mib(s.allocated_bytes), mib(s.transient_bytes - s.allocated_bytes),
            mib(s.live_peak_bytes), mib(s.imported_bytes), mib(s.used_bytes));
    fprintf(f, "  total %.3f ms (%s clock), %llu executions, %llu validation errors\n", s.ms,
            clock_name(s.clock), (unsigned long long)s.executions,
            (unsigned long long)s.validation_errors);
}

/* ---- DOT ----------------------------------------------------------------- */

typedef struct strbuf {
    char *data;
    size_t len, cap;
    bool failed;
} strbuf;

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void sb_printf(strbuf *b, const char *fmt, ...)
{
    if (b->failed)
        return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        size_t room = b->cap - b->len;
        int n = vsnprintf(b->data ? b->data + b->len : NULL, room, fmt, ap);
        va_end(ap);
        if (n < 0) {
            b->failed = true;
            return;
        }
        if ((size_t)n < room) {
            b->len += (size_t)n;
            return;
        }
        size_t cap = b->cap ? b->cap : 1024;
        while (cap < b->len + (size_t)n + 1)
            cap *= 2;
        char *d = realloc(b->data, cap);
        if (!d) {
            b->failed = true;
            return;
        }
        b->data = d;
        b->cap = cap;
    }
}

/* Name escaped for a quoted DOT string. */
static void sb_name(strbuf *b, const char *s)
{
    for (; *s; s++) {
        if (*s == '"' || *s == '\\')
            sb_printf(b, "\\%c", *s);
        else if (*s == '\n')
            sb_printf(b, "\\n");
        else
            sb_printf(b, "%c", *s);
    }
}

static const char *grey = ", style=filled, fillcolor=gray92, color=gray60, fontcolor=gray50";

char *fg_dot(const fg_graph *g)
{
    if (!g || !g->compiled) {
        DIRT_ERROR("frame graph: DOT export needs a compiled graph");
        return NULL;
    }
    strbuf b = {0};
    sb_printf(&b, "digraph frame_graph {\n  rankdir=LR;\n"
                  "  node [fontname=\"Helvetica\", fontsize=10];\n"
                  "  edge [fontname=\"Helvetica\", fontsize=9];\n");
    for (int i = 0; i < g->num_passes; i++) {
        const fg_pass *p = g->passes[i];
        const char *kind = p->kind == FG_RASTER ? "raster" : "compute";
        sb_printf(&b, "  p%d [shape=box%s, label=\"", i, p->live ? "" : grey);
        if (p->live)
            sb_printf(&b, "#%d ", p->position);
        sb_name(&b, p->name);
        sb_printf(&b, "\\n%s", kind);
        if (!p->live)
            sb_printf(&b, "\\nculled");
        else if (p->barrier) {
            char bits[256];
            sb_printf(&b, "\\nbarrier %s", fg_barrier_string(p->barrier, bits, sizeof(bits)));
        }
        sb_printf(&b, "\"];\n");
    }
    for (int i = 0; i < g->num_res; i++) {
        const fg_resource *r = &g->res[i];
        bool culled = r->first < 0;
        const char *style = culled ? grey : r->imported ? ", peripheries=2"
                                          : r->output ? ", style=bold" : "";
        sb_printf(&b, "  r%d [shape=ellipse%s, label=\"", i, style);
        sb_name(&b, r->name);
        if (r->texture) {
            sb_printf(&b, "\\n%s %dx%d", fg_format_name(r->tex.format), r->width, r->height);
            if (r->tex.array)
                sb_printf(&b, "[%d]", r->layers);
            if (r->levels > 1)
                sb_printf(&b, " mip%d", r->levels);
        } else {
            sb_printf(&b, "\\nbuffer");
        }
        sb_printf(&b, "\\n%zu B", r->bytes);
        if (r->imported)
            sb_printf(&b, "\\nimported");
        else if (culled)
            sb_printf(&b, "\\nculled");
        else
            sb_printf(&b, "\\nphys %d", r->physical);
        if (r->output)
            sb_printf(&b, ", output");
        sb_printf(&b, "\"];\n");
    }
    for (int i = 0; i < g->num_passes; i++) {
        const fg_pass *p = g->passes[i];
        for (int li = 0; li < g->num_links; li++) {
            const fg_link *l = &g->links[li];
            if (l->pass != i)
                continue;
            for (int a = 1; a < FG_ACCESS_COUNT; a++) {
                if (!(l->accesses & (1u << a)))
                    continue;
                bool rd = fg_access_reads((fg_access)a), wr = fg_access_writes((fg_access)a);
                if (wr)
                    sb_printf(&b, "  p%d -> r%d [label=\"%s\"%s%s];\n", i, l->res,
                              fg_access_name((fg_access)a), rd ? ", dir=both" : "",
                              p->live ? "" : ", color=gray60, fontcolor=gray50");
                else
                    sb_printf(&b, "  r%d -> p%d [label=\"%s\"%s];\n", l->res, i,
                              fg_access_name((fg_access)a),
                              p->live ? "" : ", color=gray60, fontcolor=gray50");
            }
        }
    }
    sb_printf(&b, "}\n");
    if (b.failed) {
        free(b.data);
        DIRT_ERROR("frame graph: out of memory writing DOT");
        return NULL;
    }
    return b.data;
}

bool fg_write_dot(const fg_graph *g, FILE *f)
{
    char *s = fg_dot(g);
    if (!s)
        return false;
    size_t n = strlen(s);
    bool ok = fwrite(s, 1, n, f) == n;
    free(s);
    if (!ok)
        DIRT_ERROR("frame graph: could not write DOT");
    return ok;
}

void fg_add_pass_times(const fg_graph *g, const char *const *names, int count, double *ms,
                       enum dirt_clock *clock)
{
    fg_stats s;
    if (!fg_get_stats(g, &s))
        return;
    for (int i = 0; i < s.num_passes; i++) {
        const fg_pass_stats *p = &s.passes[i];
        if (p->clock == DIRT_CLOCK_NONE)
            continue;
        if (*clock != DIRT_CLOCK_NONE && p->clock != *clock) {
            DIRT_ERROR("frame graph: pass '%s' measured by the %s clock, the others by the %s "
                       "clock; its time is left out", p->name, clock_name(p->clock),
                       clock_name(*clock));
            continue;
        }
        for (int k = 0; k < count; k++) {
            if (strcmp(p->name, names[k]) != 0)
                continue;
            ms[k] += p->ms;
            *clock = p->clock;
        }
    }
}
