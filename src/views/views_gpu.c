#include "views/views_gpu.h"

#include <string.h>

_Static_assert(DIRT_GPU_MAX_VIEWS == DIRT_MAX_VIEWS, "view count");
_Static_assert(DIRT_MAX_MIP_LEVELS <= 16, "level_base holds 16 levels");

void views_pack_gpu(const dirt_view_set *set, struct dirt_gpu_view out[DIRT_MAX_VIEWS])
{
    memset(out, 0, DIRT_MAX_VIEWS * sizeof(*out));
    for (int i = 0; i < set->count; i++) {
        const dirt_view *v = &set->views[i];
        struct dirt_gpu_view *g = &out[i];
        for (int c = 0; c < 4; c++)
            g->view_proj[c] = (dirt_f4){v->view_proj[c * 4], v->view_proj[c * 4 + 1],
                                        v->view_proj[c * 4 + 2], v->view_proj[c * 4 + 3]};
        g->eye_near = (dirt_f4){v->eye[0], v->eye[1], v->eye[2], v->znear};
        g->forward_far = (dirt_f4){v->forward[0], v->forward[1], v->forward[2], v->zfar};
        g->size = (dirt_i4){v->width, v->height, v->tiles_x, v->tiles_y};
        g->placement = (dirt_i4){v->tile_base, v->atlas_x, v->num_levels, v->face};
        int lb[16] = {0};
        for (int d = 0; d < set->num_levels && d < DIRT_MAX_MIP_LEVELS; d++)
            lb[d] = set->level_base[d][i];
        for (int k = 0; k < 4; k++)
            g->level_base[k] = (dirt_i4){lb[4 * k], lb[4 * k + 1], lb[4 * k + 2], lb[4 * k + 3]};
    }
}
