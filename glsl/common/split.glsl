// Split arrays in the shaders (src/gl/split.h; doc/architecture.md, "Arrays
// past one storage block"): what every array's include (common/vertices.glsl,
// common/depth.glsl, dirt/structure.glsl, mmrt/arrays.glsl,
// integrator/model.glsl) builds its declarations and accessors from, so
// that the part arithmetic and the per-part code are written once. An
// array ARRAY split into n parts (n = its DIRT_SPLIT_<ARRAY> define, 1 ..
// DIRT_SPLIT_MAX_PARTS) of 2^SHIFT records has parts NAME_part0 ..
// NAME_part<n-1>: texel buffers at units UNIT + k (samplers) or images at
// UNIT + k. Included by common/constants.h (for every shader).
#ifndef DIRT_SPLIT_GLSL
#define DIRT_SPLIT_GLSL

#if DIRT_SPLIT_MAX_PARTS != 8
#error "common/split.glsl: DIRT_SPLIT_EACH_n is written out for 8 parts"
#endif

// DIRT_SPLIT_EACH(n, M, a, b, c, d): M(0, a, b, c, d) M(1, a, b, c, d) ...
// M(n - 1, a, b, c, d), for n (a number, or a macro that is one) in 1 ..
// DIRT_SPLIT_MAX_PARTS.
#define DIRT_SPLIT_CAT_(a, b) a##b
#define DIRT_SPLIT_CAT(a, b) DIRT_SPLIT_CAT_(a, b)
#define DIRT_SPLIT_EACH_1(M, a, b, c, d) M(0, a, b, c, d)
#define DIRT_SPLIT_EACH_2(M, a, b, c, d) DIRT_SPLIT_EACH_1(M, a, b, c, d) M(1, a, b, c, d)
#define DIRT_SPLIT_EACH_3(M, a, b, c, d) DIRT_SPLIT_EACH_2(M, a, b, c, d) M(2, a, b, c, d)
#define DIRT_SPLIT_EACH_4(M, a, b, c, d) DIRT_SPLIT_EACH_3(M, a, b, c, d) M(3, a, b, c, d)
#define DIRT_SPLIT_EACH_5(M, a, b, c, d) DIRT_SPLIT_EACH_4(M, a, b, c, d) M(4, a, b, c, d)
#define DIRT_SPLIT_EACH_6(M, a, b, c, d) DIRT_SPLIT_EACH_5(M, a, b, c, d) M(5, a, b, c, d)
#define DIRT_SPLIT_EACH_7(M, a, b, c, d) DIRT_SPLIT_EACH_6(M, a, b, c, d) M(6, a, b, c, d)
#define DIRT_SPLIT_EACH_8(M, a, b, c, d) DIRT_SPLIT_EACH_7(M, a, b, c, d) M(7, a, b, c, d)
#define DIRT_SPLIT_EACH(n, M, a, b, c, d) DIRT_SPLIT_CAT(DIRT_SPLIT_EACH_, n)(M, a, b, c, d)

// ---- declarations ----
// The parts as texel buffers read with texelFetch: TYPE samplerBuffer,
// usamplerBuffer, ...
#define DIRT_SPLIT_SAMPLER_(k, unit, type, name, unused) \
    layout(binding = unit + k) uniform type name##_part##k;
#define DIRT_SPLIT_SAMPLERS(n, unit, type, name) \
    DIRT_SPLIT_EACH(n, DIRT_SPLIT_SAMPLER_, unit, type, name, 0)
// The parts as images: FORMAT r32ui, rg32ui, rgba32ui; TYPE the memory
// qualifier (may be empty: a macro) and uimageBuffer.
#define DIRT_SPLIT_IMAGE_(k, unit, format, type, name) \
    layout(format, binding = unit + k) uniform type name##_part##k;
#define DIRT_SPLIT_IMAGES(n, unit, format, type, name) \
    DIRT_SPLIT_EACH(n, DIRT_SPLIT_IMAGE_, unit, format, type, name)

// ---- accessors ----
// Declares `part` and `t`: the part of record i and its first texel there,
// for records of PER texels in parts of 2^SHIFT records.
#define DIRT_SPLIT_AT(i, shift, per) \
    uint part = (i) >> uint(shift); \
    int t = int(uint(per) * ((i) - (part << uint(shift))));
// r = FN(NAME_part<part>, t)SWIZZLE (FN texelFetch or imageLoad; SWIZZLE
// .x, .xy, .xyzw).
#define DIRT_SPLIT_LOAD_(k, r, fn, name, swizzle) \
    if (part == uint(k)) r = fn(name##_part##k, t)swizzle;
#define DIRT_SPLIT_LOAD(n, r, fn, name, swizzle) \
    DIRT_SPLIT_EACH(n, DIRT_SPLIT_LOAD_, r, fn, name, swizzle)
// FN(NAME_part<part>, t, V) (imageStore, imageAtomicMin, ...).
#define DIRT_SPLIT_STORE_(k, fn, name, v, unused) \
    if (part == uint(k)) fn(name##_part##k, t, v);
#define DIRT_SPLIT_STORE(n, fn, name, v) DIRT_SPLIT_EACH(n, DIRT_SPLIT_STORE_, fn, name, v, 0)
// r = FN(NAME_part<part>, t, V) (imageAtomicExchange).
#define DIRT_SPLIT_ATOMIC_(k, r, fn, name, v) \
    if (part == uint(k)) r = fn(name##_part##k, t, v);
#define DIRT_SPLIT_ATOMIC(n, r, fn, name, v) DIRT_SPLIT_EACH(n, DIRT_SPLIT_ATOMIC_, r, fn, name, v)

#endif
