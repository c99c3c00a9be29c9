/* The programs' one option table (src/app/options.c, programs.c): every
 * entry well formed; the choice names those of the library; per program no
 * spelling twice, every accepted option in its --help with its default,
 * every default parsing to what the program starts from; every range's
 * ends accepted and just past them refused, in every program that takes
 * the option (one range); lists, sizes in bytes, frames and the shared
 * checks; the shell quoting of the provenance's command line. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/options.h"
#include "app/provenance.h"
#include "app/setup.h"
#include "check.h"
#include "dirt/gpu.h"

static const app_program *const programs[] = {&app_render_program, &app_view_program,
                                              &app_compare_program};
#define NUM_PROGRAMS 3

static int names_len(const char *const *n)
{
    int i = 0;
    while (n[i])
        i++;
    return i;
}

static void test_table(void)
{
    for (int id = APP_OPT_NONE + 1; id < APP_NUM_OPTS; id++) {
        const app_opt_def *d = app_opt_table((enum app_opt)id);
        CHECK_MSG(d && d->id == (enum app_opt)id, "entry %d", id);
        if (!d)
            continue;
        CHECK_MSG(d->l && d->l[0] == '-' && d->l[1] == '-' && d->l[2], "entry %d's name", id);
        CHECK_MSG(d->help && d->help[0], "%s has no help", d->l);
        CHECK_MSG((d->kind == 'F') == (d->meta == NULL), "%s: a flag has no value", d->l);
        CHECK_MSG(strchr("Filufdcspbvx zTRP", d->kind) != NULL, "%s: kind %c", d->l, d->kind);
        CHECK_MSG((d->kind == 'c' || d->kind == 'p') == (d->names != NULL), "%s's names", d->l);
        CHECK_MSG(!(d->dflt && d->note), "%s: a default value or a note, not both", d->l);
    }
    /* The choices are the library's own lists. */
    CHECK(names_len(app_engine_names) == DIRT_NUM_ENGINES);
    for (int e = 0; e < DIRT_NUM_ENGINES; e++)
        CHECK(!strcmp(app_engine_names[e], dirt_engine_names[e]));
    CHECK(names_len(app_compare_names) == DIRT_NUM_ENGINES + 1);
    for (int e = 0; e < DIRT_NUM_ENGINES; e++)
        CHECK(!strcmp(app_compare_names[e + 1], dirt_engine_names[e]));
    const char *const *gpu = app_opt_table(APP_OPT_GPU)->names;
    for (int i = 0; i < 3; i++)
        CHECK(gpu[i] && dirt_gpu_platform_names[i] && !strcmp(gpu[i], dirt_gpu_platform_names[i]));
    CHECK(!strcmp(app_views_names[DIRT_SESSION_VIEWS_CUBE_CAMERA], "cube+camera"));
    CHECK(!strcmp(app_build_names[DIRT_SESSION_BUILD_COMPUTE], "compute"));
    CHECK(!strcmp(app_fetch_names[DIRT_FETCH_RASTER], "raster"));
    CHECK(!strcmp(app_march_names[DIRT_MMRT_MARCH_LINEAR], "linear"));
    CHECK(!strcmp(app_mode_names[DIRT_PT_AO], "ao"));
}

/* Calls fn(program, use) for every option the program accepts. */
#define FOR_USES(p, u) \
    for (const app_section *sec_ = (p)->sections; sec_->title; sec_++) \
        for (const app_use *u = sec_->uses; u->id != APP_OPT_NONE; u++)

static char *help_of(const app_program *p)
{
    char *buf = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&buf, &size);
    app_print_help(p, f);
    fclose(f);
    return buf;
}

/* `text` holds `word` followed by a space, a comma or the end of a line. */
static bool has_word(const char *text, const char *word)
{
    size_t n = strlen(word);
    for (const char *at = strstr(text, word); at; at = strstr(at + 1, word)) {
        char before = at == text ? ' ' : at[-1], after = at[n];
        if ((before == ' ' || before == '\n') && (after == ' ' || after == ',' || after == '\n'))
            return true;
    }
    return false;
}

static void test_programs(void)
{
    static app_opts o, o2;
    for (int pi = 0; pi < NUM_PROGRAMS; pi++) {
        const app_program *p = programs[pi];
        char *help = help_of(p);
        /* No spelling twice. */
        const char *seen[3 * APP_NUM_OPTS];
        int n = 0;
        FOR_USES(p, u) {
            const app_opt_def *d = app_opt_table(u->id);
            const char *sp[3] = {d->s, d->l, d->alias};
            for (int k = 0; k < 3; k++) {
                for (int j = 0; sp[k] && j < n; j++)
                    CHECK_MSG(strcmp(seen[j], sp[k]), "%s takes %s twice", p->name, sp[k]);
                if (sp[k])
                    seen[n++] = sp[k];
            }
            /* In the help, with its value's name and its default. */
            CHECK_MSG(has_word(help, d->l), "%s --help lacks %s", p->name, d->l);
            CHECK_MSG(!d->s || has_word(help, d->s), "%s --help lacks %s", p->name, d->s);
            CHECK_MSG(!d->alias || has_word(help, d->alias), "%s --help lacks %s", p->name,
                      d->alias);
            const char *dflt = u->note ? u->note : u->dflt ? u->dflt : d->note ? d->note : d->dflt;
            if (dflt && dflt[0]) {
                char want[256];
                snprintf(want, sizeof(want), "(default %s", dflt);
                /* The help wraps lines: compare with its spaces and breaks
                 * folded. */
                char *flat = strdup(help);
                for (char *c = flat, *w = flat; ; c++) {
                    if (*c == '\n' || *c == ' ') {
                        while (c[1] == ' ' || c[1] == '\n')
                            c++;
                        *w++ = ' ';
                    } else if (!(*w++ = *c)) {
                        break;
                    }
                }
                CHECK_MSG(strstr(flat, want) != NULL, "%s --help: %s lacks '%s'", p->name, d->l,
                          want);
                free(flat);
            }
        }
        free(help);
        /* Every default parses to what the program starts from: giving it
         * changes nothing. */
        app_opts_init(p, &o);
        FOR_USES(p, u) {
            const app_opt_def *d = app_opt_table(u->id);
            const char *v = u->dflt ? u->dflt : d->dflt;
            if (!v || !v[0])
                continue;
            o2 = o;
            CHECK_MSG(app_set(p, d->l + 2, v, 0, &o2), "%s %s %s", p->name, d->l, v);
            o2.given[u->id] = false;
            CHECK_MSG(!memcmp(&o, &o2, sizeof(o)), "%s: %s %s is not its default", p->name,
                      d->l, v);
        }
        app_opts_free(&o);
    }
}

/* The ends of every numeric range are accepted and values just past them
 * refused, in every program that takes the option. */
static void test_ranges(void)
{
    static app_opts o;
    int checked = 0;
    for (int pi = 0; pi < NUM_PROGRAMS; pi++) {
        const app_program *p = programs[pi];
        FOR_USES(p, u) {
            const app_opt_def *d = app_opt_table(u->id);
            char lo[64], hi[64], below[64], above[64];
            switch (d->kind) {
            case 'i':
            case 'l':
            case 'u':
            case 'z':
                snprintf(lo, sizeof(lo), "%.0f", d->lo);
                snprintf(hi, sizeof(hi), "%.0f", d->hi);
                snprintf(below, sizeof(below), "%.0f", d->lo - 1);
                snprintf(above, sizeof(above), "%.0f", d->hi + 1);
                break;
            case 'f':
            case 'd':
                snprintf(lo, sizeof(lo), "%.17g", d->lo);
                snprintf(hi, sizeof(hi), "%.17g", d->hi);
                snprintf(below, sizeof(below), "%.17g", d->lo - 1e-6 * (d->lo ? d->lo : 1));
                snprintf(above, sizeof(above), "%.17g", d->hi + 1e-6 * d->hi);
                if (d->lo < 0)
                    snprintf(below, sizeof(below), "%.17g", d->lo * (1 + 1e-6));
                break;
            case 'x':
                snprintf(lo, sizeof(lo), "%.0fx%.0f", d->lo, d->lo);
                snprintf(hi, sizeof(hi), "%.0fx%.0f", d->hi, d->hi);
                snprintf(below, sizeof(below), "%.0fx%.0f", d->lo - 1, d->lo);
                snprintf(above, sizeof(above), "%.0fx%.0f", d->hi, d->hi + 1);
                break;
            case 'T':
                snprintf(lo, sizeof(lo), "1");
                snprintf(hi, sizeof(hi), "8");
                snprintf(below, sizeof(below), "3"); /* not a power of two */
                snprintf(above, sizeof(above), "16");
                break;
            default:
                continue;
            }
            const char *name = d->l + 2;
            app_opts_init(p, &o);
            CHECK_MSG(app_set(p, name, lo, 0, &o), "%s %s %s refused", p->name, d->l, lo);
            CHECK_MSG(app_set(p, name, hi, 0, &o), "%s %s %s refused", p->name, d->l, hi);
            CHECK_MSG(!app_set(p, name, below, 0, &o), "%s %s %s taken", p->name, d->l, below);
            CHECK_MSG(!app_set(p, name, above, 0, &o), "%s %s %s taken", p->name, d->l, above);
            app_opts_free(&o);
            checked++;
        }
    }
    CHECK(checked > 60);
}

static void test_values(void)
{
    static app_opts o;
    const app_program *r = &app_render_program, *c = &app_compare_program;
    app_opts_init(r, &o);
    /* --max-scene-memory: the default, suffixes in powers of 1024. */
    CHECK(o.max_scene_bytes == DIRT_LOAD_DEFAULT_MAX_BYTES);
    CHECK(app_set(r, "max-scene-memory", "1K", 0, &o) && o.max_scene_bytes == 1024);
    CHECK(app_set(r, "max-scene-memory", "3m", 0, &o) && o.max_scene_bytes == 3u << 20);
    CHECK(app_set(r, "max-scene-memory", "2G", 0, &o) && o.max_scene_bytes == (size_t)2 << 30);
    CHECK(app_set(r, "max-scene-memory", "1.5K", 0, &o) && o.max_scene_bytes == 1536);
    CHECK(app_set(r, "max-scene-memory", "12345", 0, &o) && o.max_scene_bytes == 12345);
    CHECK(!app_set(r, "max-scene-memory", "0.5", 0, &o));
    CHECK(!app_set(r, "max-scene-memory", "5X", 0, &o));
    CHECK(!app_set(r, "max-scene-memory", "1KB", 0, &o));
    CHECK(!app_set(r, "max-scene-memory", "", 0, &o));
    /* The loader's and the environment's options: one budget for both. */
    CHECK(app_set(r, "max-scene-memory", "3m", 0, &o));
    CHECK(!o.strict && !o.allow_outside_paths);
    dirt_load_opts lo = app_load_opts(&o);
    CHECK(lo.max_bytes == 3u << 20 && !lo.strict && !lo.allow_outside);
    CHECK(app_set(r, "strict", "on", 0, &o) && app_set(r, "allow-outside-paths", "on", 0, &o));
    lo = app_load_opts(&o);
    CHECK(lo.strict && lo.allow_outside);
    CHECK(app_env_opts(&o).max_bytes == 3u << 20);
    /* In every program; never from a dirt-view script (a load's rules are
     * the command line's). */
    for (int i = 0; i < 3; i++) {
        const app_program *p = i == 0 ? r : i == 1 ? c : &app_view_program;
        CHECK_MSG(app_find(p, "strict", 0) == APP_OPT_STRICT, "%s --strict", p->name);
        CHECK_MSG(app_find(p, "allow-outside-paths", 0) == APP_OPT_ALLOW_OUTSIDE_PATHS,
                  "%s --allow-outside-paths", p->name);
    }
    CHECK(app_find(&app_view_program, "strict", APP_USE_RUNTIME) == APP_OPT_NONE);
    CHECK(app_find(&app_view_program, "allow-outside-paths", APP_USE_RUNTIME) == APP_OPT_NONE);
    /* The session options they set, with the table's mappings. */
    CHECK(app_set(r, "hiz-top", "2", 0, &o) && app_session_opts(&o).hiz_levels == 3);
    CHECK(app_set(r, "large", "0", 0, &o) && app_session_opts(&o).large < 0);
    CHECK(app_set(r, "large", "5", 0, &o) && app_session_opts(&o).large == 5);
    CHECK(app_set(r, "engine", "mmrt", 0, &o) && o.s.engine == DIRT_ENGINE_MMRT);
    CHECK(!app_set(r, "engine", "optix", 0, &o));
    CHECK(app_set(r, "tile-size", "4", 0, &o) && o.s.tile_size == 4);
    CHECK(app_set(r, "face", "32", 0, &o) && o.s.face_size == 32);
    CHECK(app_set(r, "stats", "s.json", 0, &o) && !app_set(r, "stats", "s.txt", 0, &o));
    CHECK(!app_set(r, "window", "64x64", 0, &o)); /* dirt-view's */
    app_opts_free(&o);
    /* Lists: each item as the single value; the default list replaced. */
    app_opts_init(c, &o);
    CHECK(o.lists[APP_OPT_TILE].n == 1 && o.lists[APP_OPT_TILE].v[0][0] == 1);
    CHECK(o.lists[APP_OPT_SPP].n == 1 && o.lists[APP_OPT_SPP].v[0][0] == 1);
    CHECK(o.s.seed == 7);
    CHECK(app_set(c, "tile", "2,4,8", 0, &o) && o.lists[APP_OPT_TILE].n == 3 &&
          o.lists[APP_OPT_TILE].v[2][0] == 8);
    CHECK(!app_set(c, "tile", "2,3", 0, &o));
    CHECK(app_set(c, "res", "32x24,48x36", 0, &o) && o.lists[APP_OPT_RES].n == 2 &&
          o.lists[APP_OPT_RES].v[1][0] == 48 && o.lists[APP_OPT_RES].v[1][1] == 36);
    CHECK(!app_set(c, "res", "64x", 0, &o));
    CHECK(app_set(c, "views", "single,cube", 0, &o) &&
          o.lists[APP_OPT_VIEWS].v[1][0] == DIRT_SESSION_VIEWS_CUBE);
    CHECK(!app_set(c, "spp", "1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17", 0, &o));
    CHECK(!app_set(c, "engine", "dirt", 0, &o)); /* dirt-compare measures both */
    app_opts_free(&o);
    /* The command line: scenes, flags, unknown options, missing values. */
    app_opts_init(r, &o);
    char *ok_args[] = {"dirt-render", "scene.glb", "-o", "x.exr", "--png", "-W", "32",
                       "--frames", "1,3-4", NULL};
    CHECK(app_parse(r, 9, ok_args, &o) == APP_PARSE_OK);
    CHECK(o.num_scenes == 1 && !strcmp(o.scenes[0], "scene.glb") && o.png && o.s.width == 32);
    CHECK(o.frames.count == 3 && o.frames.frames[2] == 4 && o.given[APP_OPT_FRAMES]);
    app_opts_free(&o);
    char *bad1[] = {"dirt-render", "--bogus", NULL};
    char *bad2[] = {"dirt-render", "-W", NULL};
    char *bad3[] = {"dirt-render", "a.glb", "b.glb", NULL};
    char *const *bads[] = {bad1, bad2, bad3};
    int bad_argc[] = {2, 2, 3};
    for (int i = 0; i < 3; i++) {
        app_opts_init(r, &o);
        CHECK_MSG(app_parse(r, bad_argc[i], (char **)bads[i], &o) == APP_PARSE_USAGE, "bad %d",
                  i);
        app_opts_free(&o);
    }
    /* The shared checks. */
    app_opts_init(r, &o);
    CHECK(app_check(r, &o));
    CHECK(app_set(r, "eye", "0,1,2", 0, &o) && !app_check(r, &o)); /* no --look-at */
    CHECK(app_set(r, "look-at", "0,0,0", 0, &o) && app_check(r, &o));
    CHECK(app_camera_choice(&o) == DIRT_CAMERA_EXPLICIT);
    CHECK(app_set(r, "camera", "0", 0, &o) && !app_check(r, &o));
    app_opts_free(&o);
    app_opts_init(r, &o);
    CHECK(app_set(r, "env-intensity", "2", 0, &o) && !app_check(r, &o)); /* no --env */
    CHECK(app_set(r, "env", "sky", 0, &o) && app_check(r, &o));
    CHECK(app_set(r, "background", "1,1,1", 0, &o) && !app_check(r, &o)); /* two environments */
    app_opts_free(&o);
    app_opts_init(r, &o);
    CHECK(app_set(r, "engine", "mmrt", 0, &o) && app_set(r, "fetch", "raster", 0, &o) &&
          !app_check(r, &o)); /* the session's own check */
    app_opts_free(&o);
}

static void test_quote(void)
{
    char buf[128];
    size_t n = 0;
    const char *args[] = {"dirt-render", "a b.glb", "it's", "-o", "f_####.exr", ""};
    for (int i = 0; i < 6; i++)
        n = app_shell_quote(buf, sizeof(buf), n, args[i]);
    CHECK_MSG(!strcmp(buf, "dirt-render 'a b.glb' 'it'\\''s' -o 'f_####.exr' ''"), "%s", buf);
    char small[8];
    n = app_shell_quote(small, sizeof(small), 0, "abcdefghijkl");
    CHECK(n == sizeof(small) && strlen(small) == sizeof(small) - 1);
}

int main(void)
{
    test_table();
    test_programs();
    test_ranges();
    test_values();
    test_quote();
    return check_finish();
}
