// The MMRT A-buffer's arrays that grow with the views and the scene: the
// bucket heads and tails (uint per bucket and pixel), the id nodes
// (DIRT_MMRT_ID_UINTS uints per node: common/mmrt_layout.h) and the data
// nodes (dirt_mmrt_gpu_data). Each is one storage block while it fits
// (DIRT_BIND_MMRT_HEADS, _TAILS, _IDS, _DATA), else a split array
// (src/gl/split.h; common/split.glsl) of DIRT_SPLIT_MMRT_<ARRAY> parts of
// 2^..._SHIFT records: images at DIRT_IMAGE_SPLIT_MMRT_<ARRAY> + part (R32UI;
// R32UI, three texels a node; RGBA32UI, two texels a node). A shader that
// only reads or only writes an array defines MMRT_<ARRAY>_READONLY or
// _WRITEONLY first (the block's qualifier as it always was; only the
// accessors it may use are declared). Accessors: mmrt_head(i),
// mmrt_head_store(i, v), mmrt_head_exchange(i, v) (atomic); mmrt_tail(i),
// mmrt_tail_store(i, v); mmrt_id(n, field), mmrt_id_store(n, field, v);
// mmrt_data(n), mmrt_data_store(n, d). Needs common/mmrt_layout.h.


#ifndef DIRT_SPLIT_MMRT_HEADS
#define DIRT_SPLIT_MMRT_HEADS 0
#define DIRT_SPLIT_MMRT_HEADS_SHIFT 0
#endif
#ifndef DIRT_SPLIT_MMRT_TAILS
#define DIRT_SPLIT_MMRT_TAILS 0
#define DIRT_SPLIT_MMRT_TAILS_SHIFT 0
#endif
#ifndef DIRT_SPLIT_MMRT_IDS
#define DIRT_SPLIT_MMRT_IDS 0
#define DIRT_SPLIT_MMRT_IDS_SHIFT 0
#endif
#ifndef DIRT_SPLIT_MMRT_DATA
#define DIRT_SPLIT_MMRT_DATA 0
#define DIRT_SPLIT_MMRT_DATA_SHIFT 0
#endif

#if defined(MMRT_HEADS_READONLY)
#define MMRT_HEADS_QUAL readonly
#else
#define MMRT_HEADS_QUAL
#endif
#if defined(MMRT_TAILS_READONLY)
#define MMRT_TAILS_QUAL readonly
#elif defined(MMRT_TAILS_WRITEONLY)
#define MMRT_TAILS_QUAL writeonly
#else
#define MMRT_TAILS_QUAL
#endif
#if defined(MMRT_IDS_READONLY)
#define MMRT_IDS_QUAL readonly
#elif defined(MMRT_IDS_WRITEONLY)
#define MMRT_IDS_QUAL writeonly
#else
#define MMRT_IDS_QUAL
#endif
#if defined(MMRT_DATA_READONLY)
#define MMRT_DATA_QUAL readonly
#elif defined(MMRT_DATA_WRITEONLY)
#define MMRT_DATA_QUAL writeonly
#else
#define MMRT_DATA_QUAL
#endif

// ---- bucket heads ----
#if DIRT_SPLIT_MMRT_HEADS == 0
layout(std430, binding = DIRT_BIND_MMRT_HEADS) MMRT_HEADS_QUAL buffer MmrtHeads {
    uint mmrt_heads[];
};
uint mmrt_head(uint i)
{
    return mmrt_heads[i];
}
#ifndef MMRT_HEADS_READONLY
void mmrt_head_store(uint i, uint v)
{
    mmrt_heads[i] = v;
}

uint mmrt_head_exchange(uint i, uint v)
{
    return atomicExchange(mmrt_heads[i], v);
}
#endif
#else
DIRT_SPLIT_IMAGES(DIRT_SPLIT_MMRT_HEADS, DIRT_IMAGE_SPLIT_MMRT_HEADS, r32ui,
                  MMRT_HEADS_QUAL uimageBuffer, mmrt_heads)
uint mmrt_head(uint i)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_MMRT_HEADS_SHIFT, 1u)
    uint r = 0u;
    DIRT_SPLIT_LOAD(DIRT_SPLIT_MMRT_HEADS, r, imageLoad, mmrt_heads, .x)
    return r;
}
#ifndef MMRT_HEADS_READONLY
void mmrt_head_store(uint i, uint v)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_MMRT_HEADS_SHIFT, 1u)
    DIRT_SPLIT_STORE(DIRT_SPLIT_MMRT_HEADS, imageStore, mmrt_heads, uvec4(v))
}

uint mmrt_head_exchange(uint i, uint v)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_MMRT_HEADS_SHIFT, 1u)
    uint r = 0u;
    DIRT_SPLIT_ATOMIC(DIRT_SPLIT_MMRT_HEADS, r, imageAtomicExchange, mmrt_heads, v)
    return r;
}
#endif
#endif

// ---- bucket tails ----
#if DIRT_SPLIT_MMRT_TAILS == 0
layout(std430, binding = DIRT_BIND_MMRT_TAILS) MMRT_TAILS_QUAL buffer MmrtTails {
    uint mmrt_tails[];
};
#ifndef MMRT_TAILS_WRITEONLY
uint mmrt_tail(uint i)
{
    return mmrt_tails[i];
}
#endif
#ifndef MMRT_TAILS_READONLY
void mmrt_tail_store(uint i, uint v)
{
    mmrt_tails[i] = v;
}
#endif
#else
DIRT_SPLIT_IMAGES(DIRT_SPLIT_MMRT_TAILS, DIRT_IMAGE_SPLIT_MMRT_TAILS, r32ui,
                  MMRT_TAILS_QUAL uimageBuffer, mmrt_tails)
#ifndef MMRT_TAILS_WRITEONLY
uint mmrt_tail(uint i)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_MMRT_TAILS_SHIFT, 1u)
    uint r = 0u;
    DIRT_SPLIT_LOAD(DIRT_SPLIT_MMRT_TAILS, r, imageLoad, mmrt_tails, .x)
    return r;
}
#endif
#ifndef MMRT_TAILS_READONLY
void mmrt_tail_store(uint i, uint v)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_MMRT_TAILS_SHIFT, 1u)
    DIRT_SPLIT_STORE(DIRT_SPLIT_MMRT_TAILS, imageStore, mmrt_tails, uvec4(v))
}
#endif
#endif

// ---- id nodes: field f (DIRT_MMRT_ID_Z, _NEXT, _PREV) of node n ----
#if DIRT_SPLIT_MMRT_IDS == 0
layout(std430, binding = DIRT_BIND_MMRT_IDS) MMRT_IDS_QUAL buffer MmrtIds {
    uint mmrt_ids[];
};
#ifndef MMRT_IDS_WRITEONLY
uint mmrt_id(uint n, uint f)
{
    return mmrt_ids[n * uint(DIRT_MMRT_ID_UINTS) + f];
}
#endif
#ifndef MMRT_IDS_READONLY
void mmrt_id_store(uint n, uint f, uint v)
{
    mmrt_ids[n * uint(DIRT_MMRT_ID_UINTS) + f] = v;
}
#endif
#else
DIRT_SPLIT_IMAGES(DIRT_SPLIT_MMRT_IDS, DIRT_IMAGE_SPLIT_MMRT_IDS, r32ui,
                  MMRT_IDS_QUAL uimageBuffer, mmrt_ids)
#ifndef MMRT_IDS_WRITEONLY
uint mmrt_id(uint n, uint f)
{
    DIRT_SPLIT_AT(n, DIRT_SPLIT_MMRT_IDS_SHIFT, DIRT_MMRT_ID_UINTS)
    t += int(f);
    uint r = 0u;
    DIRT_SPLIT_LOAD(DIRT_SPLIT_MMRT_IDS, r, imageLoad, mmrt_ids, .x)
    return r;
}
#endif
#ifndef MMRT_IDS_READONLY
void mmrt_id_store(uint n, uint f, uint v)
{
    DIRT_SPLIT_AT(n, DIRT_SPLIT_MMRT_IDS_SHIFT, DIRT_MMRT_ID_UINTS)
    t += int(f);
    DIRT_SPLIT_STORE(DIRT_SPLIT_MMRT_IDS, imageStore, mmrt_ids, uvec4(v))
}
#endif
#endif

// ---- data nodes ----
#if DIRT_SPLIT_MMRT_DATA == 0
layout(std430, binding = DIRT_BIND_MMRT_DATA) MMRT_DATA_QUAL buffer MmrtData {
    dirt_mmrt_gpu_data mmrt_data_nodes[];
};
#ifndef MMRT_DATA_WRITEONLY
dirt_mmrt_gpu_data mmrt_data(uint n)
{
    return mmrt_data_nodes[n];
}

// The primitive of data node n (its ids.x).
uint mmrt_data_prim(uint n)
{
    return mmrt_data_nodes[n].ids.x;
}
#endif
#ifndef MMRT_DATA_READONLY
void mmrt_data_store(uint n, dirt_mmrt_gpu_data d)
{
    mmrt_data_nodes[n] = d;
}
#endif
#else
DIRT_SPLIT_IMAGES(DIRT_SPLIT_MMRT_DATA, DIRT_IMAGE_SPLIT_MMRT_DATA, rgba32ui,
                  MMRT_DATA_QUAL uimageBuffer, mmrt_data)
#ifndef MMRT_DATA_WRITEONLY
// Texel j (0: ids, 1: attr bits) of data node n.
uvec4 mmrt_data_texel(uint n, uint j)
{
    DIRT_SPLIT_AT(n, DIRT_SPLIT_MMRT_DATA_SHIFT, 2u)
    t += int(j);
    uvec4 r = uvec4(0u);
    DIRT_SPLIT_LOAD(DIRT_SPLIT_MMRT_DATA, r, imageLoad, mmrt_data, .xyzw)
    return r;
}

dirt_mmrt_gpu_data mmrt_data(uint n)
{
    dirt_mmrt_gpu_data d;
    d.ids = mmrt_data_texel(n, 0u);
    d.attr = uintBitsToFloat(mmrt_data_texel(n, 1u));
    return d;
}

uint mmrt_data_prim(uint n)
{
    return mmrt_data_texel(n, 0u).x;
}
#endif
#ifndef MMRT_DATA_READONLY
void mmrt_data_store(uint n, dirt_mmrt_gpu_data d)
{
    DIRT_SPLIT_AT(n, DIRT_SPLIT_MMRT_DATA_SHIFT, 2u)
    DIRT_SPLIT_STORE(DIRT_SPLIT_MMRT_DATA, imageStore, mmrt_data, d.ids)
    t++;
    DIRT_SPLIT_STORE(DIRT_SPLIT_MMRT_DATA, imageStore, mmrt_data, floatBitsToUint(d.attr))
}
#endif
#endif
