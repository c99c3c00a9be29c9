/* Frame graph barriers without GL: the access-pair table, the bits derived
 * per pass (including aliasing and hazards carried across executes), and
 * execution on a recording fake backend with the run-time validation that
 * must catch a dropped barrier. */
#include <GL/glcorearb.h> /* constants only: the bits must equal GL's */
#include <string.h>

#include "check.h"
#include "dirt/log.h"
#include "graph/graph.h"

/* ---- log capture ---------------------------------------------------------- */

static char log_text[16384];

static void capture(void *user, enum dirt_log_level level, const char *file, int line,
                    const char *msg)
{
    (void)user;
    (void)file;
    (void)line;
    if (level > DIRT_LOG_WARN)
        return;
    size_t len = strlen(log_text);
    snprintf(log_text + len, sizeof(log_text) - len, "%s\n", msg);
}

static bool logged(const char *sub)
{
    return strstr(log_text, sub) != NULL;
}

/* ---- the table ------------------------------------------------------------ */

static void test_table(void)
{
    /* the bit values are GL's */
    CHECK(FG_BARRIER_VERTEX_ATTRIB_ARRAY == GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    CHECK(FG_BARRIER_ELEMENT_ARRAY == GL_ELEMENT_ARRAY_BARRIER_BIT);
    CHECK(FG_BARRIER_UNIFORM == GL_UNIFORM_BARRIER_BIT);
    CHECK(FG_BARRIER_TEXTURE_FETCH == GL_TEXTURE_FETCH_BARRIER_BIT);
    CHECK(FG_BARRIER_SHADER_IMAGE_ACCESS == GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    CHECK(FG_BARRIER_COMMAND == GL_COMMAND_BARRIER_BIT);
    CHECK(FG_BARRIER_TEXTURE_UPDATE == GL_TEXTURE_UPDATE_BARRIER_BIT);
    CHECK(FG_BARRIER_BUFFER_UPDATE == GL_BUFFER_UPDATE_BARRIER_BIT);
    CHECK(FG_BARRIER_FRAMEBUFFER == GL_FRAMEBUFFER_BARRIER_BIT);
    CHECK(FG_BARRIER_ATOMIC_COUNTER == GL_ATOMIC_COUNTER_BARRIER_BIT);
    CHECK(FG_BARRIER_SHADER_STORAGE == GL_SHADER_STORAGE_BARRIER_BIT);

    /* the pairs named in the design, one by one */
    CHECK(fg_barrier_bits(FG_IMAGE_STORE, FG_IMAGE_LOAD, true) ==
          GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_SSBO_WRITE, FG_SSBO_READ, false) == GL_SHADER_STORAGE_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_SSBO_WRITE, FG_VERTEX, false) == GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_SSBO_WRITE, FG_INDEX, false) == GL_ELEMENT_ARRAY_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_SSBO_WRITE, FG_INDIRECT, false) == GL_COMMAND_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_IMAGE_STORE, FG_SAMPLED, true) == GL_TEXTURE_FETCH_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_IMAGE_STORE, FG_COLOR, true) == GL_FRAMEBUFFER_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_IMAGE_ATOMIC, FG_DEPTH, true) == GL_FRAMEBUFFER_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_ATOMIC_COUNTER, FG_ATOMIC_COUNTER, false) ==
          GL_ATOMIC_COUNTER_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_ATOMIC_COUNTER, FG_SSBO_READ, false) ==
          GL_SHADER_STORAGE_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_IMAGE_STORE, FG_TRANSFER_READ, true) ==
          GL_TEXTURE_UPDATE_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_SSBO_WRITE, FG_TRANSFER_READ, false) ==
          GL_BUFFER_UPDATE_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_SSBO_WRITE, FG_UNIFORM, false) == GL_UNIFORM_BARRIER_BIT);
    /* framebuffer writes are not shader stores: GL orders them itself */
    CHECK(fg_barrier_bits(FG_COLOR, FG_SAMPLED, true) == 0);
    CHECK(fg_barrier_bits(FG_COLOR, FG_IMAGE_LOAD, true) == 0);
    CHECK(fg_barrier_bits(FG_COLOR, FG_COLOR, true) == 0);
    CHECK(fg_barrier_bits(FG_DEPTH, FG_SAMPLED, true) == 0);
    CHECK(fg_barrier_bits(FG_TRANSFER_WRITE, FG_SSBO_READ, false) == 0);
    /* write after read: a later shader store waits for earlier accesses */
    CHECK(fg_barrier_bits(FG_SAMPLED, FG_IMAGE_STORE, true) ==
          GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_VERTEX, FG_SSBO_WRITE, false) == GL_SHADER_STORAGE_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_COLOR, FG_IMAGE_STORE, true) == GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    CHECK(fg_barrier_bits(FG_SSBO_READ, FG_COLOR, true) == 0);

    /* the whole matrix: the consumer bit of the later access when either
     * side is an incoherent shader write, else nothing */
    static const uint32_t consumer[FG_ACCESS_COUNT][2] = { /* [buffer, texture] */
        [FG_SAMPLED] = {0, GL_TEXTURE_FETCH_BARRIER_BIT},
        [FG_IMAGE_LOAD] = {0, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT},
        [FG_IMAGE_STORE] = {0, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT},
        [FG_IMAGE_ATOMIC] = {0, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT},
        [FG_SSBO_READ] = {GL_SHADER_STORAGE_BARRIER_BIT, 0},
        [FG_SSBO_WRITE] = {GL_SHADER_STORAGE_BARRIER_BIT, 0},
        [FG_ATOMIC_COUNTER] = {GL_ATOMIC_COUNTER_BARRIER_BIT, 0},
        [FG_UNIFORM] = {GL_UNIFORM_BARRIER_BIT, 0},
        [FG_VERTEX] = {GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT, 0},
        [FG_INDEX] = {GL_ELEMENT_ARRAY_BARRIER_BIT, 0},
        [FG_INDIRECT] = {GL_COMMAND_BARRIER_BIT, 0},
        [FG_COLOR] = {0, GL_FRAMEBUFFER_BARRIER_BIT},
        [FG_DEPTH] = {0, GL_FRAMEBUFFER_BARRIER_BIT},
        [FG_TRANSFER_READ] = {GL_BUFFER_UPDATE_BARRIER_BIT, GL_TEXTURE_UPDATE_BARRIER_BIT},
        [FG_TRANSFER_WRITE] = {GL_BUFFER_UPDATE_BARRIER_BIT, GL_TEXTURE_UPDATE_BARRIER_BIT},
    };
    static const bool shader_write[FG_ACCESS_COUNT] = {
        [FG_IMAGE_STORE] = true, [FG_IMAGE_ATOMIC] = true, [FG_SSBO_WRITE] = true,
        [FG_ATOMIC_COUNTER] = true,
    };
    for (int e = 1; e < FG_ACCESS_COUNT; e++) {
        CHECK(fg_access_shader_write((fg_access)e) == shader_write[e]);
        for (int l = 1; l < FG_ACCESS_COUNT; l++) {
            for (int tex = 0; tex < 2; tex++) {
                uint32_t want = consumer[l][tex];
                if (!want)
                    continue; /* access not valid on this resource kind */
                if (!shader_write[e] && !shader_write[l])
                    want = 0;
                CHECK_MSG(fg_barrier_bits((fg_access)e, (fg_access)l, tex) == want,
                          "%s -> %s (%s)", fg_access_name((fg_access)e),
                          fg_access_name((fg_access)l), tex ? "texture" : "buffer");
            }
        }
    }
    CHECK(fg_barrier_bits(FG_ACCESS_NONE, FG_SSBO_READ, false) == 0);
    char s[128];
    CHECK(strcmp(fg_barrier_string(GL_SHADER_STORAGE_BARRIER_BIT |
                                   GL_TEXTURE_FETCH_BARRIER_BIT, s, sizeof(s)),
                 "TEXTURE_FETCH|SHADER_STORAGE") == 0);
    CHECK(strcmp(fg_barrier_string(0, s, sizeof(s)), "-") == 0);
    CHECK(strcmp(fg_barrier_name(GL_COMMAND_BARRIER_BIT), "GL_COMMAND_BARRIER_BIT") == 0);
    CHECK(fg_barrier_name(3) == NULL);
}

/* ---- bits derived per pass --------------------------------------------- */

typedef struct pair_case {
    fg_access earlier, later;
    bool texture;
    fg_pass_kind later_kind;
    uint32_t want;      /* bits before the later pass */
} pair_case;

/* Graph: [init (transfer write) ->] first (earlier) -> second (later); both
 * kept. Returns the bits before `second`. */
static uint32_t pair_bits(const pair_case *c)
{
    fg_graph *g = fg_create(NULL);
    fg_set_resolution(g, 4, 4);
    fg_res r = c->texture
        ? fg_texture(g, "r", &(fg_tex_desc){.format = FG_RGBA8, .width = 4, .height = 4})
        : fg_buffer(g, "r", &(fg_buf_desc){.bytes = 256});
    bool first_raster = c->earlier == FG_COLOR || c->earlier == FG_DEPTH;
    if (fg_access_reads(c->earlier)) {
        fg_pass *init = fg_add_pass(g, "init", FG_COMPUTE, NULL, NULL);
        fg_write(init, r, FG_TRANSFER_WRITE);
    }
    fg_pass *first = fg_add_pass(g, "first", first_raster ? FG_RASTER : FG_COMPUTE, NULL, NULL);
    fg_use(first, r, c->earlier, NULL);
    fg_keep(first);
    fg_pass *second = fg_add_pass(g, "second", c->later_kind, NULL, NULL);
    fg_use(second, r, c->later, NULL);
    fg_keep(second);
    uint32_t bits = 0xdeadbeef;
    if (fg_compile(g))
        bits = fg_pass_barrier(g, "second");
    else
        fprintf(stderr, "compile failed: %s\n", fg_last_error(g));
    fg_destroy(g);
    return bits;
}

static void test_pass_bits(void)
{
    static const pair_case cases[] = {
        {FG_SSBO_WRITE, FG_SSBO_READ, false, FG_COMPUTE, GL_SHADER_STORAGE_BARRIER_BIT},
        {FG_IMAGE_STORE, FG_IMAGE_LOAD, true, FG_COMPUTE, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT},
        {FG_IMAGE_STORE, FG_SAMPLED, true, FG_RASTER, GL_TEXTURE_FETCH_BARRIER_BIT},
        {FG_SSBO_WRITE, FG_VERTEX, false, FG_RASTER, GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT},
        {FG_SSBO_WRITE, FG_INDEX, false, FG_RASTER, GL_ELEMENT_ARRAY_BARRIER_BIT},
        {FG_SSBO_WRITE, FG_INDIRECT, false, FG_COMPUTE, GL_COMMAND_BARRIER_BIT},
        {FG_SSBO_WRITE, FG_UNIFORM, false, FG_COMPUTE, GL_UNIFORM_BARRIER_BIT},
        {FG_IMAGE_STORE, FG_COLOR, true, FG_RASTER, GL_FRAMEBUFFER_BARRIER_BIT},
        {FG_IMAGE_STORE, FG_TRANSFER_READ, true, FG_COMPUTE, GL_TEXTURE_UPDATE_BARRIER_BIT},
        {FG_SSBO_WRITE, FG_TRANSFER_READ, false, FG_COMPUTE, GL_BUFFER_UPDATE_BARRIER_BIT},
        {FG_ATOMIC_COUNTER, FG_ATOMIC_COUNTER, false, FG_COMPUTE,
         GL_ATOMIC_COUNTER_BARRIER_BIT},
        /* raster -> raster through the framebuffer: nothing */
        {FG_COLOR, FG_SAMPLED, true, FG_RASTER, 0},
        {FG_COLOR, FG_COLOR, true, FG_RASTER, 0},
        {FG_COLOR, FG_IMAGE_LOAD, true, FG_COMPUTE, 0},
        {FG_TRANSFER_WRITE, FG_SSBO_READ, false, FG_COMPUTE, 0},
        /* write after read */
        {FG_SAMPLED, FG_IMAGE_STORE, true, FG_COMPUTE, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT},
        {FG_SSBO_READ, FG_SSBO_WRITE, false, FG_COMPUTE, GL_SHADER_STORAGE_BARRIER_BIT},
        /* a buffer read as a texel buffer (split arrays, gl/split.h): the
         * texture accesses' bits, a buffer's for transfers */
        {FG_IMAGE_STORE, FG_IMAGE_LOAD, false, FG_COMPUTE, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT},
        {FG_IMAGE_STORE, FG_SAMPLED, false, FG_RASTER, GL_TEXTURE_FETCH_BARRIER_BIT},
        {FG_IMAGE_STORE, FG_TRANSFER_READ, false, FG_COMPUTE, GL_BUFFER_UPDATE_BARRIER_BIT},
        {FG_IMAGE_ATOMIC, FG_SSBO_READ, false, FG_COMPUTE, GL_SHADER_STORAGE_BARRIER_BIT},
        {FG_TRANSFER_WRITE, FG_SAMPLED, false, FG_COMPUTE, 0},
    };
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        uint32_t got = pair_bits(&cases[i]);
        CHECK_MSG(got == cases[i].want, "%s -> %s: got 0x%x want 0x%x",
                  fg_access_name(cases[i].earlier), fg_access_name(cases[i].later), got,
                  cases[i].want);
    }

    /* a bit issued once covers later readers: only the first reader pays */
    fg_graph *g = fg_create(NULL);
    fg_res b = fg_buffer(g, "b", &(fg_buf_desc){.bytes = 64});
    fg_res t = fg_texture(g, "t", &(fg_tex_desc){.format = FG_R32F, .width = 2, .height = 2});
    fg_pass *w = fg_add_pass(g, "w", FG_COMPUTE, NULL, NULL);
    fg_write(w, b, FG_SSBO_WRITE);
    fg_write(w, t, FG_IMAGE_STORE);
    fg_pass *r1 = fg_add_pass(g, "r1", FG_COMPUTE, NULL, NULL);
    fg_read(r1, b, FG_SSBO_READ);
    fg_read(r1, t, FG_SAMPLED);
    fg_keep(r1);
    fg_pass *r2 = fg_add_pass(g, "r2", FG_COMPUTE, NULL, NULL);
    fg_read(r2, b, FG_SSBO_READ);
    fg_read(r2, t, FG_IMAGE_LOAD);
    fg_keep(r2);
    CHECK(fg_compile(g));
    CHECK(fg_pass_barrier(g, "r1") ==
          (GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT));
    CHECK(fg_pass_barrier(g, "r2") == GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    /* steady state: w overwrites what r1/r2 read in the previous execute */
    CHECK(fg_pass_barrier(g, "w") ==
          (GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
    fg_destroy(g);

    /* loop-carried: an imported accumulation image written at the end of an
     * execute is read at the start of the next */
    g = fg_create(NULL);
    fg_res acc = fg_import_texture(g, "accum", 9, &(fg_tex_desc){.format = FG_RGBA32F,
                                                                 .width = 4, .height = 4});
    fg_res out = fg_import_texture(g, "display", 10, &(fg_tex_desc){.format = FG_RGBA8,
                                                                    .width = 4, .height = 4});
    fg_pass *show = fg_add_pass(g, "show", FG_RASTER, NULL, NULL);
    fg_read(show, acc, FG_SAMPLED);
    fg_write(show, out, FG_COLOR);
    fg_pass *add = fg_add_pass(g, "accumulate", FG_COMPUTE, NULL, NULL);
    fg_read(add, acc, FG_IMAGE_LOAD);
    fg_write(add, acc, FG_IMAGE_STORE);
    CHECK(fg_compile(g));
    CHECK(fg_position(g, "show") == 0 && fg_position(g, "accumulate") == 1);
    CHECK(fg_pass_barrier(g, "show") == GL_TEXTURE_FETCH_BARRIER_BIT);
    CHECK(fg_pass_barrier(g, "accumulate") == GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    fg_destroy(g);

    /* shared imports: written outside between executes, so each one's first
     * access gets its bit (a clear, a transfer, pays for what shaders wrote),
     * later accesses only what the graph's own writes need */
    for (int shared = 0; shared < 2; shared++) {
        g = fg_create(NULL);
        fg_res in = fg_import_buffer(g, "in", 5, 64);
        fg_res lists = fg_import_buffer(g, "lists", 6, 64);
        fg_res tex = fg_import_texture(g, "tex", 7, &(fg_tex_desc){.format = FG_R32F,
                                                                    .width = 2, .height = 2});
        fg_pass *clear = fg_add_pass(g, "clear", FG_COMPUTE, NULL, NULL);
        fg_write(clear, lists, FG_TRANSFER_WRITE);
        fg_pass *fill = fg_add_pass(g, "fill", FG_COMPUTE, NULL, NULL);
        fg_read(fill, in, FG_SSBO_READ);
        fg_read(fill, tex, FG_SAMPLED);
        fg_use(fill, lists, FG_SSBO_READ, NULL);
        fg_write(fill, lists, FG_SSBO_WRITE);
        fg_pass *again = fg_add_pass(g, "again", FG_COMPUTE, NULL, NULL);
        fg_read(again, in, FG_SSBO_READ);
        fg_read(again, lists, FG_SSBO_READ);
        fg_keep(again);
        fg_set_shared_imports(g, shared);
        CHECK(fg_compile(g));
        if (shared) {
            CHECK(fg_pass_barrier(g, "clear") == GL_BUFFER_UPDATE_BARRIER_BIT);
            CHECK(fg_pass_barrier(g, "fill") ==
                  (GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT));
        } else {
            /* the graph's own steady state: the last execute's fill wrote
             * the lists the clear overwrites; nothing wrote `in` or `tex` */
            CHECK(fg_pass_barrier(g, "clear") == GL_BUFFER_UPDATE_BARRIER_BIT);
            CHECK(fg_pass_barrier(g, "fill") == GL_SHADER_STORAGE_BARRIER_BIT);
        }
        CHECK(fg_pass_barrier(g, "again") == GL_SHADER_STORAGE_BARRIER_BIT);
        fg_destroy(g);
    }
}

/* Graph whose second resource reuses the first one's memory. */
static fg_graph *alias_graph(bool aliasing, fg_backend *backend)
{
    fg_graph *g = fg_create(backend);
    fg_set_aliasing(g, aliasing);
    fg_res x = fg_buffer(g, "x", &(fg_buf_desc){.bytes = 1000});
    fg_res y = fg_buffer(g, "y", &(fg_buf_desc){.bytes = 1000});
    fg_res out1 = fg_import_buffer(g, "out1", 501, 64);
    fg_res out2 = fg_import_buffer(g, "out2", 502, 64);
    fg_pass *p1 = fg_add_pass(g, "p1", FG_COMPUTE, NULL, NULL);
    fg_write(p1, x, FG_SSBO_WRITE);
    fg_pass *p2 = fg_add_pass(g, "p2", FG_COMPUTE, NULL, NULL);
    fg_read(p2, x, FG_SSBO_READ);
    fg_write(p2, out1, FG_SSBO_WRITE);
    fg_pass *p3 = fg_add_pass(g, "p3", FG_COMPUTE, NULL, NULL);
    fg_write(p3, y, FG_TRANSFER_WRITE);
    fg_pass *p4 = fg_add_pass(g, "p4", FG_COMPUTE, NULL, NULL);
    fg_read(p4, y, FG_SSBO_READ);
    fg_write(p4, out2, FG_SSBO_WRITE);
    return g;
}

/* The clear of y reuses x's memory, which p1 wrote with a shader: with
 * aliasing the clear needs BUFFER_UPDATE, on its own memory it needs nothing. */
static void test_alias_bits(void)
{
    fg_graph *g = alias_graph(true, NULL);
    CHECK(fg_compile(g));
    CHECK(fg_num_physical(g) == 1);
    CHECK(fg_pass_barrier(g, "p3") == GL_BUFFER_UPDATE_BARRIER_BIT);
    CHECK(fg_pass_barrier(g, "p2") == GL_SHADER_STORAGE_BARRIER_BIT);
    CHECK(fg_pass_barrier(g, "p4") == 0);
    fg_destroy(g);
    g = alias_graph(false, NULL);
    CHECK(fg_compile(g));
    CHECK(fg_num_physical(g) == 2);
    CHECK(fg_pass_barrier(g, "p3") == 0);
    CHECK(fg_pass_barrier(g, "p4") == 0);
    fg_destroy(g);
}

/* ---- execution on a fake backend -------------------------------------------- */

typedef struct fake {
    uint32_t next_name;
    int creates, destroys, live;
    int begins, ends;
    char events[4096];
    bool released;
    uint32_t names_seen[16][2];  /* per pass index: names of its first two bindings */
    /* end_pass reports 0.5 ms per timed pass, measured by `clock`
     * (DIRT_CLOCK_NONE: the GPU clock); the pass of declaration index
     * odd_pass - 1 (none when 0) by odd_clock (a broken backend). */
    enum dirt_clock clock;
    int odd_pass;
    enum dirt_clock odd_clock;
    /* asynchronous ends (p->async): each leaves one 0.25 ms time in flight
     * for the pass, which fake_drain gives (or forgets) */
    int asyncs;
    int in_flight[16];
} fake;

static void ev(fake *f, const char *fmt, const char *a, unsigned x)
{
    size_t len = strlen(f->events);
    snprintf(f->events + len, sizeof(f->events) - len, fmt, a, x);
}

static uint32_t fake_create(void *self, const fg_phys_desc *d)
{
    fake *f = self;
    f->creates++;
    f->live++;
    (void)d;
    return f->next_name++;
}

static void fake_destroy(void *self, const fg_phys_desc *d, uint32_t name)
{
    fake *f = self;
    (void)d;
    (void)name;
    f->destroys++;
    f->live--;
}

static void fake_barrier(void *self, uint32_t bits)
{
    char s[256];
    ev(self, "barrier %s;", fg_barrier_string(bits, s, sizeof(s)), 0);
}

static bool fake_begin(void *self, const fg_pass_info *p)
{
    fake *f = self;
    f->begins++;
    ev(f, "%s@%u;", p->name, (unsigned)p->position);
    for (int i = 0; i < p->num_bindings && i < 2; i++) {
        if (p->index < 16)
            f->names_seen[p->index][i] = p->bindings[i].name;
    }
    return true;
}

static bool fake_end(void *self, const fg_pass_info *p, double *ms, enum dirt_clock *clock)
{
    fake *f = self;
    f->ends++;
    if (!p->timed)
        return true; /* the graph preset -1 and DIRT_CLOCK_NONE */
    *ms = 0.5;
    *clock = f->clock == DIRT_CLOCK_NONE ? DIRT_CLOCK_GPU : f->clock;
    if (p->async) {
        f->asyncs++;
        if (p->index < 16)
            f->in_flight[p->index]++;
    }
    if (f->odd_pass == p->index + 1)
        *clock = f->odd_clock;
    return true;
}

static void fake_release(void *self)
{
    ((fake *)self)->released = true;
}

static void fake_drain(void *self, int index, bool discard, double *ms, enum dirt_clock *clock)
{
    fake *f = self;
    if (index >= 16 || !f->in_flight[index])
        return;
    if (!discard) {
        *ms = 0.25 * f->in_flight[index];
        *clock = DIRT_CLOCK_GPU;
    }
    f->in_flight[index] = 0;
}

static const fg_backend_ops fake_ops = {
    fake_create, fake_destroy, fake_barrier, fake_begin, fake_end, fake_release,
};

static const fg_backend_ops fake_async_ops = {
    fake_create, fake_destroy, fake_barrier, fake_begin, fake_end, fake_release, fake_drain,
};

typedef struct demo {
    fg_res values, img, target, undeclared;
    bool fail_draw;
    bool peek_undeclared;
    uint32_t seen_values_name;
} demo;

static bool exec_fill(fg_ctx *ctx, void *user)
{
    demo *d = user;
    d->seen_values_name = fg_name(ctx, d->values);
    fg_report_used(ctx, d->values, 100);
    if (d->peek_undeclared)
        fg_name(ctx, d->undeclared);
    return true;
}

static bool exec_draw(fg_ctx *ctx, void *user)
{
    demo *d = user;
    int w = 0, h = 0;
    CHECK(fg_texture_size(ctx, d->target, &w, &h, NULL, NULL) && w == 8 && h == 4);
    CHECK(fg_declares(ctx, d->img, FG_SAMPLED) && !fg_declares(ctx, d->img, FG_IMAGE_LOAD));
    return !d->fail_draw;
}

/* fill -> to_image -> draw -> readback, the GPU test's graph. */
static fg_graph *demo_graph(fake *f, demo *d)
{
    fg_backend b = {&fake_ops, f};
    fg_graph *g = fg_create(&b);
    fg_set_resolution(g, 8, 4);
    d->values = fg_buffer(g, "values", &(fg_buf_desc){.per_pixel = 4});
    d->img = fg_texture(g, "img", &(fg_tex_desc){.format = FG_R32F});
    d->target = fg_texture(g, "target", &(fg_tex_desc){.format = FG_RGBA32F});
    d->undeclared = fg_buffer(g, "unrelated", &(fg_buf_desc){.bytes = 16});
    fg_pass *fill = fg_add_pass(g, "fill", FG_COMPUTE, exec_fill, d);
    fg_use(fill, d->values, FG_SSBO_WRITE, &(fg_use_opts){.bind = true, .binding = 0});
    fg_pass *conv = fg_add_pass(g, "to_image", FG_COMPUTE, NULL, d);
    fg_use(conv, d->values, FG_SSBO_READ, &(fg_use_opts){.bind = true, .binding = 0});
    fg_use(conv, d->img, FG_IMAGE_STORE, &(fg_use_opts){.bind = true, .binding = 0});
    fg_pass *draw = fg_add_pass(g, "draw", FG_RASTER, exec_draw, d);
    fg_use(draw, d->img, FG_SAMPLED, &(fg_use_opts){.bind = true, .binding = 0});
    fg_write(draw, d->target, FG_COLOR);
    fg_pass *rb = fg_add_pass(g, "readback", FG_COMPUTE, NULL, d);
    fg_read(rb, d->target, FG_TRANSFER_READ);
    fg_keep(rb);
    return g;
}

static void test_execute(void)
{
    fake f = {.next_name = 100};
    demo d = {0};
    fg_graph *g = demo_graph(&f, &d);
    CHECK(fg_compile(g));
    CHECK(fg_pass_barrier(g, "fill") == GL_SHADER_STORAGE_BARRIER_BIT);
    CHECK(fg_pass_barrier(g, "to_image") ==
          (GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
    CHECK(fg_pass_barrier(g, "draw") == GL_TEXTURE_FETCH_BARRIER_BIT);
    CHECK(fg_pass_barrier(g, "readback") == 0);

    fg_exec_opts vopts = {.validate = true};
    log_text[0] = '\0';
    CHECK(fg_execute(g, &vopts));
    /* the first execute after a compile starts with one full barrier */
    char want[1024], all[256];
    snprintf(want, sizeof(want), "barrier %s;barrier SHADER_STORAGE;fill@0;"
             "barrier SHADER_IMAGE_ACCESS|SHADER_STORAGE;to_image@1;"
             "barrier TEXTURE_FETCH;draw@2;readback@3;",
             fg_barrier_string(FG_BARRIER_ALL, all, sizeof(all)));
    CHECK_MSG(strcmp(f.events, want) == 0, "events: %s", f.events);
    f.events[0] = '\0';
    CHECK(fg_execute(g, &vopts));
    CHECK_MSG(strcmp(f.events, want + strlen("barrier ;") + strlen(all)) == 0, "events: %s",
              f.events);
    CHECK(f.creates == 3 && f.live == 3);
    CHECK(d.seen_values_name == f.names_seen[0][0] && d.seen_values_name >= 100);
    CHECK(!logged("validation"));
    CHECK(fg_execute(g, &vopts));
    CHECK(f.creates == 3);

    fg_stats s;
    CHECK(fg_get_stats(g, &s));
    CHECK(s.executions == 3 && s.validation_errors == 0);
    CHECK_NEAR(s.ms, 2.0, 1e-9);
    CHECK(s.clock == DIRT_CLOCK_GPU);
    CHECK(s.resources[0].used_reported && s.resources[0].used_bytes == 100);
    CHECK(s.used_bytes == 100);
    CHECK(s.passes[1].barrier == fg_pass_barrier(g, "to_image"));

    /* the test hook drops a derived barrier: validation reports it */
    log_text[0] = '\0';
    CHECK(!fg_execute(g, &(fg_exec_opts){.validate = true, .debug_drop_barrier = "to_image"}));
    CHECK(logged("pass 'to_image' accesses 'values' (ssbo read) after pass 'fill' wrote "
                 "'values' (ssbo write) with no GL_SHADER_STORAGE_BARRIER_BIT in between"));
    CHECK(logged("pass 'to_image' accesses 'img' (image store) after pass 'to_image' wrote "
                 "'img' (image store) with no GL_SHADER_IMAGE_ACCESS_BARRIER_BIT in between"));
    CHECK(fg_get_stats(g, &s) && s.validation_errors == 2);
    /* back to normal: clean again */
    log_text[0] = '\0';
    CHECK(fg_execute(g, &vopts));
    CHECK(!logged("validation"));

    log_text[0] = '\0';
    CHECK(!fg_execute(g, &(fg_exec_opts){.validate = true, .debug_drop_barrier = "draw"}));
    CHECK(logged("pass 'draw' accesses 'img' (sampled) after pass 'to_image' wrote 'img' "
                 "(image store) with no GL_TEXTURE_FETCH_BARRIER_BIT in between"));
    CHECK(fg_get_stats(g, &s) && s.validation_errors == 3);

    /* without validation the drop goes unnoticed (the run succeeds) */
    CHECK(fg_execute(g, &(fg_exec_opts){.debug_drop_barrier = "draw"}));
    CHECK(fg_execute(g, &vopts));

    /* a pass body touching a resource it did not declare */
    log_text[0] = '\0';
    d.peek_undeclared = true;
    uint64_t before = s.validation_errors;
    CHECK(!fg_execute(g, NULL));
    CHECK(logged("pass 'fill' calls fg_name on 'unrelated', which it did not declare"));
    CHECK(fg_get_stats(g, &s) && s.validation_errors > before);
    d.peek_undeclared = false;

    /* a failing pass stops the execute */
    f.events[0] = '\0';
    d.fail_draw = true;
    CHECK(!fg_execute(g, NULL));
    CHECK_MSG(strstr(f.events, "readback") == NULL, "events: %s", f.events);
    CHECK(f.begins == f.ends);
    d.fail_draw = false;

    /* growing a buffer reallocates only it */
    CHECK(fg_set_buffer(g, d.values, &(fg_buf_desc){.per_pixel = 8}));
    CHECK(!fg_execute(g, NULL)); /* needs a compile */
    CHECK(fg_compile(g));
    CHECK(fg_execute(g, &vopts));
    CHECK(f.creates == 4 && f.destroys == 1 && f.live == 3);
    fg_destroy(g);
    CHECK(f.released && f.live == 0);
}

/* The validator works on real objects: the aliased clear is checked
 * against the shader write of the other resource in the same memory. */
static void test_alias_validation(void)
{
    fake f = {.next_name = 700};
    fg_backend b = {&fake_ops, &f};
    fg_graph *g = alias_graph(true, &b);
    CHECK(fg_compile(g));
    CHECK(fg_execute(g, &(fg_exec_opts){.validate = true}));
    CHECK(f.creates == 1);
    CHECK(f.names_seen[0][0] == f.names_seen[2][0]); /* x and y: one object */
    log_text[0] = '\0';
    CHECK(!fg_execute(g, &(fg_exec_opts){.validate = true, .debug_drop_barrier = "p3"}));
    CHECK(logged("pass 'p3' accesses 'y' (transfer write) after pass 'p1' wrote 'x' (same "
                 "memory) (ssbo write) with no GL_BUFFER_UPDATE_BARRIER_BIT in between"));
    fg_destroy(g);
}

/* One clock per graph: pass stats carry the backend's (ms, clock), the
 * totals and fg_add_pass_times follow it, no_timers measures nothing, and
 * a backend mixing clocks is caught rather than summed. */
static void test_timing(void)
{
    fake f = {.next_name = 900, .clock = DIRT_CLOCK_CPU};
    demo d = {0};
    fg_graph *g = demo_graph(&f, &d);
    CHECK(fg_compile(g));
    CHECK(fg_execute(g, &(fg_exec_opts){.validate = true}));
    fg_stats s;
    CHECK(fg_get_stats(g, &s));
    for (int i = 0; i < s.num_passes; i++)
        CHECK_MSG(s.passes[i].clock == DIRT_CLOCK_CPU && s.passes[i].ms == 0.5, "pass %s: %g %s",
                  s.passes[i].name, s.passes[i].ms, dirt_clock_names[s.passes[i].clock]);
    CHECK(s.clock == DIRT_CLOCK_CPU);
    CHECK_NEAR(s.ms, 2.0, 1e-9);

    /* by name, over several executes; unknown names stay 0 */
    const char *const names[3] = {"fill", "draw", "no such pass"};
    double ms[3] = {0};
    enum dirt_clock clock = DIRT_CLOCK_NONE;
    fg_add_pass_times(g, names, 3, ms, &clock);
    CHECK(clock == DIRT_CLOCK_CPU && ms[0] == 0.5 && ms[1] == 0.5 && ms[2] == 0);
    CHECK(fg_execute(g, NULL));
    fg_add_pass_times(g, names, 3, ms, &clock);
    CHECK(clock == DIRT_CLOCK_CPU && ms[0] == 1.0 && ms[1] == 1.0 && ms[2] == 0);

    /* no timers: nothing measured, nothing added */
    CHECK(fg_execute(g, &(fg_exec_opts){.no_timers = true}));
    CHECK(fg_get_stats(g, &s) && s.clock == DIRT_CLOCK_NONE && s.ms == -1);
    for (int i = 0; i < s.num_passes; i++)
        CHECK(s.passes[i].clock == DIRT_CLOCK_NONE && s.passes[i].ms == -1);
    fg_add_pass_times(g, names, 3, ms, &clock);
    CHECK(clock == DIRT_CLOCK_CPU && ms[0] == 1.0 && ms[1] == 1.0);
    enum dirt_clock none = DIRT_CLOCK_NONE;
    double none_ms[3] = {0};
    fg_add_pass_times(g, names, 3, none_ms, &none);
    CHECK(none == DIRT_CLOCK_NONE && none_ms[0] == 0 && none_ms[1] == 0);

    /* a backend that mixes clocks (draw on the GPU clock): no total, and
     * the odd pass is left out of a CPU-clock sum, logged */
    f.odd_pass = 3; /* "draw", declaration index 2 */
    f.odd_clock = DIRT_CLOCK_GPU;
    CHECK(fg_execute(g, NULL));
    CHECK(fg_get_stats(g, &s) && s.clock == DIRT_CLOCK_NONE && s.ms == -1);
    CHECK(s.passes[2].clock == DIRT_CLOCK_GPU && s.passes[0].clock == DIRT_CLOCK_CPU);
    log_text[0] = '\0';
    fg_add_pass_times(g, names, 3, ms, &clock);
    CHECK(clock == DIRT_CLOCK_CPU && ms[0] == 1.5 && ms[1] == 1.0);
    CHECK(logged("pass 'draw' measured by the gpu clock, the others by the cpu clock"));
    fg_destroy(g);
}

/* Asynchronous timers: the backend is told (not with no_timers), and
 * fg_drain_timers hands its late times back per pass, once; a discard
 * forgets them; a backend without drain has nothing late. */
static void test_async_timing(void)
{
    fake f = {.next_name = 950};
    demo d = {0};
    fg_graph *g = demo_graph(&f, &d);
    CHECK(fg_compile(g));
    double late[8];
    enum dirt_clock clock = DIRT_CLOCK_CPU;
    CHECK(fg_execute(g, &(fg_exec_opts){.async_timers = true}));
    CHECK(f.asyncs == 4); /* the backend without drain: told, nothing late */
    CHECK(fg_drain_timers(g, late, 8, &clock) && clock == DIRT_CLOCK_NONE && late[0] == 0);
    fg_destroy(g);

    f = (fake){.next_name = 960};
    fg_backend b = {&fake_async_ops, &f};
    g = fg_create(&b);
    CHECK(g != NULL);
    fg_res buf = fg_buffer(g, "buf", &(fg_buf_desc){.bytes = 64});
    fg_res out = fg_import_buffer(g, "out", 5, 64);
    fg_pass *p1 = fg_add_pass(g, "one", FG_COMPUTE, NULL, NULL);
    fg_write(p1, buf, FG_SSBO_WRITE);
    fg_pass *p2 = fg_add_pass(g, "two", FG_COMPUTE, NULL, NULL);
    fg_read(p2, buf, FG_SSBO_READ);
    fg_write(p2, out, FG_SSBO_WRITE);
    fg_pass *p3 = fg_add_pass(g, "culled", FG_COMPUTE, NULL, NULL);
    fg_write(p3, fg_buffer(g, "unused", &(fg_buf_desc){.bytes = 4}), FG_SSBO_WRITE);
    CHECK(fg_compile(g) && fg_culled(g, "culled"));
    CHECK(fg_execute(g, &(fg_exec_opts){.async_timers = true, .no_timers = true}));
    CHECK(f.asyncs == 0); /* no timers: nothing asynchronous */
    CHECK(fg_execute(g, NULL));
    CHECK(f.asyncs == 0);
    for (int run = 0; run < 3; run++)
        CHECK(fg_execute(g, &(fg_exec_opts){.async_timers = true}));
    CHECK(f.asyncs == 6);
    CHECK(fg_drain_timers(g, late, 3, &clock) && clock == DIRT_CLOCK_GPU);
    CHECK(late[0] == 0.75 && late[1] == 0.75 && late[2] == 0);
    CHECK(fg_drain_timers(g, late, 3, &clock) && clock == DIRT_CLOCK_NONE && late[0] == 0);
    CHECK(fg_execute(g, &(fg_exec_opts){.async_timers = true}));
    fg_discard_timers(g);
    CHECK(fg_drain_timers(g, late, 3, NULL) && late[0] == 0 && late[1] == 0);
    fg_destroy(g);
    /* no backend: nothing to drain */
    g = fg_create(NULL);
    CHECK(!fg_drain_timers(g, late, 3, &clock) && clock == DIRT_CLOCK_NONE);
    fg_discard_timers(g);
    fg_destroy(g);
}

int main(void)
{
    dirt_log_set_callback(capture, NULL);
    test_table();
    test_pass_bits();
    test_alias_bits();
    test_execute();
    test_alias_validation();
    test_timing();
    test_async_timing();
    dirt_log_set_callback(NULL, NULL);
    return check_finish();
}
