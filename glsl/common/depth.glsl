// The depth bounds of every tile (DIRT) or pixel (MMRT) and their Hi-Z
// pyramid (dirt/views.h): uvec2 (zmin, zmax) float bits per entry. One
// storage block while it fits (DIRT_BIND_DEPTH), else a split array
// (src/gl/split.h; DIRT_SPLIT_EACH) of DIRT_SPLIT_DEPTH parts of
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
#define DIRT_DEPTH_PART(k, a) \
    layout(r32ui, binding = DIRT_IMAGE_SPLIT_DEPTH + k) uniform DIRT_DEPTH_QUAL uimageBuffer \
        dirt_depth_part##k;
DIRT_SPLIT_EACH(DIRT_SPLIT_DEPTH, DIRT_DEPTH_PART, 0)
#define DIRT_DEPTH_LOAD(k, a) \
    if (part == uint(k)) \
        r = uvec2(imageLoad(dirt_depth_part##k, t).x, imageLoad(dirt_depth_part##k, t + 1).x);
uvec2 dirt_depth(uint i)
{
    uint part = i >> uint(DIRT_SPLIT_DEPTH_SHIFT);
    int t = int(2u * (i - (part << uint(DIRT_SPLIT_DEPTH_SHIFT))));
    uvec2 r = uvec2(0u);
    DIRT_SPLIT_EACH(DIRT_SPLIT_DEPTH, DIRT_DEPTH_LOAD, 0)
    return r;
}
#ifndef DIRT_DEPTH_READONLY
#define DIRT_DEPTH_ATOMIC(k, a) \
    if (part == uint(k)) a(dirt_depth_part##k, t, v);
// part and t: the part and texel of value j (0: zmin, 1: zmax) of entry i.
#define DIRT_DEPTH_TEXEL(i, j) \
    uint part = (i) >> uint(DIRT_SPLIT_DEPTH_SHIFT); \
    int t = int(2u * ((i) - (part << uint(DIRT_SPLIT_DEPTH_SHIFT))) + (j));
void dirt_depth_min(uint i, uint v)
{
    DIRT_DEPTH_TEXEL(i, 0u)
    DIRT_SPLIT_EACH(DIRT_SPLIT_DEPTH, DIRT_DEPTH_ATOMIC, imageAtomicMin)
}

void dirt_depth_max(uint i, uint v)
{
    DIRT_DEPTH_TEXEL(i, 1u)
    DIRT_SPLIT_EACH(DIRT_SPLIT_DEPTH, DIRT_DEPTH_ATOMIC, imageAtomicMax)
}

#define DIRT_DEPTH_STORE(k, a) \
    if (part == uint(k)) { \
        imageStore(dirt_depth_part##k, t, uvec4(e.x)); \
        imageStore(dirt_depth_part##k, t + 1, uvec4(e.y)); \
    }
void dirt_depth_store(uint i, uvec2 e)
{
    DIRT_DEPTH_TEXEL(i, 0u)
    DIRT_SPLIT_EACH(DIRT_SPLIT_DEPTH, DIRT_DEPTH_STORE, 0)
}
#endif
#endif
