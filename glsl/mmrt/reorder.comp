#version 450 core
// MMRT reorder pass: one invocation per pixel (all views). Sorts each of the
// pixel's B bucket lists by depth, nearest first, ties broken by primitive
// id (a total order: a primitive has at most one fragment per pixel), then
// sets the next/prev pointers, the head (nearest) and tail (farthest) of
// every bucket. Lists of up to DIRT_MMRT_SORT_CHUNK nodes are sorted in
// registers (insertion sort); longer lists are consumed in chunks of that
// size, each sorted in registers and merged into the sorted list, so nothing
// is ever dropped (cost O(n * n / chunk) for a list of n).
#include "common/layout.h"
#include "common/mmrt_layout.h"

layout(local_size_x = 64) in;

layout(std430, binding = DIRT_BIND_MMRT_PARAMS) readonly buffer Params {
    dirt_mmrt_gpu_params params;
};
layout(std430, binding = DIRT_BIND_MMRT_HEADS) buffer Heads {
    uint heads[];
};
layout(std430, binding = DIRT_BIND_MMRT_TAILS) writeonly buffer Tails {
    uint tails[];
};
layout(std430, binding = DIRT_BIND_MMRT_IDS) buffer Ids {
    uint ids[];
};
layout(std430, binding = DIRT_BIND_MMRT_DATA) readonly buffer Data {
    dirt_mmrt_gpu_data data[];
};
layout(std430, binding = DIRT_BIND_MMRT_COUNTERS) buffer Counters {
    dirt_mmrt_gpu_counters counters;
};

#define CHUNK DIRT_MMRT_SORT_CHUNK

float node_z(uint n)
{
    return uintBitsToFloat(ids[n * uint(DIRT_MMRT_ID_UINTS) + uint(DIRT_MMRT_ID_Z)]);
}

uint node_next(uint n)
{
    return ids[n * uint(DIRT_MMRT_ID_UINTS) + uint(DIRT_MMRT_ID_NEXT)];
}

void set_next(uint n, uint next)
{
    ids[n * uint(DIRT_MMRT_ID_UINTS) + uint(DIRT_MMRT_ID_NEXT)] = next;
}

void set_prev(uint n, uint prev)
{
    ids[n * uint(DIRT_MMRT_ID_UINTS) + uint(DIRT_MMRT_ID_PREV)] = prev;
}

// Strict order of fragments (a, za) < (b, zb).
bool before(uint a, float za, uint b, float zb)
{
    if (za != zb)
        return za < zb;
    uint pa = data[a].ids.x, pb = data[b].ids.x;
    return pa != pb ? pa < pb : a < b;
}

void main()
{
    uint g = gl_GlobalInvocationID.x;
    uint pixels = uint(params.config.z);
    if (g >= pixels)
        return;
    int B = params.config.y;
    uint layers = 0u;
    for (int b = 0; b < B; b++) {
        uint slot = uint(b) * pixels + g;
        uint rest = heads[slot];    // nodes not sorted yet (original order)
        uint sorted = DIRT_LIST_END; // sorted list built so far
        uint count = 0u;
        uint chunks = 0u;
        while (rest != DIRT_LIST_END) {
            uint idx[CHUNK];
            float key[CHUNK];
            int n = 0;
            while (rest != DIRT_LIST_END && n < CHUNK) {
                idx[n] = rest;
                key[n] = node_z(rest);
                rest = node_next(rest);
                n++;
            }
            // Insertion sort of the chunk in registers.
            for (int i = 1; i < n; i++) {
                uint ni = idx[i];
                float ki = key[i];
                int j = i - 1;
                while (j >= 0 && before(ni, ki, idx[j], key[j])) {
                    idx[j + 1] = idx[j];
                    key[j + 1] = key[j];
                    j--;
                }
                idx[j + 1] = ni;
                key[j + 1] = ki;
            }
            // Merge the chunk with the sorted list (next pointers only).
            uint s = sorted;
            float zs = s != DIRT_LIST_END ? node_z(s) : 0.0;
            uint first = DIRT_LIST_END, last = DIRT_LIST_END;
            int i = 0;
            while (i < n || s != DIRT_LIST_END) {
                uint pick;
                if (i < n && (s == DIRT_LIST_END || before(idx[i], key[i], s, zs))) {
                    pick = idx[i++];
                } else {
                    pick = s;
                    s = node_next(s);
                    zs = s != DIRT_LIST_END ? node_z(s) : 0.0;
                }
                if (last == DIRT_LIST_END)
                    first = pick;
                else
                    set_next(last, pick);
                last = pick;
            }
            set_next(last, DIRT_LIST_END);
            sorted = first;
            count += uint(n);
            chunks++;
        }
        // prev pointers, head and tail.
        uint prev = DIRT_LIST_END;
        for (uint n = sorted; n != DIRT_LIST_END; n = node_next(n)) {
            set_prev(n, prev);
            prev = n;
        }
        heads[slot] = sorted;
        tails[slot] = prev;
        layers += count;
        if (chunks > 1u)
            atomicAdd(counters.build.z, 1u);
    }
    if (layers > 0u) {
        atomicMax(counters.build.y, layers);
        atomicAdd(counters.build.w, 1u);
    }
}
