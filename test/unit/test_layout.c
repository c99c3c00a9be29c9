/* The shared-constants registry at run time, without GL: the binding table
 * of test/common/layout_check.c against the ranges (each binding named once, in
 * the range the table says, the ranges tiling [0, DIRT_BIND_LAST]), the
 * per-program uniform locations (distinct, within GL's guaranteed 1024),
 * the workgroup rounding and the public node sizes. */
#include <string.h>

#include "check.h"
#include "common/constants.h"
#include "mmrt/mmrt.h"
#include "layout_check.h"

static void test_bindings(void)
{
    CHECK(dirt_layout_num_bindings == DIRT_BIND_LAST + 1);
    int next = 0;
    for (size_t r = 0; r < dirt_layout_num_ranges; r++) {
        const dirt_layout_range *rg = &dirt_layout_ranges[r];
        CHECK_MSG(rg->first == next && rg->last >= rg->first, "range %s [%d, %d] after %d",
                  rg->name, rg->first, rg->last, next - 1);
        next = rg->last + 1;
    }
    CHECK(next == DIRT_BIND_LAST + 1);
    int count[DIRT_BIND_LAST + 1] = {0};
    for (size_t i = 0; i < dirt_layout_num_bindings; i++) {
        const dirt_layout_binding *b = &dirt_layout_bindings[i];
        CHECK_MSG(b->binding >= 0 && b->binding <= DIRT_BIND_LAST, "%s = %d", b->name, b->binding);
        if (b->binding < 0 || b->binding > DIRT_BIND_LAST)
            continue;
        count[b->binding]++;
        const char *nm = dirt_layout_binding_name(b->binding);
        CHECK_MSG(nm && strcmp(nm, b->name) == 0, "%s: switch says %s", b->name, nm ? nm : "none");
        const dirt_layout_range *own = NULL;
        for (size_t r = 0; r < dirt_layout_num_ranges; r++)
            if (b->binding >= dirt_layout_ranges[r].first && b->binding <= dirt_layout_ranges[r].last)
                own = &dirt_layout_ranges[r];
        CHECK_MSG(own && strcmp(own->name, b->range) == 0, "%s = %d: in range %s, table says %s",
                  b->name, b->binding, own ? own->name : "none", b->range);
    }
    for (int i = 0; i <= DIRT_BIND_LAST; i++)
        CHECK_MSG(count[i] == 1, "binding %d named %d times", i, count[i]);
    CHECK(dirt_layout_binding_name(-1) == NULL && dirt_layout_binding_name(DIRT_BIND_LAST + 1) == NULL);
}

static void test_uniforms(void)
{
    for (size_t p = 0; p < dirt_layout_num_programs; p++) {
        const dirt_layout_program *lp = &dirt_layout_programs[p];
        /* ranges 0: a program without storage buffers (the presentation). */
        CHECK(lp->paths[0] != NULL && lp->num_uniforms > 0 &&
              (lp->ranges >> dirt_layout_num_ranges) == 0);
        for (size_t i = 0; i < lp->num_uniforms; i++) {
            CHECK(lp->uniforms[i].location >= 0 && lp->uniforms[i].location < 1024);
            for (size_t j = 0; j < i; j++) {
                CHECK_MSG(lp->uniforms[i].location != lp->uniforms[j].location,
                          "%s: %s and %s share location %d", lp->paths[0], lp->uniforms[i].name,
                          lp->uniforms[j].name, lp->uniforms[i].location);
                CHECK(strcmp(lp->uniforms[i].name, lp->uniforms[j].name) != 0);
            }
        }
    }
}

static void test_sizes(void)
{
    static const unsigned n[] = {0, 1, 63, 64, 65, 1000};
    for (size_t i = 0; i < sizeof(n) / sizeof(n[0]); i++) {
        unsigned g = DIRT_GROUPS(n[i]);
        CHECK(g * DIRT_GROUP_SIZE >= n[i] && (g == 0 || (g - 1) * DIRT_GROUP_SIZE < n[i]));
        unsigned g2 = DIRT_GROUPS_2D(n[i]);
        CHECK(g2 * DIRT_GROUP_SIZE_2D >= n[i] && (g2 == 0 || (g2 - 1) * DIRT_GROUP_SIZE_2D < n[i]));
    }
    CHECK(DIRT_MMRT_ID_NODE_BYTES == 12 && DIRT_MMRT_DATA_NODE_BYTES == 32);
    CHECK(sizeof(dirt_mmrt_id_node) == DIRT_MMRT_ID_NODE_BYTES);
    CHECK(sizeof(dirt_mmrt_data_node) == DIRT_MMRT_DATA_NODE_BYTES);
    CHECK(DIRT_NODE_BYTES == 8 && DIRT_HIT_NODE_BYTES == 32);
}

int main(void)
{
    test_bindings();
    test_uniforms();
    test_sizes();
    return check_finish();
}
