#version 450 core
#include "common/constants.h"
// Frame graph GPU test: an attachment-less raster pass that adds u_add to
// its pixel of an r32ui image with an image atomic (the pattern of DIRT's
// build passes).

layout(r32ui, binding = DIRT_UNIT_TEST) uniform uimage2D u_counts;

layout(location = DIRT_LOC_TEST_SPLAT_ADD) uniform uint u_add;

void main()
{
    imageAtomicAdd(u_counts, ivec2(gl_FragCoord.xy), u_add);
}
