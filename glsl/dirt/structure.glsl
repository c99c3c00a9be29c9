// The DIRT structure's arrays that grow with the scene and the views: the
// build's candidates (uvec4, common/layout.h), the id nodes (uvec2
// (primitive, next)) and the list heads (uint per bucket and tile). Each is
// one storage block while it fits (DIRT_BIND_CANDIDATES, _NODES, _HEADS),
// else a split array (src/gl/split.h; DIRT_SPLIT_EACH) of DIRT_SPLIT_<ARRAY> parts of
// 2^DIRT_SPLIT_<ARRAY>_SHIFT records: images at DIRT_IMAGE_SPLIT_<ARRAY> +
// part (RGBA32UI, RG32UI, R32UI). A shader that only reads or only writes an
// array defines DIRT_<ARRAY>_READONLY or _WRITEONLY first (the storage
// block's qualifier, as it always was; only the accessors it may use are
// declared); one that does not use an array at all defines DIRT_<ARRAY>_NONE
// (candidates only: a shader's storage blocks are limited, 16 on llvmpipe).
// Accessors by record index: dirt_candidate(i),
// dirt_candidate_store(i, c), dirt_candidate_store_zw(i, zw); dirt_node(i),
// dirt_node_store(i, n); dirt_head(i), dirt_head_exchange(i, v) (atomic).
// Needs common/layout.h.

#ifndef DIRT_SPLIT_CANDIDATES
#define DIRT_SPLIT_CANDIDATES 0
#define DIRT_SPLIT_CANDIDATES_SHIFT 0
#endif
#ifndef DIRT_SPLIT_NODES
#define DIRT_SPLIT_NODES 0
#define DIRT_SPLIT_NODES_SHIFT 0
#endif
#ifndef DIRT_SPLIT_HEADS
#define DIRT_SPLIT_HEADS 0
#define DIRT_SPLIT_HEADS_SHIFT 0
#endif

#if defined(DIRT_CANDIDATES_READONLY)
#define DIRT_CANDIDATES_QUAL readonly
#elif defined(DIRT_CANDIDATES_WRITEONLY)
#define DIRT_CANDIDATES_QUAL writeonly
#else
#define DIRT_CANDIDATES_QUAL
#endif
#if defined(DIRT_NODES_READONLY)
#define DIRT_NODES_QUAL readonly
#elif defined(DIRT_NODES_WRITEONLY)
#define DIRT_NODES_QUAL writeonly
#else
#define DIRT_NODES_QUAL
#endif
#if defined(DIRT_HEADS_READONLY)
#define DIRT_HEADS_QUAL readonly
#elif defined(DIRT_HEADS_WRITEONLY)
#define DIRT_HEADS_QUAL writeonly
#else
#define DIRT_HEADS_QUAL
#endif

// ---- candidates ----
#ifndef DIRT_CANDIDATES_NONE
#if DIRT_SPLIT_CANDIDATES == 0
layout(std430, binding = DIRT_BIND_CANDIDATES) DIRT_CANDIDATES_QUAL buffer Candidates {
    uvec4 candidates[];
};
#ifndef DIRT_CANDIDATES_WRITEONLY
uvec4 dirt_candidate(uint i)
{
    return candidates[i];
}
#endif
#ifndef DIRT_CANDIDATES_READONLY
void dirt_candidate_store(uint i, uvec4 c)
{
    candidates[i] = c;
}

void dirt_candidate_store_zw(uint i, uvec2 zw)
{
    candidates[i].zw = zw;
}
#endif
#else
#define DIRT_CANDIDATES_PART(k, a) \
    layout(rgba32ui, binding = DIRT_IMAGE_SPLIT_CANDIDATES + k) uniform DIRT_CANDIDATES_QUAL \
        uimageBuffer dirt_candidates_part##k;
DIRT_SPLIT_EACH(DIRT_SPLIT_CANDIDATES, DIRT_CANDIDATES_PART, 0)
#ifndef DIRT_CANDIDATES_WRITEONLY
#define DIRT_CANDIDATES_LOAD(k, a) \
    if (part == uint(k)) r = imageLoad(dirt_candidates_part##k, t);
uvec4 dirt_candidate(uint i)
{
    uint part = i >> uint(DIRT_SPLIT_CANDIDATES_SHIFT);
    int t = int(i - (part << uint(DIRT_SPLIT_CANDIDATES_SHIFT)));
    uvec4 r = uvec4(0u);
    DIRT_SPLIT_EACH(DIRT_SPLIT_CANDIDATES, DIRT_CANDIDATES_LOAD, 0)
    return r;
}
#endif
#ifndef DIRT_CANDIDATES_READONLY
#define DIRT_CANDIDATES_STORE(k, a) \
    if (part == uint(k)) imageStore(dirt_candidates_part##k, t, c);
void dirt_candidate_store(uint i, uvec4 c)
{
    uint part = i >> uint(DIRT_SPLIT_CANDIDATES_SHIFT);
    int t = int(i - (part << uint(DIRT_SPLIT_CANDIDATES_SHIFT)));
    DIRT_SPLIT_EACH(DIRT_SPLIT_CANDIDATES, DIRT_CANDIDATES_STORE, 0)
}
#endif
#if !defined(DIRT_CANDIDATES_READONLY) && !defined(DIRT_CANDIDATES_WRITEONLY)
void dirt_candidate_store_zw(uint i, uvec2 zw)
{
    dirt_candidate_store(i, uvec4(dirt_candidate(i).xy, zw));
}
#endif
#endif

#endif // DIRT_CANDIDATES_NONE

// ---- id nodes ----
#if DIRT_SPLIT_NODES == 0
layout(std430, binding = DIRT_BIND_NODES) DIRT_NODES_QUAL buffer Nodes {
    uvec2 nodes[];
};
#ifndef DIRT_NODES_WRITEONLY
uvec2 dirt_node(uint i)
{
    return nodes[i];
}
#endif
#ifndef DIRT_NODES_READONLY
void dirt_node_store(uint i, uvec2 n)
{
    nodes[i] = n;
}
#endif
#else
#define DIRT_NODES_PART(k, a) \
    layout(rg32ui, binding = DIRT_IMAGE_SPLIT_NODES + k) uniform DIRT_NODES_QUAL uimageBuffer \
        dirt_nodes_part##k;
DIRT_SPLIT_EACH(DIRT_SPLIT_NODES, DIRT_NODES_PART, 0)
#ifndef DIRT_NODES_WRITEONLY
#define DIRT_NODES_LOAD(k, a) \
    if (part == uint(k)) r = imageLoad(dirt_nodes_part##k, t).xy;
uvec2 dirt_node(uint i)
{
    uint part = i >> uint(DIRT_SPLIT_NODES_SHIFT);
    int t = int(i - (part << uint(DIRT_SPLIT_NODES_SHIFT)));
    uvec2 r = uvec2(0u);
    DIRT_SPLIT_EACH(DIRT_SPLIT_NODES, DIRT_NODES_LOAD, 0)
    return r;
}
#endif
#ifndef DIRT_NODES_READONLY
#define DIRT_NODES_STORE(k, a) \
    if (part == uint(k)) imageStore(dirt_nodes_part##k, t, uvec4(n, 0u, 0u));
void dirt_node_store(uint i, uvec2 n)
{
    uint part = i >> uint(DIRT_SPLIT_NODES_SHIFT);
    int t = int(i - (part << uint(DIRT_SPLIT_NODES_SHIFT)));
    DIRT_SPLIT_EACH(DIRT_SPLIT_NODES, DIRT_NODES_STORE, 0)
}
#endif
#endif

// ---- list heads ----
#if DIRT_SPLIT_HEADS == 0
layout(std430, binding = DIRT_BIND_HEADS) DIRT_HEADS_QUAL buffer Heads {
    uint heads[];
};
#ifndef DIRT_HEADS_WRITEONLY
uint dirt_head(uint i)
{
    return heads[i];
}
#endif
#if !defined(DIRT_HEADS_READONLY) && !defined(DIRT_HEADS_WRITEONLY)
uint dirt_head_exchange(uint i, uint v)
{
    return atomicExchange(heads[i], v);
}
#endif
#else
#define DIRT_HEADS_PART(k, a) \
    layout(r32ui, binding = DIRT_IMAGE_SPLIT_HEADS + k) uniform DIRT_HEADS_QUAL uimageBuffer \
        dirt_heads_part##k;
DIRT_SPLIT_EACH(DIRT_SPLIT_HEADS, DIRT_HEADS_PART, 0)
#ifndef DIRT_HEADS_WRITEONLY
#define DIRT_HEADS_LOAD(k, a) \
    if (part == uint(k)) r = imageLoad(dirt_heads_part##k, t).x;
uint dirt_head(uint i)
{
    uint part = i >> uint(DIRT_SPLIT_HEADS_SHIFT);
    int t = int(i - (part << uint(DIRT_SPLIT_HEADS_SHIFT)));
    uint r = 0u;
    DIRT_SPLIT_EACH(DIRT_SPLIT_HEADS, DIRT_HEADS_LOAD, 0)
    return r;
}
#endif
#if !defined(DIRT_HEADS_READONLY) && !defined(DIRT_HEADS_WRITEONLY)
#define DIRT_HEADS_EXCHANGE(k, a) \
    if (part == uint(k)) r = imageAtomicExchange(dirt_heads_part##k, t, v);
uint dirt_head_exchange(uint i, uint v)
{
    uint part = i >> uint(DIRT_SPLIT_HEADS_SHIFT);
    int t = int(i - (part << uint(DIRT_SPLIT_HEADS_SHIFT)));
    uint r = 0u;
    DIRT_SPLIT_EACH(DIRT_SPLIT_HEADS, DIRT_HEADS_EXCHANGE, 0)
    return r;
}
#endif
#endif
