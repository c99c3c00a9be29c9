#version 450 core
// MMRT reorder pass: one invocation per pixel (all views; launched in rows,
// common/rows.glsl). Sorts each of the
// pixel's B bucket lists by depth, nearest first, ties broken by primitive
// id (a total order: a primitive has at most one fragment per pixel), then
// sets the next/prev pointers, the head (nearest) and tail (farthest) of
// every non-empty bucket (the build clears the tails, so empty buckets cost
// one read). Lists of one or two nodes are linked directly. Longer ones:
//  default:         chunks of DIRT_MMRT_SORT_CHUNK nodes are sorted in
//                   registers (a fixed sorting network, constant indices) and
//                   merged into the sorted list: one chunk for short lists,
//                   O(n * n / chunk) for a list of n;
//  MMRT_SORT_LIST:  insertion sort in the list itself (O(n^2) reads; no
//                   arrays: 2-4x faster on llvmpipe, whose SIMD lanes pay for
//                   the network's masked comparators).
// Both keep every node and give the same order.
#include "common/layout.h"
#include "common/mmrt_layout.h"
#include "common/rows.glsl"

layout(local_size_x = DIRT_GROUP_SIZE) in;

layout(std430, binding = DIRT_BIND_MMRT_PARAMS) readonly buffer Params {
    dirt_mmrt_gpu_params params;
};
#define MMRT_TAILS_WRITEONLY
#define MMRT_DATA_READONLY
#include "mmrt/arrays.glsl"
layout(std430, binding = DIRT_BIND_MMRT_COUNTERS) buffer Counters {
    dirt_mmrt_gpu_counters counters;
};

// The register sort below is a fixed sorting network on 8 entries.
#if DIRT_MMRT_SORT_CHUNK != 8
#error "reorder.comp sorts chunks of 8"
#endif
#define CHUNK 8

#define inf uintBitsToFloat(0x7F800000u)

float node_z(uint n)
{
    return uintBitsToFloat(mmrt_id(n, uint(DIRT_MMRT_ID_Z)));
}

uint node_next(uint n)
{
    return mmrt_id(n, uint(DIRT_MMRT_ID_NEXT));
}

void set_next(uint n, uint next)
{
    mmrt_id_store(n, uint(DIRT_MMRT_ID_NEXT), next);
}

void set_prev(uint n, uint prev)
{
    mmrt_id_store(n, uint(DIRT_MMRT_ID_PREV), prev);
}

// Strict order of fragments (a, za) < (b, zb): depth, then primitive id,
// then node index. Padding entries (DIRT_LIST_END, +inf) sort last.
bool before(uint a, float za, uint b, float zb)
{
    if (za != zb)
        return za < zb;
    if (a == DIRT_LIST_END || b == DIRT_LIST_END)
        return a < b;
    uint pa = mmrt_data_prim(a), pb = mmrt_data_prim(b);
    return pa != pb ? pa < pb : a < b;
}

#ifndef MMRT_SORT_LIST
// Compare-exchange of entries a, b (compile-time constants, so the chunk
// arrays idx/key of main() stay in registers).
#define CX(a, b)                                                  \
    if (before(idx[b], key[b], idx[a], key[a])) {                 \
        uint ti = idx[a];                                         \
        idx[a] = idx[b];                                          \
        idx[b] = ti;                                              \
        float tk = key[a];                                        \
        key[a] = key[b];                                          \
        key[b] = tk;                                              \
    }

// Batcher's odd-even merge sort network for 8 entries (19 comparators).
#define SORT_CHUNK()                                              \
    CX(0, 1) CX(2, 3) CX(4, 5) CX(6, 7)                           \
    CX(0, 2) CX(1, 3) CX(4, 6) CX(5, 7)                           \
    CX(1, 2) CX(5, 6)                                             \
    CX(0, 4) CX(1, 5) CX(2, 6) CX(3, 7)                           \
    CX(2, 4) CX(3, 5)                                             \
    CX(1, 2) CX(3, 4) CX(5, 6)
#endif

// Sorts the non-empty list of `slot` (= bucket * pixels + pixel), sets its
// head, tail, next and prev pointers; returns its length.
uint sort_bucket(uint slot)
{
    uint rest = mmrt_head(slot);     // nodes not sorted yet (original order)
    uint second = node_next(rest);
    if (second == DIRT_LIST_END || node_next(second) == DIRT_LIST_END) {
        // One or two nodes (the common case): no sort needed beyond a swap.
        uint a = rest, c = second;
        if (c != DIRT_LIST_END && before(c, node_z(c), a, node_z(a))) {
            a = second;
            c = rest;
        }
        set_prev(a, DIRT_LIST_END);
        set_next(a, c);
        if (c != DIRT_LIST_END) {
            set_prev(c, a);
            set_next(c, DIRT_LIST_END);
        }
        mmrt_head_store(slot, a);
        mmrt_tail_store(slot, c != DIRT_LIST_END ? c : a);
        return c != DIRT_LIST_END ? 2u : 1u;
    }
    uint sorted = DIRT_LIST_END; // sorted list built so far
    uint count = 0u;
    uint chunks = 0u;
#ifdef MMRT_SORT_LIST
    // Insertion sort in the list itself: each node is linked into the
    // sorted list, walking it from its head.
    while (rest != DIRT_LIST_END) {
        uint node = rest;
        float z = node_z(node);
        rest = node_next(node);
        count++;
        if (sorted == DIRT_LIST_END || before(node, z, sorted, node_z(sorted))) {
            set_next(node, sorted);
            sorted = node;
        } else {
            uint p = sorted, q = node_next(sorted);
            while (q != DIRT_LIST_END && !before(node, z, q, node_z(q))) {
                p = q;
                q = node_next(q);
            }
            set_next(node, q);
            set_next(p, node);
        }
    }
    chunks = (count + uint(CHUNK) - 1u) / uint(CHUNK);
#else
    uint idx[CHUNK];
    float key[CHUNK];
    while (rest != DIRT_LIST_END) {
        // Up to CHUNK nodes into registers, padded with (END, +inf).
        for (int k = 0; k < CHUNK; k++) {
            if (rest != DIRT_LIST_END) {
                idx[k] = rest;
                key[k] = node_z(rest);
                rest = node_next(rest);
                count++;
            } else {
                idx[k] = DIRT_LIST_END;
                key[k] = inf;
            }
        }
        SORT_CHUNK()
        // Merge the chunk with the sorted list (next pointers only).
        uint s = sorted;
        float zs = s != DIRT_LIST_END ? node_z(s) : inf;
        uint first = DIRT_LIST_END, last = DIRT_LIST_END;
        while (idx[0] != DIRT_LIST_END || s != DIRT_LIST_END) {
            uint pick;
            if (idx[0] != DIRT_LIST_END &&
                (s == DIRT_LIST_END || before(idx[0], key[0], s, zs))) {
                pick = idx[0];
                for (int k = 0; k < CHUNK - 1; k++) {
                    idx[k] = idx[k + 1];
                    key[k] = key[k + 1];
                }
                idx[CHUNK - 1] = DIRT_LIST_END;
                key[CHUNK - 1] = inf;
            } else {
                pick = s;
                s = node_next(s);
                zs = s != DIRT_LIST_END ? node_z(s) : inf;
            }
            if (last == DIRT_LIST_END)
                first = pick;
            else
                set_next(last, pick);
            last = pick;
        }
        set_next(last, DIRT_LIST_END);
        sorted = first;
        chunks++;
    }
#endif
    // prev pointers, head and tail.
    uint prev = DIRT_LIST_END;
    for (uint n = sorted; n != DIRT_LIST_END; n = node_next(n)) {
        set_prev(n, prev);
        prev = n;
    }
    mmrt_head_store(slot, sorted);
    mmrt_tail_store(slot, prev);
    if (chunks > 1u)
        atomicAdd(counters.build.z, 1u);
    return count;
}

void main()
{
    uint g = dirt_row_invocation();
    uint pixels = uint(params.config.z);
    if (g >= pixels)
        return;
    int B = params.config.y;
    uint layers = 0u;
    // Non-empty buckets first, 32 at a time, as a bit mask: the sort then
    // runs once per non-empty bucket (SIMD lanes diverge far less than when
    // looping over all B). Tails of empty buckets stay as the build cleared
    // them (DIRT_LIST_END).
    for (int base = 0; base < B; base += 32) {
        uint mask = 0u;
        int nb = min(32, B - base);
        for (int k = 0; k < nb; k++) {
            if (mmrt_head(uint(base + k) * pixels + g) != DIRT_LIST_END)
                mask |= 1u << uint(k);
        }
        while (mask != 0u) {
            int b = base + findLSB(mask);
            mask &= mask - 1u;
            layers += sort_bucket(uint(b) * pixels + g);
        }
    }
    if (layers > 0u) {
        atomicMax(counters.build.y, layers);
        atomicAdd(counters.build.w, 1u);
    }
}
