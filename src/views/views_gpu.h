/* Packing of a view set into the GPU view records (glsl/common/layout.h),
 * shared by every technique that uploads views (DIRT, MMRT). Pure C. */
#ifndef DIRT_VIEWS_VIEWS_GPU_H
#define DIRT_VIEWS_VIEWS_GPU_H

#include "common/layout.h"
#include "views/views.h"

/* Fills out[0 .. DIRT_MAX_VIEWS) (unused entries zeroed). */
void views_pack_gpu(const dirt_view_set *set, struct dirt_gpu_view out[DIRT_MAX_VIEWS]);

#endif
