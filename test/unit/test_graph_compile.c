/* Frame graph compile without GL: order, culling, lifetimes and every
 * validation error. */
#include <string.h>

#include "check.h"
#include "dirt/log.h"
#include "graph/graph.h"

static const fg_buf_desc buf1k = {.bytes = 1024};

static bool has(const char *s, const char *sub)
{
    return s && strstr(s, sub) != NULL;
}

/* A chain declared in order runs in order; independent passes keep
 * declaration order. */
static void test_linear_order(void)
{
    fg_graph *g = fg_create(NULL);
    fg_res a = fg_buffer(g, "a", &buf1k);
    fg_res b = fg_buffer(g, "b", &buf1k);
    fg_res c = fg_buffer(g, "c", &buf1k);
    fg_pass *p0 = fg_add_pass(g, "p0", FG_COMPUTE, NULL, NULL);
    fg_write(p0, a, FG_SSBO_WRITE);
    fg_pass *q = fg_add_pass(g, "independent", FG_COMPUTE, NULL, NULL);
    fg_write(q, c, FG_SSBO_WRITE);
    fg_output(g, c);
    fg_pass *p1 = fg_add_pass(g, "p1", FG_COMPUTE, NULL, NULL);
    fg_read(p1, a, FG_SSBO_READ);
    fg_write(p1, b, FG_SSBO_WRITE);
    fg_output(g, b);
    CHECK(fg_compile(g));
    CHECK(fg_num_ordered(g) == 3);
    CHECK(fg_position(g, "p0") == 0);
    CHECK(fg_position(g, "independent") == 1);
    CHECK(fg_position(g, "p1") == 2);
    CHECK(fg_order(g, 0) == 0 && fg_order(g, 1) == 1 && fg_order(g, 2) == 2);
    CHECK(fg_order(g, 3) == -1);
    fg_destroy(g);
}

/* A use added to an earlier-created pass sees the later-declared write:
 * "shade" is created first but must run after "trace". Free passes keep
 * declaration order around them. */
static void test_reorder(void)
{
    fg_graph *g = fg_create(NULL);
    fg_res hits = fg_buffer(g, "hits", &buf1k);
    fg_res img = fg_buffer(g, "image", &buf1k);
    fg_res other = fg_buffer(g, "other", &buf1k);
    fg_pass *shade = fg_add_pass(g, "shade", FG_COMPUTE, NULL, NULL);
    fg_pass *free0 = fg_add_pass(g, "free0", FG_COMPUTE, NULL, NULL);
    fg_pass *trace = fg_add_pass(g, "trace", FG_COMPUTE, NULL, NULL);
    fg_write(trace, hits, FG_SSBO_WRITE);
    fg_read(shade, hits, FG_SSBO_READ);
    fg_write(shade, img, FG_SSBO_WRITE);
    fg_write(free0, other, FG_SSBO_WRITE);
    fg_output(g, img);
    fg_output(g, other);
    CHECK(fg_compile(g));
    CHECK(fg_position(g, "free0") == 0);
    CHECK(fg_position(g, "trace") == 1);
    CHECK(fg_position(g, "shade") == 2);
    fg_destroy(g);
}

/* Versions: write, read, overwrite, read. The first reader runs before the
 * overwrite (write after read), the second sees the second version. */
static void test_versions(void)
{
    fg_graph *g = fg_create(NULL);
    fg_res x = fg_buffer(g, "x", &buf1k);
    fg_res out1 = fg_buffer(g, "out1", &buf1k);
    fg_res out2 = fg_buffer(g, "out2", &buf1k);
    fg_pass *w1 = fg_add_pass(g, "w1", FG_COMPUTE, NULL, NULL);
    fg_pass *w2 = fg_add_pass(g, "w2", FG_COMPUTE, NULL, NULL);
    fg_pass *r1 = fg_add_pass(g, "r1", FG_COMPUTE, NULL, NULL);
    fg_pass *r2 = fg_add_pass(g, "r2", FG_COMPUTE, NULL, NULL);
    fg_write(w1, x, FG_SSBO_WRITE);
    fg_read(r1, x, FG_SSBO_READ);     /* reads w1's version */
    fg_write(w2, x, FG_SSBO_WRITE);   /* must wait for r1 */
    fg_read(r2, x, FG_SSBO_READ);     /* reads w2's version */
    fg_write(r1, out1, FG_SSBO_WRITE);
    fg_write(r2, out2, FG_SSBO_WRITE);
    fg_output(g, out1);
    fg_output(g, out2);
    CHECK(fg_compile(g));
    /* declaration order would be w1 w2 r1 r2; the hazard forces r1 before w2 */
    CHECK(fg_position(g, "w1") == 0);
    CHECK(fg_position(g, "r1") == 1);
    CHECK(fg_position(g, "w2") == 2);
    CHECK(fg_position(g, "r2") == 3);
    int first = -2, last = -2;
    CHECK(fg_lifetime(g, x, &first, &last));
    CHECK(first == 0 && last == 3);
    fg_destroy(g);
}

static void test_culling(void)
{
    fg_graph *g = fg_create(NULL);
    fg_res a = fg_buffer(g, "a", &buf1k);
    fg_res dbg = fg_buffer(g, "debug_buf", &buf1k);
    fg_res dbg2 = fg_buffer(g, "debug_buf2", &buf1k);
    fg_res out = fg_buffer(g, "out", &buf1k);
    fg_res persistent = fg_import_buffer(g, "persistent", 42, 256);
    fg_res side = fg_buffer(g, "side", &buf1k);
    fg_pass *make = fg_add_pass(g, "make", FG_COMPUTE, NULL, NULL);
    fg_write(make, a, FG_SSBO_WRITE);
    fg_pass *debug1 = fg_add_pass(g, "debug1", FG_COMPUTE, NULL, NULL);
    fg_read(debug1, a, FG_SSBO_READ);
    fg_write(debug1, dbg, FG_SSBO_WRITE);
    fg_pass *debug2 = fg_add_pass(g, "debug2", FG_COMPUTE, NULL, NULL);
    fg_read(debug2, dbg, FG_SSBO_READ);
    fg_write(debug2, dbg2, FG_SSBO_WRITE);
    fg_pass *use = fg_add_pass(g, "use", FG_COMPUTE, NULL, NULL);
    fg_read(use, a, FG_SSBO_READ);
    fg_write(use, out, FG_SSBO_WRITE);
    fg_output(g, out);
    fg_pass *acc = fg_add_pass(g, "accumulate", FG_COMPUTE, NULL, NULL);
    fg_write(acc, persistent, FG_SSBO_WRITE);   /* imported: kept */
    fg_pass *kept = fg_add_pass(g, "readback", FG_COMPUTE, NULL, NULL);
    fg_write(kept, side, FG_TRANSFER_WRITE);
    fg_keep(kept);
    CHECK(fg_compile(g));
    CHECK(!fg_culled(g, "make"));
    CHECK(fg_culled(g, "debug1"));
    CHECK(fg_culled(g, "debug2"));
    CHECK(!fg_culled(g, "use"));
    CHECK(!fg_culled(g, "accumulate"));
    CHECK(!fg_culled(g, "readback"));
    CHECK(fg_num_ordered(g) == 4);
    CHECK(fg_position(g, "debug1") == -1);
    CHECK(fg_position(g, "use") == 1);
    CHECK(fg_position(g, "accumulate") == 2);
    CHECK(fg_position(g, "readback") == 3);
    int first, last;
    CHECK(!fg_lifetime(g, dbg, &first, &last));
    CHECK(first == -1 && last == -1);
    CHECK(fg_physical(g, dbg) == -1);
    CHECK(fg_physical(g, persistent) == -1);
    fg_stats s;
    CHECK(fg_get_stats(g, &s));
    CHECK(s.resources[1].culled && s.passes[1].culled && !s.passes[0].culled);
    fg_destroy(g);

    /* a read-write writer needs the earlier writer, which stays alive */
    g = fg_create(NULL);
    fg_res counter = fg_buffer(g, "counter", &(fg_buf_desc){.bytes = 4});
    fg_res res_out = fg_buffer(g, "result", &buf1k);
    fg_pass *clear = fg_add_pass(g, "clear", FG_COMPUTE, NULL, NULL);
    fg_write(clear, counter, FG_TRANSFER_WRITE);
    fg_pass *count = fg_add_pass(g, "count", FG_COMPUTE, NULL, NULL);
    fg_write(count, counter, FG_ATOMIC_COUNTER);
    fg_pass *consume = fg_add_pass(g, "consume", FG_COMPUTE, NULL, NULL);
    fg_read(consume, counter, FG_SSBO_READ);
    fg_write(consume, res_out, FG_SSBO_WRITE);
    fg_output(g, res_out);
    CHECK(fg_compile(g));
    CHECK(fg_num_ordered(g) == 3);
    CHECK(fg_position(g, "clear") == 0 && fg_position(g, "count") == 1 &&
          fg_position(g, "consume") == 2);
    fg_destroy(g);

    /* nothing reaches an output: everything is culled */
    g = fg_create(NULL);
    fg_res t = fg_buffer(g, "t", &buf1k);
    fg_write(fg_add_pass(g, "lonely", FG_COMPUTE, NULL, NULL), t, FG_SSBO_WRITE);
    CHECK(fg_compile(g));
    CHECK(fg_num_ordered(g) == 0 && fg_culled(g, "lonely"));
    fg_destroy(g);
}

static void test_lifetimes(void)
{
    fg_graph *g = fg_create(NULL);
    fg_set_resolution(g, 16, 8);
    fg_res a = fg_texture(g, "a", &(fg_tex_desc){.format = FG_R32F});
    fg_res b = fg_texture(g, "b", &(fg_tex_desc){.format = FG_R32F});
    fg_res c = fg_buffer(g, "c", &(fg_buf_desc){.per_pixel = 4});
    fg_res d = fg_buffer(g, "d", &buf1k);
    fg_pass *p[5];
    const char *names[5] = {"p0", "p1", "p2", "p3", "p4"};
    for (int i = 0; i < 5; i++)
        p[i] = fg_add_pass(g, names[i], FG_COMPUTE, NULL, NULL);
    fg_write(p[0], a, FG_IMAGE_STORE);
    fg_read(p[1], a, FG_IMAGE_LOAD);
    fg_write(p[1], b, FG_IMAGE_STORE);
    fg_read(p[2], b, FG_SAMPLED);
    fg_read(p[3], a, FG_SAMPLED);
    fg_write(p[3], c, FG_SSBO_WRITE);
    fg_read(p[4], c, FG_SSBO_READ);
    fg_read(p[4], b, FG_IMAGE_LOAD);
    fg_write(p[4], d, FG_SSBO_WRITE);
    fg_output(g, d);
    fg_write(p[2], c, FG_SSBO_WRITE);   /* declared after p3's write: p2 runs after p3 */
    fg_output(g, c);
    CHECK(fg_compile(g));
    /* p2's write of c comes after p3's write (call order) and p4 read the
     * version of p3, so p2 must follow p4: order p0 p1 p3 p4 p2 */
    CHECK(fg_position(g, "p0") == 0 && fg_position(g, "p1") == 1 &&
          fg_position(g, "p3") == 2 && fg_position(g, "p4") == 3 && fg_position(g, "p2") == 4);
    int f, l;
    CHECK(fg_lifetime(g, a, &f, &l) && f == 0 && l == 2);
    CHECK(fg_lifetime(g, b, &f, &l) && f == 1 && l == 4);
    CHECK(fg_lifetime(g, c, &f, &l) && f == 2 && l == 4);
    CHECK(fg_bytes(g, c) == 16 * 8 * 4);
    CHECK(fg_bytes(g, a) == 16 * 8 * 4);
    fg_destroy(g);
}

/* Compiles `g`, expects failure with `msg` in the first error. */
#define EXPECT_ERROR(g, msg) do { \
        CHECK(!fg_compile(g)); \
        CHECK_MSG(has(fg_last_error(g), (msg)), "error was: %s", fg_last_error(g)); \
        CHECK(fg_num_ordered(g) == 0); \
    } while (0)

static void test_errors(void)
{
    fg_graph *g;
    fg_pass *p, *q;
    fg_res a, b, t, d;

    /* unknown resource */
    g = fg_create(NULL);
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_write(p, (fg_res){7}, FG_SSBO_WRITE);
    fg_keep(p);
    EXPECT_ERROR(g, "pass 'p' uses unknown resource #7");
    fg_destroy(g);

    /* reading something nobody wrote */
    g = fg_create(NULL);
    a = fg_buffer(g, "a", &buf1k);
    p = fg_add_pass(g, "reader", FG_COMPUTE, NULL, NULL);
    fg_read(p, a, FG_SSBO_READ);
    fg_keep(p);
    EXPECT_ERROR(g, "pass 'reader' reads 'a' (ssbo read) but no pass writes it before");
    fg_destroy(g);

    /* ... also through a read-write access; an imported resource is fine */
    g = fg_create(NULL);
    a = fg_buffer(g, "counter", &buf1k);
    b = fg_import_buffer(g, "imported", 5, 64);
    p = fg_add_pass(g, "count", FG_COMPUTE, NULL, NULL);
    fg_write(p, a, FG_ATOMIC_COUNTER);
    fg_read(p, b, FG_SSBO_READ);
    fg_keep(p);
    EXPECT_ERROR(g, "pass 'count' reads 'counter' (atomic counter) but no pass writes it");
    fg_destroy(g);

    /* cycle: a reads y (written by b), b reads x (written by a) */
    g = fg_create(NULL);
    a = fg_buffer(g, "x", &buf1k);
    b = fg_buffer(g, "y", &buf1k);
    p = fg_add_pass(g, "a", FG_COMPUTE, NULL, NULL);
    q = fg_add_pass(g, "b", FG_COMPUTE, NULL, NULL);
    fg_write(p, a, FG_SSBO_WRITE);
    fg_write(q, b, FG_SSBO_WRITE);
    fg_read(p, b, FG_SSBO_READ);
    fg_read(q, a, FG_SSBO_READ);
    fg_keep(p);
    EXPECT_ERROR(g, "dependency cycle: a -> b (reads 'x') -> a (reads 'y')");
    fg_destroy(g);

    /* cycle through call order on one resource */
    g = fg_create(NULL);
    a = fg_buffer(g, "x", &buf1k);
    b = fg_buffer(g, "seed", &buf1k);
    p = fg_add_pass(g, "a", FG_COMPUTE, NULL, NULL);
    q = fg_add_pass(g, "b", FG_COMPUTE, NULL, NULL);
    fg_write(q, b, FG_SSBO_WRITE);
    fg_write(q, a, FG_SSBO_WRITE);
    fg_read(p, a, FG_SSBO_READ);
    fg_write(q, b, FG_SSBO_WRITE);
    fg_write(p, a, FG_SSBO_WRITE);  /* nobody wrote x since a read it: fine */
    fg_keep(p);
    CHECK(fg_compile(g));          /* b, a */
    CHECK(fg_position(g, "b") == 0 && fg_position(g, "a") == 1);
    /* all accesses of one pass to one resource are one use: b's late read
     * of x sees the content before b's own write, which nobody wrote */
    fg_read(q, a, FG_SSBO_READ);
    EXPECT_ERROR(g, "pass 'b' reads 'x' (ssbo read) but no pass writes it before");
    fg_destroy(g);

    g = fg_create(NULL);
    a = fg_buffer(g, "x", &buf1k);
    p = fg_add_pass(g, "a", FG_COMPUTE, NULL, NULL);
    q = fg_add_pass(g, "b", FG_COMPUTE, NULL, NULL);
    fg_write(q, a, FG_SSBO_WRITE);
    fg_read(p, a, FG_SSBO_READ);
    fg_write(q, a, FG_SSBO_WRITE);  /* same access again: merged, fine */
    fg_keep(p);
    CHECK(fg_compile(g));
    fg_destroy(g);

    g = fg_create(NULL);
    a = fg_buffer(g, "x", &buf1k);
    p = fg_add_pass(g, "a", FG_COMPUTE, NULL, NULL);
    q = fg_add_pass(g, "b", FG_COMPUTE, NULL, NULL);
    fg_write(q, a, FG_SSBO_WRITE);
    fg_read(p, a, FG_SSBO_READ);    /* reads b's version */
    fg_write(fg_add_pass(g, "c", FG_COMPUTE, NULL, NULL), a, FG_SSBO_WRITE);
    fg_write(p, a, FG_SSBO_WRITE);  /* p read before c's write, writes after it */
    fg_keep(p);
    EXPECT_ERROR(g, "dependency cycle: pass 'a' reads 'x' before pass 'c' writes it");
    fg_destroy(g);

    /* two different writes of one resource in one pass */
    g = fg_create(NULL);
    t = fg_texture(g, "t", &(fg_tex_desc){.format = FG_R32UI, .width = 4, .height = 4});
    p = fg_add_pass(g, "fill", FG_COMPUTE, NULL, NULL);
    fg_write(p, t, FG_TRANSFER_WRITE);
    fg_write(p, t, FG_IMAGE_ATOMIC);
    fg_keep(p);
    EXPECT_ERROR(g, "pass 'fill' writes 't' with two different accesses (transfer write and "
                    "image atomic)");
    fg_destroy(g);

    /* access/resource mismatches: an image the graph is asked to bind must
     * be a texture (a buffer read as a texel buffer is bound by its pass) */
    g = fg_create(NULL);
    a = fg_buffer(g, "buf", &buf1k);
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_use(p, a, FG_IMAGE_STORE, &(fg_use_opts){.bind = true, .binding = 1});
    fg_keep(p);
    EXPECT_ERROR(g, "pass 'p': access 'image store' needs a texture, but 'buf' is a buffer");
    fg_destroy(g);

    g = fg_create(NULL);
    t = fg_texture(g, "tex", &(fg_tex_desc){.format = FG_RGBA8, .width = 4, .height = 4});
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_write(p, t, FG_SSBO_WRITE);
    fg_keep(p);
    EXPECT_ERROR(g, "access 'ssbo write' needs a buffer, but 'tex' is a texture");
    fg_destroy(g);

    g = fg_create(NULL);
    t = fg_texture(g, "color", &(fg_tex_desc){.format = FG_RGBA8, .width = 4, .height = 4});
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_write(p, t, FG_COLOR);
    fg_keep(p);
    EXPECT_ERROR(g, "pass 'p' is a compute pass and cannot use 'color' as a color attachment");
    fg_destroy(g);

    g = fg_create(NULL);
    d = fg_texture(g, "depth", &(fg_tex_desc){.format = FG_DEPTH32F, .width = 4, .height = 4});
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_write(p, d, FG_IMAGE_STORE);
    fg_keep(p);
    EXPECT_ERROR(g, "depth texture 'depth' cannot be used as image store");
    fg_destroy(g);

    g = fg_create(NULL);
    t = fg_texture(g, "t", &(fg_tex_desc){.format = FG_RGBA8, .width = 4, .height = 4});
    p = fg_add_pass(g, "p", FG_RASTER, NULL, NULL);
    fg_write(p, t, FG_DEPTH);
    fg_keep(p);
    EXPECT_ERROR(g, "'t' (rgba8) is not a depth format");
    fg_destroy(g);

    /* direction checks of fg_read / fg_write */
    g = fg_create(NULL);
    a = fg_buffer(g, "a", &buf1k);
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_read(p, a, FG_SSBO_WRITE);
    fg_keep(p);
    EXPECT_ERROR(g, "fg_read of 'a' with the writing access 'ssbo write'");
    fg_destroy(g);

    g = fg_create(NULL);
    a = fg_import_buffer(g, "a", 3, 16);
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_write(p, a, FG_VERTEX);
    EXPECT_ERROR(g, "fg_write of 'a' with the read-only access 'vertex'");
    fg_destroy(g);

    /* sizes */
    g = fg_create(NULL);
    t = fg_texture(g, "rel", &(fg_tex_desc){.format = FG_R32F, .div = 2});
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_write(p, t, FG_IMAGE_STORE);
    fg_keep(p);
    EXPECT_ERROR(g, "texture 'rel' is sized relative to the output resolution, but none is set");
    fg_set_resolution(g, 9, 5);
    CHECK(fg_compile(g));
    int w = 0;
    fg_stats s;
    CHECK(fg_get_stats(g, &s) && s.resources[0].bytes == 5 * 3 * 4);
    (void)w;
    fg_destroy(g);

    g = fg_create(NULL);
    a = fg_buffer(g, "empty", &(fg_buf_desc){0});
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_write(p, a, FG_SSBO_WRITE);
    fg_keep(p);
    EXPECT_ERROR(g, "buffer 'empty' has size 0");
    fg_destroy(g);

    g = fg_create(NULL);
    t = fg_texture(g, "m", &(fg_tex_desc){.format = FG_R32F, .width = 8, .height = 4,
                                           .levels = 5});
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_write(p, t, FG_IMAGE_STORE);
    fg_keep(p);
    EXPECT_ERROR(g, "texture 'm': 5 mip levels (a 8x4 texture has at most 4)");
    fg_destroy(g);

    /* raster attachments of different sizes */
    g = fg_create(NULL);
    t = fg_texture(g, "c0", &(fg_tex_desc){.format = FG_RGBA8, .width = 8, .height = 8});
    d = fg_texture(g, "z", &(fg_tex_desc){.format = FG_DEPTH32F, .width = 4, .height = 4});
    p = fg_add_pass(g, "draw", FG_RASTER, NULL, NULL);
    fg_write(p, t, FG_COLOR);
    fg_write(p, d, FG_DEPTH);
    fg_keep(p);
    EXPECT_ERROR(g, "raster pass 'draw': attachment 'z' is 4x4x1 but 'c0' is 8x8x1");
    fg_destroy(g);

    /* declaration errors are reported by every compile */
    g = fg_create(NULL);
    a = fg_buffer(g, "dup", &buf1k);
    b = fg_buffer(g, "dup", &buf1k);
    CHECK(a.id != 0 && b.id == 0);
    t = fg_texture(g, "noformat", &(fg_tex_desc){.width = 4, .height = 4});
    CHECK(t.id == 0);
    EXPECT_ERROR(g, "resource 'dup' is declared twice");
    EXPECT_ERROR(g, "resource 'dup' is declared twice");
    fg_destroy(g);

    g = fg_create(NULL);
    t = fg_texture(g, "noformat", &(fg_tex_desc){.width = 4, .height = 4});
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_write(p, t, FG_IMAGE_STORE);
    fg_keep(p);
    CHECK(!fg_compile(g));
    CHECK(has(fg_last_error(g), "texture 'noformat': no valid format"));
    fg_destroy(g);

    /* execute without compile or without a GPU */
    g = fg_create(NULL);
    a = fg_buffer(g, "a", &buf1k);
    p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_write(p, a, FG_SSBO_WRITE);
    fg_keep(p);
    CHECK(!fg_execute(g, NULL));
    CHECK(fg_compile(g));
    CHECK(!fg_execute(g, NULL));
    fg_destroy(g);
    fg_destroy(NULL);
}

int main(void)
{
    dirt_log_set_level(DIRT_LOG_WARN);
    test_linear_order();
    test_reorder();
    test_versions();
    test_culling();
    test_lifetimes();
    test_errors();
    return check_finish();
}
