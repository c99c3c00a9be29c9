/* Frame graph memory without GL: sizes, aliasing decisions and the bytes
 * aliasing saves, computed by hand. */
#include <string.h>

#include "check.h"
#include "dirt/log.h"
#include "graph/graph.h"

static void test_sizes(void)
{
    fg_graph *g = fg_create(NULL);
    fg_set_resolution(g, 64, 32);
    fg_res mip = fg_texture(g, "mip", &(fg_tex_desc){.format = FG_R32F, .levels = FG_MIPS_FULL});
    fg_res arr = fg_texture(g, "arr", &(fg_tex_desc){.format = FG_RG32UI, .width = 8,
                                                     .height = 8, .array = true, .layers = 3,
                                                     .levels = 2});
    fg_res tile = fg_texture(g, "tile", &(fg_tex_desc){.format = FG_RGBA16F, .div = 3});
    fg_res nodes = fg_buffer(g, "nodes", &(fg_buf_desc){.bytes = 100, .per_pixel = 12,
                                                        .div = 2, .layers = 7});
    fg_pass *p = fg_add_pass(g, "p", FG_COMPUTE, NULL, NULL);
    fg_write(p, mip, FG_IMAGE_STORE);
    fg_write(p, arr, FG_IMAGE_STORE);
    fg_write(p, tile, FG_IMAGE_STORE);
    fg_write(p, nodes, FG_SSBO_WRITE);
    fg_keep(p);
    CHECK(fg_compile(g));
    /* 64x32 full chain: 7 levels, 2048+512+128+32+8+2+1 texels of 4 bytes */
    CHECK(fg_bytes(g, mip) == 2731 * 4);
    /* 8x8 and 4x4 levels, 3 layers, 8 bytes */
    CHECK(fg_bytes(g, arr) == (64 + 16) * 3 * 8);
    /* ceil(64/3) x ceil(32/3) = 22 x 11, 8 bytes */
    CHECK(fg_bytes(g, tile) == 22 * 11 * 8);
    /* 100 + (32 x 16 pixels) x 7 layers x 12 bytes */
    CHECK(fg_bytes(g, nodes) == 100 + 32 * 16 * 7 * 12);
    fg_stats s;
    CHECK(fg_get_stats(g, &s));
    CHECK(s.transient_bytes == 2731 * 4 + 1920 + 1936 + 43108);
    /* one pass: nothing can share */
    CHECK(s.allocated_bytes == s.transient_bytes && s.num_physical == 4);
    fg_destroy(g);
}

/* p0 -> p1 -> p2 -> p3, six transients; computed by hand:
 *   t0 rgba32f 64x32 = 32768 B, life [0,1]     t1 rgba32f = 32768 B, [2,3]
 *   t2 r32f = 8192 B, [2,3]                     b0 1000 B, [0,1]
 *   b1 3000 B, [2,3]                            b2 500 B, [1,2]
 * t1 takes t0's memory (same kind/format/size, disjoint), b1 takes b0's
 * (grown to 3000: the largest wins); t2 (other format) and b2 (overlaps both)
 * get their own. Saved: 32768 + 1000 = 33768 B. */
static fg_graph *memory_graph(bool aliasing, fg_res *h)
{
    fg_graph *g = fg_create(NULL);
    fg_set_resolution(g, 64, 32);
    fg_set_aliasing(g, aliasing);
    h[0] = fg_texture(g, "t0", &(fg_tex_desc){.format = FG_RGBA32F});
    h[1] = fg_texture(g, "t1", &(fg_tex_desc){.format = FG_RGBA32F});
    h[2] = fg_texture(g, "t2", &(fg_tex_desc){.format = FG_R32F});
    h[3] = fg_buffer(g, "b0", &(fg_buf_desc){.bytes = 1000});
    h[4] = fg_buffer(g, "b1", &(fg_buf_desc){.bytes = 3000});
    h[5] = fg_buffer(g, "b2", &(fg_buf_desc){.bytes = 500});
    fg_res out = fg_import_buffer(g, "out", 77, 256);
    fg_pass *p0 = fg_add_pass(g, "p0", FG_COMPUTE, NULL, NULL);
    fg_write(p0, h[0], FG_IMAGE_STORE);
    fg_write(p0, h[3], FG_SSBO_WRITE);
    fg_pass *p1 = fg_add_pass(g, "p1", FG_COMPUTE, NULL, NULL);
    fg_read(p1, h[0], FG_SAMPLED);
    fg_read(p1, h[3], FG_SSBO_READ);
    fg_write(p1, h[5], FG_SSBO_WRITE);
    fg_pass *p2 = fg_add_pass(g, "p2", FG_COMPUTE, NULL, NULL);
    fg_read(p2, h[5], FG_SSBO_READ);
    fg_write(p2, h[1], FG_IMAGE_STORE);
    fg_write(p2, h[2], FG_IMAGE_STORE);
    fg_write(p2, h[4], FG_SSBO_WRITE);
    fg_pass *p3 = fg_add_pass(g, "p3", FG_COMPUTE, NULL, NULL);
    fg_read(p3, h[1], FG_IMAGE_LOAD);
    fg_read(p3, h[2], FG_IMAGE_LOAD);
    fg_read(p3, h[4], FG_SSBO_READ);
    fg_write(p3, out, FG_SSBO_WRITE);
    return g;
}

static void test_aliasing(void)
{
    fg_res h[6];
    fg_graph *g = memory_graph(true, h);
    CHECK(fg_compile(g));
    CHECK(fg_num_physical(g) == 4);
    CHECK(fg_physical(g, h[0]) == fg_physical(g, h[1]));
    CHECK(fg_physical(g, h[3]) == fg_physical(g, h[4]));
    CHECK(fg_physical(g, h[2]) != fg_physical(g, h[0]));
    CHECK(fg_physical(g, h[5]) != fg_physical(g, h[3]));
    /* assignment order is by first use, then declaration */
    CHECK(fg_physical(g, h[0]) == 0 && fg_physical(g, h[3]) == 1 &&
          fg_physical(g, h[5]) == 2 && fg_physical(g, h[2]) == 3);
    fg_stats s;
    CHECK(fg_get_stats(g, &s));
    const size_t transient = 32768 + 32768 + 8192 + 1000 + 3000 + 500;
    const size_t allocated = 32768 + 8192 + 3000 + 500;
    CHECK(s.transient_bytes == transient);
    CHECK(s.allocated_bytes == allocated);
    CHECK(s.imported_bytes == 256);
    CHECK(s.peak_bytes == allocated + 256);
    CHECK(s.peak_bytes_no_alias == transient + 256);
    CHECK(s.peak_bytes_no_alias - s.peak_bytes == 33768);
    /* alive per position: 33768, 34268, 44460, 43960 */
    CHECK(s.live_peak_bytes == 44460);
    CHECK(s.resources[4].bytes == 3000 && s.resources[4].physical == 1);
    CHECK(s.resources[6].imported && s.resources[6].physical == -1);
    fg_destroy(g);

    g = memory_graph(false, h);
    CHECK(fg_compile(g));
    CHECK(fg_num_physical(g) == 6);
    CHECK(fg_get_stats(g, &s));
    CHECK(s.allocated_bytes == transient && s.peak_bytes == s.peak_bytes_no_alias);
    fg_destroy(g);
}

static void test_alias_choices(void)
{
    fg_graph *g = fg_create(NULL);
    fg_set_resolution(g, 16, 16);
    fg_res a = fg_buffer(g, "a", &(fg_buf_desc){.bytes = 100});
    fg_res b = fg_buffer(g, "b", &(fg_buf_desc){.bytes = 5000});
    fg_res c = fg_buffer(g, "c", &(fg_buf_desc){.bytes = 90});
    fg_res d = fg_buffer(g, "d", &(fg_buf_desc){.bytes = 4000});
    fg_res e = fg_buffer(g, "e", &(fg_buf_desc){.bytes = 6000});
    fg_res rb = fg_buffer(g, "rb", &(fg_buf_desc){.bytes = 10, .readback = true});
    fg_res t = fg_texture(g, "t", &(fg_tex_desc){.format = FG_R32UI});
    fg_res t_mips = fg_texture(g, "t_mips", &(fg_tex_desc){.format = FG_R32UI, .levels = 2});
    fg_res t_arr = fg_texture(g, "t_arr", &(fg_tex_desc){.format = FG_R32UI, .array = true});
    fg_res t_same = fg_texture(g, "t_same", &(fg_tex_desc){.format = FG_R32UI});
    fg_res t_small = fg_texture(g, "t_small", &(fg_tex_desc){.format = FG_R32UI, .div = 2});
    fg_pass *q0 = fg_add_pass(g, "q0", FG_COMPUTE, NULL, NULL);
    fg_write(q0, a, FG_SSBO_WRITE);
    fg_write(q0, b, FG_SSBO_WRITE);
    fg_write(q0, t, FG_IMAGE_STORE);
    fg_keep(q0);
    fg_pass *q1 = fg_add_pass(g, "q1", FG_COMPUTE, NULL, NULL);
    fg_write(q1, c, FG_SSBO_WRITE);
    fg_write(q1, d, FG_SSBO_WRITE);
    fg_write(q1, t_mips, FG_IMAGE_STORE);
    fg_write(q1, t_arr, FG_IMAGE_STORE);
    fg_write(q1, t_small, FG_IMAGE_STORE);
    fg_keep(q1);
    fg_pass *q2 = fg_add_pass(g, "q2", FG_COMPUTE, NULL, NULL);
    fg_write(q2, e, FG_SSBO_WRITE);
    fg_write(q2, rb, FG_TRANSFER_WRITE);
    fg_write(q2, t_same, FG_IMAGE_STORE);
    fg_keep(q2);
    CHECK(fg_compile(g));
    /* best fit: c (90) takes a's 100 B, d (4000) takes b's 5000 B */
    CHECK(fg_physical(g, c) == fg_physical(g, a));
    CHECK(fg_physical(g, d) == fg_physical(g, b));
    /* nothing fits e (6000): it grows the largest free one */
    CHECK(fg_physical(g, e) == fg_physical(g, b));
    /* a readback buffer does not share with plain ones */
    CHECK(fg_physical(g, rb) != fg_physical(g, a) && fg_physical(g, rb) != fg_physical(g, b));
    /* textures only share with identical descriptors */
    CHECK(fg_physical(g, t_mips) != fg_physical(g, t));
    CHECK(fg_physical(g, t_arr) != fg_physical(g, t));
    CHECK(fg_physical(g, t_small) != fg_physical(g, t));
    CHECK(fg_physical(g, t_same) == fg_physical(g, t));
    fg_stats s;
    CHECK(fg_get_stats(g, &s));
    /* allocations: a/c 100, b/d/e 6000, t/t_same 1024, t_mips 1024+256,
     * t_arr 1024, t_small 256, rb 10 */
    CHECK(s.allocated_bytes == 100 + 6000 + 1024 + 1280 + 1024 + 256 + 10);
    CHECK(s.num_physical == 7);
    fg_destroy(g);
}

int main(void)
{
    dirt_log_set_level(DIRT_LOG_WARN);
    test_sizes();
    test_aliasing();
    test_alias_choices();
    return check_finish();
}
