// The MMRT A-buffer's arrays that grow with the views and the scene: the
// bucket heads and tails (uint per bucket and pixel), the id nodes
// (DIRT_MMRT_ID_UINTS uints per node: common/mmrt_layout.h) and the data
// nodes (dirt_mmrt_gpu_data). Each is one storage block while it fits
// (DIRT_BIND_MMRT_HEADS, _TAILS, _IDS, _DATA), else a split array
// (src/gl/split.h; DIRT_SPLIT_EACH) of DIRT_SPLIT_MMRT_<ARRAY> parts of
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
#define MMRT_HEADS_PART(k, a) \
    layout(r32ui, binding = DIRT_IMAGE_SPLIT_MMRT_HEADS + k) uniform MMRT_HEADS_QUAL \
        uimageBuffer mmrt_heads_part##k;
DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_HEADS, MMRT_HEADS_PART, 0)
#define MMRT_HEADS_LOAD(k, a) \
    if (part == uint(k)) r = imageLoad(mmrt_heads_part##k, t).x;
uint mmrt_head(uint i)
{
    uint part = i >> uint(DIRT_SPLIT_MMRT_HEADS_SHIFT);
    int t = int(i - (part << uint(DIRT_SPLIT_MMRT_HEADS_SHIFT)));
    uint r = 0u;
    DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_HEADS, MMRT_HEADS_LOAD, 0)
    return r;
}
#ifndef MMRT_HEADS_READONLY
#define MMRT_HEADS_STORE(k, a) \
    if (part == uint(k)) imageStore(mmrt_heads_part##k, t, uvec4(v));
void mmrt_head_store(uint i, uint v)
{
    uint part = i >> uint(DIRT_SPLIT_MMRT_HEADS_SHIFT);
    int t = int(i - (part << uint(DIRT_SPLIT_MMRT_HEADS_SHIFT)));
    DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_HEADS, MMRT_HEADS_STORE, 0)
}

#define MMRT_HEADS_EXCHANGE(k, a) \
    if (part == uint(k)) r = imageAtomicExchange(mmrt_heads_part##k, t, v);
uint mmrt_head_exchange(uint i, uint v)
{
    uint part = i >> uint(DIRT_SPLIT_MMRT_HEADS_SHIFT);
    int t = int(i - (part << uint(DIRT_SPLIT_MMRT_HEADS_SHIFT)));
    uint r = 0u;
    DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_HEADS, MMRT_HEADS_EXCHANGE, 0)
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
#define MMRT_TAILS_PART(k, a) \
    layout(r32ui, binding = DIRT_IMAGE_SPLIT_MMRT_TAILS + k) uniform MMRT_TAILS_QUAL \
        uimageBuffer mmrt_tails_part##k;
DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_TAILS, MMRT_TAILS_PART, 0)
#ifndef MMRT_TAILS_WRITEONLY
#define MMRT_TAILS_LOAD(k, a) \
    if (part == uint(k)) r = imageLoad(mmrt_tails_part##k, t).x;
uint mmrt_tail(uint i)
{
    uint part = i >> uint(DIRT_SPLIT_MMRT_TAILS_SHIFT);
    int t = int(i - (part << uint(DIRT_SPLIT_MMRT_TAILS_SHIFT)));
    uint r = 0u;
    DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_TAILS, MMRT_TAILS_LOAD, 0)
    return r;
}
#endif
#ifndef MMRT_TAILS_READONLY
#define MMRT_TAILS_STORE(k, a) \
    if (part == uint(k)) imageStore(mmrt_tails_part##k, t, uvec4(v));
void mmrt_tail_store(uint i, uint v)
{
    uint part = i >> uint(DIRT_SPLIT_MMRT_TAILS_SHIFT);
    int t = int(i - (part << uint(DIRT_SPLIT_MMRT_TAILS_SHIFT)));
    DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_TAILS, MMRT_TAILS_STORE, 0)
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
#define MMRT_IDS_PART(k, a) \
    layout(r32ui, binding = DIRT_IMAGE_SPLIT_MMRT_IDS + k) uniform MMRT_IDS_QUAL \
        uimageBuffer mmrt_ids_part##k;
DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_IDS, MMRT_IDS_PART, 0)
#ifndef MMRT_IDS_WRITEONLY
#define MMRT_IDS_LOAD(k, a) \
    if (part == uint(k)) r = imageLoad(mmrt_ids_part##k, t).x;
uint mmrt_id(uint n, uint f)
{
    uint part = n >> uint(DIRT_SPLIT_MMRT_IDS_SHIFT);
    int t = int((n - (part << uint(DIRT_SPLIT_MMRT_IDS_SHIFT))) * uint(DIRT_MMRT_ID_UINTS) + f);
    uint r = 0u;
    DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_IDS, MMRT_IDS_LOAD, 0)
    return r;
}
#endif
#ifndef MMRT_IDS_READONLY
#define MMRT_IDS_STORE(k, a) \
    if (part == uint(k)) imageStore(mmrt_ids_part##k, t, uvec4(v));
void mmrt_id_store(uint n, uint f, uint v)
{
    uint part = n >> uint(DIRT_SPLIT_MMRT_IDS_SHIFT);
    int t = int((n - (part << uint(DIRT_SPLIT_MMRT_IDS_SHIFT))) * uint(DIRT_MMRT_ID_UINTS) + f);
    DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_IDS, MMRT_IDS_STORE, 0)
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
#define MMRT_DATA_PART(k, a) \
    layout(rgba32ui, binding = DIRT_IMAGE_SPLIT_MMRT_DATA + k) uniform MMRT_DATA_QUAL \
        uimageBuffer mmrt_data_part##k;
DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_DATA, MMRT_DATA_PART, 0)
#ifndef MMRT_DATA_WRITEONLY
#define MMRT_DATA_LOAD(k, a) \
    if (part == uint(k)) r = imageLoad(mmrt_data_part##k, t);
// Texel j (0: ids, 1: attr bits) of data node n.
uvec4 mmrt_data_texel(uint n, uint j)
{
    uint part = n >> uint(DIRT_SPLIT_MMRT_DATA_SHIFT);
    int t = int(2u * (n - (part << uint(DIRT_SPLIT_MMRT_DATA_SHIFT))) + j);
    uvec4 r = uvec4(0u);
    DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_DATA, MMRT_DATA_LOAD, 0)
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
#define MMRT_DATA_STORE(k, a) \
    if (part == uint(k)) { \
        imageStore(mmrt_data_part##k, t, d.ids); \
        imageStore(mmrt_data_part##k, t + 1, floatBitsToUint(d.attr)); \
    }
void mmrt_data_store(uint n, dirt_mmrt_gpu_data d)
{
    uint part = n >> uint(DIRT_SPLIT_MMRT_DATA_SHIFT);
    int t = int(2u * (n - (part << uint(DIRT_SPLIT_MMRT_DATA_SHIFT))));
    DIRT_SPLIT_EACH(DIRT_SPLIT_MMRT_DATA, MMRT_DATA_STORE, 0)
}
#endif
#endif
