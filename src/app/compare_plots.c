/* dirt-compare's figures from the rows (app/compare.h; doc/compare.md,
 * "Figures"): each figure is a grid of facets under one legend, drawn by
 * gnuplot from its own data file, one block per facet and series. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/cli.h"
#include "app/compare.h"
#include "dirt/types.h"

#define MAX_STYLES 64

typedef struct fig_point {
    char key[96]; /* what the point is of (a size, a scene, ...): one per series */
    double x, y, lo, hi;
} fig_point;

typedef struct fig_series {
    int style;
    int block;    /* its block in the data file (write_figure); -1: none */
    fig_point *p;
    int n, cap;
} fig_series;

typedef struct fig_facet {
    char title[240];
    fig_series *s;
    int n, cap;
} fig_facet;

/* A series' look, the same in every facet: its legend entry. */
typedef struct fig_style {
    char label[400];
    int color, point, dash; /* gnuplot line type, point type, dash type */
    int list;               /* style_of's point list (0: none) */
    bool parity;            /* the line y = 1, no points */
} fig_style;

typedef struct figure {
    const char *name, *title, *xlabel, *ylabel;
    bool logx, logy, bars;
    int categories;         /* n: x = 1..n named by xtics, the series spread around
                               them, points without lines; 0: x is a number */
    int cols;               /* facets per row (0: up to 3) */
    compare_buf xtics;      /* "'label' x, ..." or empty (gnuplot's own) */
    bool xtics_rotate;      /* many or long tic labels: upright */
    int xtics_len;          /* the longest tic label (characters) */
    fig_facet *f;
    int n, cap;
    fig_style st[MAX_STYLES];
    int nst;
} figure;

static void *grow(void *p, int *cap, int n, size_t size)
{
    if (n < *cap)
        return p;
    int c = *cap ? 2 * *cap : 8;
    void *q = realloc(p, (size_t)c * size);
    if (q)
        *cap = c;
    return q;
}

/* The style of `label` in `g`, made on first use (color < 0: the next
 * colour; point < 0: the next point type of the list -point, 1 DIRT's, 2
 * MMRT's); -1 when there are too many. */
static int style_of(figure *g, const char *label, int color, int point, int dash, bool parity)
{
    static const int dirt_points[] = {7, 6, 15, 14}, mmrt_points[] = {5, 9, 11, 13, 4, 8, 10, 12};
    for (int i = 0; i < g->nst; i++)
        if (!strcmp(g->st[i].label, label))
            return i;
    if (g->nst == MAX_STYLES)
        return -1;
    fig_style *s = &g->st[g->nst];
    snprintf(s->label, sizeof(s->label), "%s", label);
    int colors = 0;
    for (int i = 0; i < g->nst; i++)
        colors += !g->st[i].parity;
    s->color = color >= 0 ? color : colors + 1;
    if (point < 0) {
        int same = 0;
        for (int i = 0; i < g->nst; i++)
            same += g->st[i].list == -point;
        s->list = -point;
        point = point == -1 ? dirt_points[same % 4] : mmrt_points[same % 8];
    }
    s->point = point, s->dash = dash, s->parity = parity;
    return g->nst++;
}

/* The series of style `st` in the facet titled `title` (both made on first
 * use); NULL on out-of-memory or too many styles. */
static fig_series *series_in(figure *g, const char *title, int st)
{
    if (st < 0)
        return NULL;
    fig_facet *f = NULL;
    for (int i = 0; i < g->n && !f; i++)
        if (!strcmp(g->f[i].title, title))
            f = &g->f[i];
    if (!f) {
        fig_facet *nf = grow(g->f, &g->cap, g->n, sizeof(*g->f));
        if (!nf)
            return NULL;
        g->f = nf;
        f = &g->f[g->n++];
        memset(f, 0, sizeof(*f));
        snprintf(f->title, sizeof(f->title), "%s", title);
    }
    for (int i = 0; i < f->n; i++)
        if (f->s[i].style == st)
            return &f->s[i];
    fig_series *ns = grow(f->s, &f->cap, f->n, sizeof(*f->s));
    if (!ns)
        return NULL;
    f->s = ns;
    fig_series *s = &f->s[f->n++];
    memset(s, 0, sizeof(*s));
    s->style = st;
    return s;
}

/* Adds a point unless y is not a number or the series has one of that
 * key already (the first row's figure is kept: DIRT is measured again in
 * every row of MMRT's settings). Bars: [lo, hi], NAN for none (= y). */
static void add(fig_series *s, const char *key, double x, double y, double lo, double hi)
{
    if (!s || isnan(y) || isnan(x))
        return;
    for (int i = 0; i < s->n; i++)
        if (!strcmp(s->p[i].key, key))
            return;
    fig_point *np = grow(s->p, &s->cap, s->n, sizeof(*s->p));
    if (!np)
        return;
    s->p = np;
    fig_point *p = &s->p[s->n++];
    snprintf(p->key, sizeof(p->key), "%s", key);
    p->x = x, p->y = y;
    p->lo = isnan(lo) ? y : lo;
    p->hi = isnan(hi) ? y : hi;
}

static void figure_free(figure *g)
{
    for (int i = 0; i < g->n; i++) {
        for (int k = 0; k < g->f[i].n; k++)
            free(g->f[i].s[k].p);
        free(g->f[i].s);
    }
    free(g->f);
    free(g->xtics.p);
}

/* A facet is drawn when one of its series (the parity line aside) has two
 * points or more. */
static bool facet_drawn(const figure *g, const fig_facet *f)
{
    for (int k = 0; k < f->n; k++)
        if (!g->st[f->s[k].style].parity && f->s[k].n >= 2)
            return true;
    return false;
}

static int cmp_x(const void *a, const void *b)
{
    double x = ((const fig_point *)a)->x, y = ((const fig_point *)b)->x;
    return x < y ? -1 : x > y;
}

/* `s` as a single-quoted gnuplot string ('' is a quote). */
static void gp_str(compare_buf *b, const char *s)
{
    compare_bprintf(b, "'");
    for (; *s; s++)
        compare_bprintf(b, *s == '\'' ? "''" : "%c", *s);
    compare_bprintf(b, "'");
}

/* A name or label in the data file's block headers (tab-separated). */
static void dat_str(compare_buf *b, const char *s)
{
    for (; *s; s++)
        compare_bprintf(b, "%c", *s == '\t' || *s == '\n' ? ' ' : *s);
}

/* Labelled tics of a log axis over [lo, hi]: the coarsest of decades,
 * 1-2-5, 1-1.5-2-3-5-7 and 1..9 per decade that puts three tics in the
 * range (nothing when the range is not positive). */
static void log_tics(compare_buf *b, double lo, double hi)
{
    static const double m1[] = {1}, m125[] = {1, 2, 5}, m6[] = {1, 1.5, 2, 3, 5, 7},
                        m9[] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    static const struct { const double *m; int n; } sets[4] = {
        {m1, 1}, {m125, 3}, {m6, 6}, {m9, 9}};
    if (!(lo > 0) || !(hi >= lo) || !isfinite(hi))
        return;
    int e0 = (int)floor(log10(lo)), e1 = (int)ceil(log10(hi)), pick = 3;
    for (int k = 0; k < 4 && pick == 3; k++) {
        int count = 0;
        for (int e = e0; e <= e1; e++)
            for (int i = 0; i < sets[k].n; i++) {
                double t = sets[k].m[i] * pow(10, e);
                count += t >= lo * (1 - 1e-9) && t <= hi * (1 + 1e-9);
            }
        if (count >= 3)
            pick = k;
    }
    int n = 0;
    for (int e = e0; e <= e1; e++)
        for (int i = 0; i < sets[pick].n; i++) {
            double t = sets[pick].m[i] * pow(10, e);
            if (t >= lo * (1 - 1e-9) && t <= hi * (1 + 1e-9))
                compare_bprintf(b, "%s'%g' %.9g", n++ ? ", " : "", t, t);
        }
}

enum { CELL_W = 340, CELL_H = 260, TITLE_H = 34, KEY_ROW_H = 20, KEY_COL_W = 230 };

/* Appends figure `g` to the script `gp` (SVG and PNG) and writes its data
 * file; removes the files of an earlier run when it is not drawn. */
static bool write_figure(const char *prog, const char *dir, figure *g, compare_buf *gp)
{
    char path[1200], dat[64];
    snprintf(dat, sizeof(dat), "%s.dat", g->name);
    int drawn = 0;
    for (int i = 0; i < g->n; i++)
        drawn += facet_drawn(g, &g->f[i]);
    if (!drawn) {
        static const char *const ext[] = {".dat", ".svg", ".png"};
        for (int e = 0; e < 3; e++) {
            snprintf(path, sizeof(path), "%s/%s%s", dir, g->name, ext[e]);
            unlink(path);
        }
        return true;
    }
    /* The data: one block per drawn facet and series. */
    compare_buf d = {0};
    compare_bprintf(&d, "# dirt-compare figure %s (%s.svg, %s.png; drawn by plots.gp): %s\n"
                        "# x: %s; y: %s\n"
                        "# One block per facet and series, in gnuplot's index order, each after "
                        "a header line\n# \"# block<TAB>index<TAB>facet<TAB>series\"; columns: "
                        "x y y_min y_max (the bars; = y where there are none)\n",
                    g->name, g->name, g->name, g->title, g->xlabel, g->ylabel);
    int block = 0;
    for (int i = 0; i < g->n; i++) {
        fig_facet *f = &g->f[i];
        for (int k = 0; k < f->n; k++) {
            fig_series *s = &f->s[k];
            s->block = -1;
            if (!facet_drawn(g, f) || !s->n)
                continue;
            s->block = block;
            qsort(s->p, (size_t)s->n, sizeof(*s->p), cmp_x);
            compare_bprintf(&d, "%s# block\t%d\t", block ? "\n\n" : "", block);
            dat_str(&d, f->title);
            compare_bprintf(&d, "\t");
            dat_str(&d, g->st[s->style].label);
            compare_bprintf(&d, "\n");
            for (int p = 0; p < s->n; p++)
                compare_bprintf(&d, "%.9g %.9g %.9g %.9g\n", s->p[p].x, s->p[p].y, s->p[p].lo,
                                s->p[p].hi);
            block++;
        }
    }
    if (!compare_write_buf(prog, dir, dat, &d))
        return false;
    char dpath[1200];
    snprintf(dpath, sizeof(dpath), "%s/%s", dir, dat);
    /* The layout: the legend's rows, then the facets' grid. */
    int cols = g->cols ? g->cols : drawn < 3 ? drawn : 3;
    if (cols > drawn)
        cols = drawn;
    int rows = (drawn + cols - 1) / cols;
    int cell_w = cols * CELL_W < 720 ? 720 / cols : CELL_W;
    int width = cols * cell_w;
    int key_cols = width / KEY_COL_W < 1 ? 1 : width / KEY_COL_W;
    if (key_cols > g->nst)
        key_cols = g->nst;
    int key_rows = (g->nst + key_cols - 1) / key_cols;
    int key_h = key_rows * KEY_ROW_H + 12;
    /* room for upright tic labels: about 6 pixels a character at 8 points */
    int label_h = g->xtics_rotate ? 6 * g->xtics_len + 6 : 0;
    int cell_h = CELL_H + label_h;
    int height = TITLE_H + key_h + rows * cell_h;
    for (int t = 0; t < 2; t++) {
        compare_bprintf(gp, "\n# %s\nreset\nset terminal %s noenhanced size %d,%d "
                            "font 'sans,9'%s\n",
                        g->name, t ? "pngcairo" : "svg", width, height,
                        t ? "" : " background '#ffffff'");
        /* colours that stay apart in print and for colour-blind readers */
        static const char *const palette[8] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                               "#e69f00", "#56b4e9", "#999999", "#882255"};
        compare_bprintf(gp, "set for [i=1:8] linetype i lc rgb word('");
        for (int k = 0; k < 8; k++)
            compare_bprintf(gp, "%s%s", k ? " " : "", palette[k]);
        compare_bprintf(gp, "', i) lw 1.3\nset output ");
        snprintf(path, sizeof(path), "%s/%s.%s", dir, g->name, t ? "png" : "svg");
        gp_str(gp, path);
        compare_bprintf(gp, "\nset multiplot title ");
        gp_str(gp, g->title);
        /* the legend: every style, once */
        compare_bprintf(gp, "\nunset border\nunset tics\nset xrange [0:1]\nset yrange [0:1]\n"
                            "set key center center horizontal maxcols %d samplen 2.5 "
                            "reverse Left width 1 noautotitle\nset origin 0,%.6f\n"
                            "set size 1,%.6f\n"
                            "set lmargin 0\nset rmargin 0\nset tmargin 0\nset bmargin 0\nplot ",
                        key_cols, (double)(rows * cell_h) / height, (double)key_h / height);
        /* DIRT's series first, then the others, the parity line last */
        for (int pass = 0, n = 0; pass < 3; pass++)
            for (int k = 0; k < g->nst; k++) {
                const fig_style *s = &g->st[k];
                if ((pass == 0) != (s->list == 1) || (pass == 2) != s->parity)
                    continue;
                compare_bprintf(gp, "%sNaN w %s lc %s%d dt %d", n++ ? ", " : "",
                                s->parity ? "l" : g->categories ? "p" : "lp",
                                s->parity ? "rgb 'black' lt " : "",
                                s->parity ? 1 : s->color, s->dash);
                if (!s->parity)
                    compare_bprintf(gp, " pt %d ps 0.8", s->point);
                compare_bprintf(gp, " t ");
                gp_str(gp, s->label);
            }
        /* the facets: axes fitted to their points (and a margin) */
        compare_bprintf(gp, "\nset border\nset tics\nset key off\nset grid\nset autoscale\n"
                            "set autoscale fix\n"
                            "unset lmargin\nunset rmargin\nunset tmargin\nunset bmargin\n"
                            "set offsets graph %s, graph %s, graph 0.08, graph 0.08\n"
                            "set format y '%%g'\n%s\n%s\n",
                        g->categories ? "0" : "0.08", g->categories ? "0" : "0.08",
                        g->logx ? "set logscale x" : "unset logscale x",
                        g->logy ? "set logscale y" : "unset logscale y");
        if (g->categories) /* the series spread around each category */
            compare_bprintf(gp, "set xrange [0.5:%d.5]\n", g->categories);
        if (g->xtics.n)
            compare_bprintf(gp, "set xtics (%s)%s\n", g->xtics.p,
                            g->xtics_rotate ? " rotate by 90 right font ',8'" : "");
        int cell = 0;
        for (int i = 0; i < g->n; i++) {
            fig_facet *f = &g->f[i];
            if (!facet_drawn(g, f))
                continue;
            int r = cell / cols, c = cell % cols;
            cell++;
            compare_bprintf(gp, "set origin %.6f,%.6f\nset size %.6f,%.6f\nset title ",
                            (double)(c * cell_w) / width,
                            (double)((rows - 1 - r) * cell_h) / height,
                            (double)cell_w / width, (double)cell_h / height);
            gp_str(gp, f->title);
            /* axis labels on the left column and under each column's last */
            compare_bprintf(gp, "\nset ylabel ");
            gp_str(gp, c == 0 ? g->ylabel : "");
            compare_bprintf(gp, "\nset xlabel ");
            /* under upright tic labels gnuplot misplaces the axis label: the
             * tics name the points and the title says what x is */
            gp_str(gp, cell + cols > drawn && !label_h ? g->xlabel : "");
            if (label_h) /* gnuplot's own margin overestimates upright labels */
                compare_bprintf(gp, "\nset bmargin at screen %.6f",
                                (double)((rows - 1 - r) * cell_h + label_h + 16) / height);
            if (g->logy) { /* labelled tics however narrow the range */
                double lo = INFINITY, hi = -INFINITY;
                for (int k = 0; k < f->n; k++)
                    for (int p = 0; p < f->s[k].n; p++) {
                        const fig_point *q = &f->s[k].p[p];
                        lo = fmin(lo, fmin(q->y, q->lo));
                        hi = fmax(hi, fmax(q->y, q->hi));
                    }
                double m = lo > 0 ? pow(hi / lo, 0.08) : 1; /* the offsets */
                compare_buf yt = {0};
                log_tics(&yt, lo / m, hi * m);
                if (yt.n)
                    compare_bprintf(gp, "\nset ytics (%s)", yt.p);
                else
                    compare_bprintf(gp, "\nset ytics autofreq");
                free(yt.p);
            }
            compare_bprintf(gp, "\nplot ");
            int visible = 0;
            for (int k = 0; k < f->n; k++)
                visible += !g->st[f->s[k].style].parity && f->s[k].block >= 0;
            int v = 0, plotted = 0;
            for (int k = 0; k < f->n; k++) {
                const fig_style *s = &g->st[f->s[k].style];
                if (f->s[k].block < 0)
                    continue;
                compare_bprintf(gp, "%s", plotted++ ? ", " : "");
                gp_str(gp, dpath);
                compare_bprintf(gp, " index %d ", f->s[k].block);
                if (s->parity) {
                    compare_bprintf(gp, "u 1:2 w l lc rgb 'black' dt %d notitle", s->dash);
                    continue;
                }
                double off = 0;
                if (g->categories && visible > 1)
                    off = (v - (visible - 1) / 2.0) * (0.7 / visible);
                v++;
                compare_bprintf(gp, "u ($1%+.4f):2:3:4 w %s lc %d dt %d pt %d ps 0.8 notitle",
                                off, g->categories ? "yerrorbars" : g->bars ? "yerrorlines" : "lp",
                                s->color, s->dash, s->point);
            }
            compare_bprintf(gp, "\n");
        }
        compare_bprintf(gp, "unset multiplot\nset output\n");
    }
    return true;
}

/* ---- the figures from the rows ---- */

/* Which settings vary among the rows measured (they then name series). */
typedef struct varies {
    bool tile, dbuckets, mbuckets, views, spp, bounces, time, march;
} varies;

static void march_str(const cJSON *r, char *out, size_t n)
{
    if (!strcmp(compare_js(r, "settings.mmrt_march"), "linear"))
        snprintf(out, n, "linear %.0f", compare_jd(r, "settings.mmrt_samples"));
    else
        snprintf(out, n, "%s", compare_js(r, "settings.mmrt_march"));
}

static void find_varies(const cJSON *rows, varies *v)
{
    const cJSON *first = NULL, *r;
    memset(v, 0, sizeof(*v));
    cJSON_ArrayForEach(r, rows)
    {
        if (!compare_row_ok(r))
            continue;
        if (!first) {
            first = r;
            continue;
        }
#define VARY(f, path) v->f |= compare_jd(r, path) != compare_jd(first, path)
        VARY(tile, "settings.dirt_tile_size");
        VARY(dbuckets, "settings.dirt_buckets");
        VARY(mbuckets, "settings.mmrt_buckets");
        VARY(spp, "settings.spp");
        VARY(bounces, "settings.bounces");
        VARY(time, "settings.time");
#undef VARY
        v->views |= strcmp(compare_js(r, "settings.views"), compare_js(first, "settings.views"));
        char a[32], b[32];
        march_str(r, a, sizeof(a));
        march_str(first, b, sizeof(b));
        v->march |= strcmp(a, b) != 0;
    }
}

/* The settings that vary, other than the techniques': " cube 4 spp". */
static void common_str(const cJSON *r, const varies *v, bool light_transport, char *out,
                       size_t n)
{
    out[0] = 0;
    size_t k = 0;
    if (v->views)
        k += (size_t)snprintf(out + k, n - k, " %s", compare_js(r, "settings.views"));
    if (v->time && k < n)
        k += (size_t)snprintf(out + k, n - k, " t %g s", compare_jd(r, "settings.time"));
    if (light_transport && v->spp && k < n)
        k += (size_t)snprintf(out + k, n - k, " %g spp", compare_jd(r, "settings.spp"));
    if (light_transport && v->bounces && k < n)
        snprintf(out + k, n - k, " %g bounces", compare_jd(r, "settings.bounces"));
}

/* "DIRT S2 B4" (the parts that vary); `light_transport`: spp and bounces
 * count (times, images), else only the structure's settings (memory). */
static void dirt_label(const cJSON *r, const varies *v, bool light_transport, char *out,
                       size_t n)
{
    char s[32] = "", b[32] = "", c[96];
    if (v->tile)
        snprintf(s, sizeof(s), " S%g", compare_jd(r, "settings.dirt_tile_size"));
    if (v->dbuckets)
        snprintf(b, sizeof(b), " B%g", compare_jd(r, "settings.dirt_buckets"));
    common_str(r, v, light_transport, c, sizeof(c));
    snprintf(out, n, "DIRT%s%s%s", s, b, c);
}

/* "th 0.2 %" (of the scene's diagonal) or "th default (0.2 %)". */
static void thickness_str(const cJSON *r, char *out, size_t n)
{
    if (cJSON_IsTrue(compare_jget(r, "settings.mmrt_thickness_default")))
        snprintf(out, n, "th default (0.2 %%)");
    else
        snprintf(out, n, "th %.2g %%", 100 * compare_jd(r, "settings.mmrt_thickness") /
                                           compare_jd(r, "scene.diagonal"));
}

/* "MMRT B8 th 0.2 % linear 30": the thickness and march only where they
 * count (`trace`: not for memory). */
static void mmrt_label(const cJSON *r, const varies *v, bool trace, bool thickness, char *out,
                       size_t n)
{
    char b[32] = "", th[48] = "", m[48] = "", c[96];
    if (v->mbuckets)
        snprintf(b, sizeof(b), " B%g", compare_jd(r, "settings.mmrt_buckets"));
    if (trace && thickness) {
        th[0] = ' ';
        thickness_str(r, th + 1, sizeof(th) - 1);
    }
    if (trace && v->march) {
        m[0] = ' ';
        march_str(r, m + 1, sizeof(m) - 1);
    }
    common_str(r, v, trace, c, sizeof(c));
    snprintf(out, n, "MMRT%s%s%s%s", b, th, m, c);
}

static void scene_title(const cJSON *r, char *out, size_t n)
{
    snprintf(out, n, "%s (%.0f triangles)", compare_js(r, "scene.name"),
             compare_jd(r, "scene.triangles"));
}

static void size_str(const cJSON *r, char *out, size_t n)
{
    snprintf(out, n, "%.0fx%.0f", compare_jd(r, "settings.width"),
             compare_jd(r, "settings.height"));
}

/* Adds "'label' x" to the x tics unless a tic at x (to 1e-5, the rounding
 * of a thickness in float) is there ("a / b" when two labels share an x). */
typedef struct tic {
    double x;
    char label[200];
} tic;

static void add_tic(tic *t, int *n, int max, double x, const char *label)
{
    for (int i = 0; i < *n; i++) {
        if (fabs(t[i].x - x) > 1e-5 * fabs(x))
            continue;
        if (!strstr(t[i].label, label)) {
            size_t k = strlen(t[i].label);
            snprintf(t[i].label + k, sizeof(t[i].label) - k, " / %s", label);
        }
        return;
    }
    if (*n < max) {
        t[*n].x = x;
        snprintf(t[*n].label, sizeof(t[*n].label), "%s", label);
        (*n)++;
    }
}

static void tics_str(figure *g, const tic *t, int n)
{
    compare_buf *b = &g->xtics;
    for (int i = 0; i < n; i++) {
        int len = (int)strlen(t[i].label);
        g->xtics_len = len > g->xtics_len ? len : g->xtics_len;
        compare_bprintf(b, "%s", i ? ", " : "");
        gp_str(b, t[i].label);
        compare_bprintf(b, " %.9g", t[i].x);
    }
}

static double mb(double bytes)
{
    return bytes / 1048576.0;
}

static const char *const quantity[3] = {"build", "trace", "frame"};

/* memory_vs_X and time_vs_X: X the image's pixels (facets per scene) or
 * the scene's triangles (facets per image size). */
static void scaling_figures(const cJSON *rows, const varies *v, bool by_size, figure *mem,
                            figure *time)
{
    tic t[64];
    int nt = 0;
    const cJSON *r;
    cJSON_ArrayForEach(r, rows)
    {
        if (!compare_row_ok(r))
            continue;
        char ft[240], key[96], sz[32], dl[160], ml[160], mlm[160];
        size_str(r, sz, sizeof(sz));
        double x;
        if (by_size) {
            scene_title(r, ft, sizeof(ft));
            x = compare_jd(r, "settings.width") * compare_jd(r, "settings.height");
            snprintf(key, sizeof(key), "%s", sz);
            add_tic(t, &nt, 64, x, sz);
        } else {
            snprintf(ft, sizeof(ft), "%s", sz);
            x = compare_jd(r, "scene.triangles");
            snprintf(key, sizeof(key), "%.90s", compare_js(r, "scene.path"));
            char name[160];
            snprintf(name, sizeof(name), "%.120s (%.0f)", compare_js(r, "scene.name"), x);
            add_tic(t, &nt, 64, x, name);
        }
        /* memory: the structure's settings only */
        dirt_label(r, v, false, dl, sizeof(dl));
        mmrt_label(r, v, false, false, mlm, sizeof(mlm));
        add(series_in(mem, ft, style_of(mem, dl, -1, -1, 1, false)), key, x,
            mb(compare_jd(r, "dirt.memory.structure_used")), NAN, NAN);
        add(series_in(mem, ft, style_of(mem, mlm, -1, -2, 1, false)), key, x,
            mb(compare_jd(r, "mmrt.memory.structure_used")), NAN, NAN);
        /* times: a row of facets per scene (size), one per quantity */
        dirt_label(r, v, true, dl, sizeof(dl));
        mmrt_label(r, v, true, true, ml, sizeof(ml));
        for (int q = 0; q < 3; q++) {
            char qt[300], p[64];
            snprintf(qt, sizeof(qt), "%s: %s", ft, quantity[q]);
            for (int e = 0; e < 2; e++) {
                const char *tech = e ? "mmrt" : "dirt";
                int st = e ? style_of(time, ml, -1, -2, 1, false)
                           : style_of(time, dl, -1, -1, 1, false);
                double y, lo, hi;
                snprintf(p, sizeof(p), "%s.%s.median_ms", tech, quantity[q]);
                y = compare_jd(r, p);
                snprintf(p, sizeof(p), "%s.%s.min_ms", tech, quantity[q]);
                lo = compare_jd(r, p);
                snprintf(p, sizeof(p), "%s.%s.max_ms", tech, quantity[q]);
                hi = compare_jd(r, p);
                add(series_in(time, qt, st), key, x, y, lo, hi);
            }
        }
    }
    tics_str(mem, t, nt);
    tics_str(time, t, nt);
    mem->xtics_rotate = time->xtics_rotate = !by_size || nt > 4;
}

/* Facets per scene and size: the sizes side by side when there are 2 to 4
 * of them (one scene a row), else 0 (the default). */
static int size_columns(const cJSON *rows)
{
    char sizes[4][32];
    int ns = 0;
    const cJSON *r;
    cJSON_ArrayForEach(r, rows)
    {
        char sz[32];
        bool seen = false;
        size_str(r, sz, sizeof(sz));
        for (int k = 0; k < ns && !seen; k++)
            seen = !strcmp(sizes[k], sz);
        if (!seen && ns == 4)
            return 0;
        if (!seen)
            snprintf(sizes[ns++], sizeof(sizes[0]), "%s", sz);
    }
    return ns > 1 ? ns : 0;
}

/* ratios_per_scene: per scene and size, DIRT / MMRT of each quantity. */
static void ratio_figure(const cJSON *rows, const varies *v, figure *g)
{
    static const char *const cat[5] = {"entries", "memory", "build", "trace", "frame"};
    const cJSON *r;
    cJSON_ArrayForEach(r, rows)
    {
        if (!compare_row_ok(r))
            continue;
        char ft[300], st[400], sz[32], dl[160], ml[160], sc[240];
        scene_title(r, sc, sizeof(sc));
        size_str(r, sz, sizeof(sz));
        snprintf(ft, sizeof(ft), "%s, %s", sc, sz);
        dirt_label(r, v, true, dl, sizeof(dl));
        mmrt_label(r, v, true, true, ml, sizeof(ml));
        snprintf(st, sizeof(st), "%s / %s", dl, ml);
        fig_series *s = series_in(g, ft, style_of(g, st, -1, -2, 1, false));
        for (int k = 0; k < 5; k++) {
            char p[64];
            snprintf(p, sizeof(p), "ratios.%s", k ? cat[k] : "records");
            double y = compare_jd(r, p), lo = NAN, hi = NAN;
            if (k >= 2) { /* the repeats' extremes: min / max, max / min */
                char a[64], b[64];
                snprintf(a, sizeof(a), "dirt.%s.min_ms", cat[k]);
                snprintf(b, sizeof(b), "mmrt.%s.max_ms", cat[k]);
                lo = compare_jd(r, a) / compare_jd(r, b);
                snprintf(a, sizeof(a), "dirt.%s.max_ms", cat[k]);
                snprintf(b, sizeof(b), "mmrt.%s.min_ms", cat[k]);
                hi = compare_jd(r, a) / compare_jd(r, b);
            }
            add(s, cat[k], k + 1, y, lo, hi);
        }
        fig_series *par = series_in(g, ft, style_of(g, "parity: DIRT = MMRT", 0, 0, 2, true));
        add(par, "left", 0.5, 1, NAN, NAN);
        add(par, "right", 5.5, 1, NAN, NAN);
    }
    for (int k = 0; k < 5; k++)
        compare_bprintf(&g->xtics, "%s'%s' %d", k ? ", " : "", cat[k], k + 1);
    g->cols = size_columns(rows);
}

/* agreement_vs_thickness: per scene and size, MMRT's agreement per ray
 * type over its thickness (DIRT's does not depend on it: table.md). */
static void agreement_figure(const cJSON *rows, const varies *v, figure *g)
{
    tic tics[64];
    int nt = 0;
    const cJSON *r;
    cJSON_ArrayForEach(r, rows)
    {
        if (!compare_row_ok(r) || !compare_jget(r, "mmrt.agreement"))
            continue;
        char ft[300], sz[32], sc[240], ml[160], key[48];
        scene_title(r, sc, sizeof(sc));
        size_str(r, sz, sizeof(sz));
        snprintf(ft, sizeof(ft), "%s, %s", sc, sz);
        mmrt_label(r, v, true, false, ml, sizeof(ml));
        double x = 100 * compare_jd(r, "mmrt.thickness_used") / compare_jd(r, "scene.diagonal");
        snprintf(key, sizeof(key), "%.9g", compare_jd(r, "mmrt.thickness_used"));
        char tl[32];
        snprintf(tl, sizeof(tl), "%.2g", x);
        add_tic(tics, &nt, 64, x, tl);
        for (int t = 0; t < DIRT_RAY_TYPES; t++) {
            char label[200], p[96];
            snprintf(label, sizeof(label), "%s %s", ml, dirt_ray_type_names[t]);
            snprintf(p, sizeof(p), "mmrt.agreement.fraction.%s", dirt_ray_type_names[t]);
            add(series_in(g, ft, style_of(g, label, t + 1, -2, 1, false)), key, x,
                100 * compare_jd(r, p), NAN, NAN);
        }
    }
    tics_str(g, tics, nt);
    g->xtics_rotate = nt > 6;
    g->cols = size_columns(rows);
}

bool compare_write_plots(const char *prog, const char *dir, const cJSON *doc)
{
    const cJSON *rows = compare_jget(doc, "configurations");
    varies v;
    find_varies(rows, &v);
    figure fig[6] = {
        {.name = "memory_vs_resolution", .title = "Structure memory vs image size, per scene",
         .xlabel = "image size (pixels, log)", .ylabel = "used MB (log)", .logx = true,
         .logy = true},
        {.name = "time_vs_resolution", .title = "Times vs image size, per scene: the build, "
         "the trace passes, the whole frame (medians; bars: min-max of the repeats)",
         .xlabel = "image size (pixels, log)", .ylabel = "ms (log)", .logx = true,
         .logy = true, .bars = true, .cols = 3},
        {.name = "memory_vs_triangles", .title = "Structure memory vs the scenes' triangles "
         "(log), per image size",
         .xlabel = "scene (triangles, log)", .ylabel = "used MB (log)", .logx = true,
         .logy = true},
        {.name = "time_vs_triangles", .title = "Times vs the scenes' triangles (log), per image "
         "size: the build, the trace passes, the whole frame (medians; bars: min-max of the "
         "repeats)",
         .xlabel = "scene (triangles, log)", .ylabel = "ms (log)", .logx = true, .logy = true,
         .bars = true, .cols = 3},
        {.name = "ratios_per_scene", .title = "DIRT / MMRT per scene and image size (below "
         "1: DIRT's is smaller or faster; bars: the repeats' extremes)",
         .xlabel = "", .ylabel = "DIRT / MMRT (log)", .logy = true, .bars = true,
         .categories = 5},
        {.name = "agreement_vs_thickness", .title = "MMRT's hit agreement with Embree vs its "
         "thickness, per scene and image size",
         .xlabel = "MMRT thickness (% of the scene's diagonal, log)",
         .ylabel = "rays agreeing with Embree (%)", .logx = true},
    };
    scaling_figures(rows, &v, true, &fig[0], &fig[1]);
    scaling_figures(rows, &v, false, &fig[2], &fig[3]);
    ratio_figure(rows, &v, &fig[4]);
    agreement_figure(rows, &v, &fig[5]);
    compare_buf gp = {0};
    compare_bprintf(&gp, "# dirt-compare's figures: gnuplot %s/plots.gp (data: NAME.dat)\n", dir);
    bool ok = true;
    int drawn = 0;
    for (int i = 0; i < 6; i++) {
        size_t before = gp.n;
        ok = write_figure(prog, dir, &fig[i], &gp) && ok;
        drawn += gp.n > before;
        figure_free(&fig[i]);
    }
    char old[1100]; /* the single data file of earlier versions */
    snprintf(old, sizeof(old), "%s/plot.dat", dir);
    unlink(old);
    if (!ok || !compare_write_buf(prog, dir, "plots.gp", &gp))
        return false;
    if (!drawn)
        return true;
    char cmd[2400];
    snprintf(cmd, sizeof(cmd), "gnuplot '%s/plots.gp' 2>'%s/plots.log'", dir, dir);
    int st = system(cmd);
    if (st != 0) {
        cli_error(prog, "gnuplot failed (exit %d; is gnuplot-nox installed? see %s/plots.log)",
                  st, dir);
        return false;
    }
    return true;
}
