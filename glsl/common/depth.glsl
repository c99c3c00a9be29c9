// The depth bounds of every tile (DIRT) or pixel (MMRT) and their Hi-Z
// pyramid (dirt/views.h): uvec2 (zmin, zmax) float bits per entry. One
// storage block while it fits (DIRT_BIND_DEPTH), else a split array
// (src/gl/split.h; common/split.glsl) of DIRT_SPLIT_DEPTH parts of
// 2^DIRT_SPLIT_DEPTH_SHIFT entries: R32UI images, two texels an entry (so
// the min and the max take image atomics), at DIRT_IMAGE_SPLIT_DEPTH + part.
// A shader that only reads it defines DIRT_DEPTH_READONLY first.
// Accessors: dirt_depth(i); dirt_depth_min(i, zmin), dirt_depth_max(i,
// zmax) (atomic), dirt_depth_store(i, e). Needs common/constants.h.


#ifndef DIRT_SPLIT_DEPTH
#define DIRT_SPLIT_DEPTH 0
#define DIRT_SPLIT_DEPTH_SHIFT 0
#endif
#ifdef DIRT_DEPTH_READONLY
#define DIRT_DEPTH_QUAL readonly
#else
#define DIRT_DEPTH_QUAL
#endif

#if DIRT_SPLIT_DEPTH == 0
layout(std430, binding = DIRT_BIND_DEPTH) DIRT_DEPTH_QUAL buffer Depth {
    uvec2 depth[];
};

uvec2 dirt_depth(uint i)
{
    return depth[i];
}
#ifndef DIRT_DEPTH_READONLY
void dirt_depth_min(uint i, uint zmin)
{
    atomicMin(depth[i].x, zmin);
}

void dirt_depth_max(uint i, uint zmax)
{
    atomicMax(depth[i].y, zmax);
}

void dirt_depth_store(uint i, uvec2 e)
{
    depth[i] = e;
}
#endif
#else
DIRT_SPLIT_IMAGES(DIRT_SPLIT_DEPTH, DIRT_IMAGE_SPLIT_DEPTH, r32ui,
                  DIRT_DEPTH_QUAL uimageBuffer, dirt_depth)
uvec2 dirt_depth(uint i)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_DEPTH_SHIFT, 2u)
    uint lo = 0u, hi = 0u;
    DIRT_SPLIT_LOAD(DIRT_SPLIT_DEPTH, lo, imageLoad, dirt_depth, .x)
    t++;
    DIRT_SPLIT_LOAD(DIRT_SPLIT_DEPTH, hi, imageLoad, dirt_depth, .x)
    return uvec2(lo, hi);
}
#ifndef DIRT_DEPTH_READONLY
void dirt_depth_min(uint i, uint v)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_DEPTH_SHIFT, 2u)
    DIRT_SPLIT_STORE(DIRT_SPLIT_DEPTH, imageAtomicMin, dirt_depth, v)
}

void dirt_depth_max(uint i, uint v)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_DEPTH_SHIFT, 2u)
    t++;
    DIRT_SPLIT_STORE(DIRT_SPLIT_DEPTH, imageAtomicMax, dirt_depth, v)
}

void dirt_depth_store(uint i, uvec2 e)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_DEPTH_SHIFT, 2u)
    DIRT_SPLIT_STORE(DIRT_SPLIT_DEPTH, imageStore, dirt_depth, uvec4(e.x))
    t++;
    DIRT_SPLIT_STORE(DIRT_SPLIT_DEPTH, imageStore, dirt_depth, uvec4(e.y))
}
#endif
#endif
