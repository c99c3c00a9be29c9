// MMRT A-buffer helpers shared by the store, reorder and trace passes.
// Include file (no #version); needs common/mmrt_layout.h.
#ifndef DIRT_MMRT_ABUFFER_GLSL
#define DIRT_MMRT_ABUFFER_GLSL

// Bucket of eye-space depth z in a pixel whose bounds are [zmin, zmin +
// range]: buckets are B uniform slices of the linear depth range (MMRT
// paper, 3.3), b = floor(B (z - zmin) / range), clamped to [0, B-1]; a pixel
// with zero range keeps everything in bucket 0. Monotonic in z (every
// operation is), so a depth interval maps to a contiguous bucket range.
int mmrt_bucket(float z, float zmin, float range, int B)
{
    if (!(range > 0.0))
        return 0;
    precise float x = float(B) * (z - zmin) / range;
    return clamp(int(floor(x)), 0, B - 1);
}

// Octahedral encoding of a unit vector into two snorm16 (packSnorm2x16).
uint mmrt_pack_normal(vec3 n)
{
    n /= max(abs(n.x) + abs(n.y) + abs(n.z), 1e-20);
    vec2 e = n.xy;
    if (n.z < 0.0) {
        vec2 s = vec2(e.x >= 0.0 ? 1.0 : -1.0, e.y >= 0.0 ? 1.0 : -1.0);
        e = (1.0 - abs(e.yx)) * s;
    }
    return packSnorm2x16(e);
}

vec3 mmrt_unpack_normal(uint p)
{
    vec2 e = unpackSnorm2x16(p);
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) {
        vec2 s = vec2(e.x >= 0.0 ? 1.0 : -1.0, e.y >= 0.0 ? 1.0 : -1.0);
        n.xy = (1.0 - abs(n.yx)) * s;
    }
    return normalize(n);
}

// Integer hash for the deterministic jitter of linear marching (xor-shift
// and odd-multiplier rounds; bijective on 32 bits).
uint dirt_mmrt_hash(uint x)
{
    x ^= x >> 17;
    x *= 0xed5ad4bbu;
    x ^= x >> 11;
    x *= 0xac4c1b51u;
    x ^= x >> 15;
    x *= 0x31848babu;
    x ^= x >> 14;
    return x;
}

#endif
