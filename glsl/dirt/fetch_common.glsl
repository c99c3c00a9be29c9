// Fetch: turns a hit record into the shading point G_{k+1} of its owner
// pixel: position and shading normal interpolated with the hit's
// barycentrics, the primitive's material (dirt_gpu_gpoint says what Shade
// derives itself). Shared by the compute Fetch (fetch.comp) and the paper's raster
// Fetch (build.frag with DIRT_PASS_FETCH), so both write the same bits.
// Needs common/layout.h and these buffers declared by the includer:
// dirt_vertex_at(), dirt_prim_material(), hits[], gpoints[], fetch (params).

#include "common/geometry.glsl"

void dirt_fetch_record(uint r)
{
    dirt_gpu_hit h = hits[r];
    uint owner = h.ids.z;
    uint slot = 3u * owner + fetch.config.y;
    dirt_gpu_gpoint g;
    uint p = h.ids.x;
    if (p == DIRT_NO_HIT) {
        g.pos_prim = vec4(0.0, 0.0, 0.0, uintBitsToFloat(DIRT_NO_HIT));
        g.n_mat = vec4(0.0);
        gpoints[slot] = g;
        return;
    }
    float u = h.bary_t.x, v = h.bary_t.y, w = 1.0 - u - v;
    dirt_gpu_vertex a = dirt_vertex_at(3u * p), b = dirt_vertex_at(3u * p + 1u),
                    c = dirt_vertex_at(3u * p + 2u);
    vec3 pos = w * a.position.xyz + u * b.position.xyz + v * c.position.xyz;
    vec3 ns = w * a.normal.xyz + u * b.normal.xyz + v * c.normal.xyz;
    float ls = length(ns);
    ns = ls > 0.0 ? ns / ls
                  : dirt_geometric_normal(a.position.xyz, b.position.xyz, c.position.xyz);
    g.pos_prim = vec4(pos, uintBitsToFloat(p));
    g.n_mat = vec4(ns, uintBitsToFloat(dirt_prim_material(p)));
    gpoints[slot] = g;
}
