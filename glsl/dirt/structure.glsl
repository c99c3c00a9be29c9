// The DIRT structure's arrays that grow with the scene and the views: the
// build's candidates (uvec4, common/layout.h), the id nodes (uvec2
// (primitive, next)) and the list heads (uint per bucket and tile). Each is
// one storage block while it fits (DIRT_BIND_CANDIDATES, _NODES, _HEADS),
// else a split array (src/gl/split.h; common/split.glsl) of DIRT_SPLIT_<ARRAY> parts of
// 2^DIRT_SPLIT_<ARRAY>_SHIFT records: images at DIRT_IMAGE_SPLIT_<ARRAY> +
// part (RGBA32UI, RG32UI, R32UI). A shader that only reads or only writes an
// array defines DIRT_<ARRAY>_READONLY or _WRITEONLY first (the storage
// block's qualifier, as it always was; only the accessors it may use are
// declared); one that does not use an array at all defines DIRT_<ARRAY>_NONE
// (candidates only: a shader's storage blocks are limited, 16 on llvmpipe).
// Accessors by record index: dirt_candidate(i),
// dirt_candidate_store(i, c), dirt_candidate_store_zw(i, zw); dirt_node(i),
// dirt_node_store(i, n), dirt_work_record(r), dirt_work_record_store(r, w);
// dirt_head(i), dirt_head_exchange(i, v), dirt_head_add(i, v),
// dirt_head_and(i, v) (atomic). Bucket occupancy masks (common/constants.h,
// DIRT_BUCKET_MASK_*): dirt_bucket_bits, dirt_bucket_occupancy.
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
DIRT_SPLIT_IMAGES(DIRT_SPLIT_CANDIDATES, DIRT_IMAGE_SPLIT_CANDIDATES, rgba32ui,
                  DIRT_CANDIDATES_QUAL uimageBuffer, dirt_candidates)
#ifndef DIRT_CANDIDATES_WRITEONLY
uvec4 dirt_candidate(uint i)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_CANDIDATES_SHIFT, 1u)
    uvec4 r = uvec4(0u);
    DIRT_SPLIT_LOAD(DIRT_SPLIT_CANDIDATES, r, imageLoad, dirt_candidates, .xyzw)
    return r;
}
#endif
#ifndef DIRT_CANDIDATES_READONLY
void dirt_candidate_store(uint i, uvec4 c)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_CANDIDATES_SHIFT, 1u)
    DIRT_SPLIT_STORE(DIRT_SPLIT_CANDIDATES, imageStore, dirt_candidates, c)
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
DIRT_SPLIT_IMAGES(DIRT_SPLIT_NODES, DIRT_IMAGE_SPLIT_NODES, rg32ui,
                  DIRT_NODES_QUAL uimageBuffer, dirt_nodes)
#ifndef DIRT_NODES_WRITEONLY
uvec2 dirt_node(uint i)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_NODES_SHIFT, 1u)
    uvec2 r = uvec2(0u);
    DIRT_SPLIT_LOAD(DIRT_SPLIT_NODES, r, imageLoad, dirt_nodes, .xy)
    return r;
}
#endif
#ifndef DIRT_NODES_READONLY
void dirt_node_store(uint i, uvec2 n)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_NODES_SHIFT, 1u)
    DIRT_SPLIT_STORE(DIRT_SPLIT_NODES, imageStore, dirt_nodes, uvec4(n, 0u, 0u))
}
#endif
#endif

// A work record of the compute build (common/layout.h) in the node pool,
// which holds no node until the fill pass: record r is nodes 2r and 2r + 1
// (DIRT_WORK_RECORD_NODES).
#ifndef DIRT_NODES_WRITEONLY
uvec4 dirt_work_record(uint r)
{
    return uvec4(dirt_node(uint(DIRT_WORK_RECORD_NODES) * r),
                 dirt_node(uint(DIRT_WORK_RECORD_NODES) * r + 1u));
}
#endif
#ifndef DIRT_NODES_READONLY
void dirt_work_record_store(uint r, uvec4 w)
{
    dirt_node_store(uint(DIRT_WORK_RECORD_NODES) * r, w.xy);
    dirt_node_store(uint(DIRT_WORK_RECORD_NODES) * r + 1u, w.zw);
}
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

uint dirt_head_add(uint i, uint v)
{
    return atomicAdd(heads[i], v);
}

uint dirt_head_and(uint i, uint v)
{
    return atomicAnd(heads[i], v);
}
#endif
#else
DIRT_SPLIT_IMAGES(DIRT_SPLIT_HEADS, DIRT_IMAGE_SPLIT_HEADS, r32ui,
                  DIRT_HEADS_QUAL uimageBuffer, dirt_heads)
#ifndef DIRT_HEADS_WRITEONLY
uint dirt_head(uint i)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_HEADS_SHIFT, 1u)
    uint r = 0u;
    DIRT_SPLIT_LOAD(DIRT_SPLIT_HEADS, r, imageLoad, dirt_heads, .x)
    return r;
}
#endif
#if !defined(DIRT_HEADS_READONLY) && !defined(DIRT_HEADS_WRITEONLY)
uint dirt_head_exchange(uint i, uint v)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_HEADS_SHIFT, 1u)
    uint r = 0u;
    DIRT_SPLIT_ATOMIC(DIRT_SPLIT_HEADS, r, imageAtomicExchange, dirt_heads, v)
    return r;
}

uint dirt_head_add(uint i, uint v)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_HEADS_SHIFT, 1u)
    uint r = 0u;
    DIRT_SPLIT_ATOMIC(DIRT_SPLIT_HEADS, r, imageAtomicAdd, dirt_heads, v)
    return r;
}

uint dirt_head_and(uint i, uint v)
{
    DIRT_SPLIT_AT(i, DIRT_SPLIT_HEADS_SHIFT, 1u)
    uint r = 0u;
    DIRT_SPLIT_ATOMIC(DIRT_SPLIT_HEADS, r, imageAtomicAnd, dirt_heads, v)
    return r;
}
#endif
#endif

// ---- adaptive depth buckets (common/constants.h, DIRT_ADAPT_*) ----
// dirt_fine_bin(z, zlo, range, H): the fine bin of depth z in a tile of
// bounds [zlo, zlo + range] (eq. 1a/1b with H bins); dirt_adapt_edge(gt, b,
// B, T): edge e(b) of tile gt (0 for b = 0, H for b = B); dirt_adapt_bucket:
// the bucket of fine bin f (the number of edges e(1..B-1) at or below f).
int dirt_fine_bin(float z, float zlo, float range, int H)
{
    if (!(range > 0.0))
        return 0;
    return clamp(int(floor(float(H) * (z - zlo) / range)), 0, H - 1);
}

#ifndef DIRT_HEADS_WRITEONLY
int dirt_adapt_edge(uint gt, int b, int B, uint T)
{
    if (b <= 0)
        return 0;
    if (b >= B)
        return DIRT_ADAPT_FINE * B;
    uint w = dirt_head(uint(B) * T + gt * uint(DIRT_ADAPT_EDGE_WORDS(B)) + uint(b - 1) / 2u);
    return int((b & 1) != 0 ? w & 0xFFFFu : w >> 16);
}

int dirt_adapt_bucket(uint gt, int f, int B, uint T)
{
    int b = 0;
    uint base = uint(B) * T + gt * uint(DIRT_ADAPT_EDGE_WORDS(B));
    for (int k = 1; k < B; k += 2) {
        uint w = dirt_head(base + uint(k - 1) / 2u);
        b += int(w & 0xFFFFu) <= f ? 1 : 0;
        if (k + 1 < B)
            b += int(w >> 16) <= f ? 1 : 0;
    }
    return b;
}
#endif

// ---- node depth ranges (common/layout.h, DIRT_NODE_DEPTH_*) ----
// dirt_node_depth_q(z, zlo, range, n): depth z's position in a tile of
// bounds [zlo, zlo + range] cut into n equal parts, before the floor of eq.
// 1a/1b (n = B: uniform buckets, bucket b is [b, b + 1); n = H: adaptive,
// bucket b is [e(b), e(b+1)) in fine bins), clamped to [-1, n + 1]; 0 when
// range is 0. dirt_node_depth_sub(q, q0, q1): the sub-slab of position q in
// the bucket [q0, q1), of DIRT_NODE_DEPTH_SLABS equal ones, clamped to them
// (0 for an empty bucket). The count pass and the trace compute both alike,
// so for one bucket they are monotonic in z for both: a primitive's range
// that meets the ray's depth span there has a sub-slab among the span's.
float dirt_node_depth_q(float z, float zlo, float range, int n)
{
    if (!(range > 0.0))
        return 0.0;
    return clamp(float(n) * (z - zlo) / range, -1.0, float(n + 1));
}

uint dirt_node_depth_sub(float q, float q0, float q1)
{
    if (!(q1 > q0))
        return 0u;
    float s = floor(float(DIRT_NODE_DEPTH_SLABS) * (q - q0) / (q1 - q0));
    return uint(clamp(s, 0.0, float(DIRT_NODE_DEPTH_SLABS - 1)));
}

// The next node of raw next word `raw` of a build that stored depth ranges
// (DIRT_LIST_END at the end of the list), and its range byte.
uint dirt_node_next_of(uint raw)
{
    uint n = raw & DIRT_NODE_NEXT_MASK;
    return n == DIRT_NODE_NEXT_END ? DIRT_LIST_END : n;
}

// ---- bucket occupancy masks (common/constants.h, DIRT_BUCKET_MASK_*) ----
// dirt_bucket_bits(b0, b1): the bits of buckets min(b0, b1) .. max(b0, b1)
// (both below DIRT_BUCKET_MASK_MAX_BUCKETS). dirt_bucket_mask_index(gt, B,
// T): the word of tile gt's mask (B <= DIRT_BUCKET_MASK_MAX_BUCKETS; the
// layout of the build's bucket kind: DIRT_ADAPTIVE or uniform).
// dirt_bucket_occupancy(gt, B, T): uniform buckets: bit s set when some
// candidate's depth range in tile gt meets its depth slab s (dirt_mask_slab);
// adaptive: bit b set when bucket b holds a node; every bit set (nothing
// known) when B has no masks. dirt_mask_slab(z, zlo, range): the slab of
// depth z in a tile of bounds [zlo, zlo + range] (uniform buckets' masks;
// the count pass and the trace compute it alike, so it is monotonic in z
// for both: a range that meets a span has a slab in the span's).
uint dirt_bucket_bits(int b0, int b1)
{
    uint lo = uint(min(b0, b1)), hi = uint(max(b0, b1));
    return ((2u << hi) - 1u) & ~((1u << lo) - 1u);
}

int dirt_mask_slab(float z, float zlo, float range)
{
    if (!(range > 0.0))
        return 0;
    return clamp(int(floor(float(DIRT_BUCKET_MASK_SLABS) * (z - zlo) / range)), 0,
                 DIRT_BUCKET_MASK_SLABS - 1);
}

uint dirt_bucket_mask_index(uint gt, int B, uint T)
{
#ifdef DIRT_ADAPTIVE
    return uint(DIRT_BUCKET_MASK_INDEX(uint(DIRT_ADAPT_TILE_UINTS(B)), T, gt));
#else
    return uint(DIRT_BUCKET_MASK_INDEX(uint(B), T, gt));
#endif
}

#ifndef DIRT_HEADS_WRITEONLY
uint dirt_bucket_occupancy(uint gt, int B, uint T)
{
    if (B > DIRT_BUCKET_MASK_MAX_BUCKETS)
        return ~0u;
    return ~dirt_head(dirt_bucket_mask_index(gt, B, T));
}
#endif
