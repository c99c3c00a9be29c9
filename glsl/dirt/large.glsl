// Large primitives (doc/dirt-trace.md, "Large primitives"): the build leaves
// them out of the tiles' lists and the trace tests them with every ray, or
// through their grid (common/layout.h) where the structure has one.
// Needs the build parameters bound as `params` (dirt_gpu_ads_params), whose
// unused slots hold DIRT_LIST_END, never a primitive id.
#ifndef DIRT_LARGE_GLSL
#define DIRT_LARGE_GLSL

// Whether primitive p is one of the large primitives.
bool dirt_is_large(uint p)
{
    uvec4 hit = uvec4(equal(params.large[0], uvec4(p)));
    for (int q = 1; q < DIRT_GPU_MAX_LARGE / 4; q++)
        hit |= uvec4(equal(params.large[q], uvec4(p)));
    return any(notEqual(hit, uvec4(0u)));
}

#endif
