// Fetch: turns a hit record into the shading point G_{k+1} of its owner
// pixel. Shared by the compute Fetch (fetch.comp) and the paper's raster
// Fetch (build.frag with DIRT_PASS_FETCH), so both write the same bits.
// Needs common/layout.h and these buffers declared by the includer:
// vertices[], prim_material[], rays[], hits[], gpoints[], fetch (params).

void dirt_fetch_record(uint r)
{
    dirt_gpu_hit h = hits[r];
    uint owner = h.ids.z;
    uint slot = 3u * owner + fetch.config.y;
    vec3 dir = normalize(rays[r].dir_tmax.xyz);
    dirt_gpu_gpoint g;
    uint p = h.ids.x;
    if (p == DIRT_NO_HIT) {
        g.pos_prim = vec4(0.0, 0.0, 0.0, uintBitsToFloat(DIRT_NO_HIT));
        g.n_mat = vec4(0.0);
        g.ng_u = vec4(0.0);
        g.wo_v = vec4(-dir, 0.0);
        gpoints[slot] = g;
        return;
    }
    float u = h.bary_t.x, v = h.bary_t.y, w = 1.0 - u - v;
    dirt_gpu_vertex a = vertices[3u * p], b = vertices[3u * p + 1u], c = vertices[3u * p + 2u];
    vec3 pos = w * a.position.xyz + u * b.position.xyz + v * c.position.xyz;
    vec3 ns = w * a.normal.xyz + u * b.normal.xyz + v * c.normal.xyz;
    vec3 ng = cross(b.position.xyz - a.position.xyz, c.position.xyz - a.position.xyz);
    float lg = length(ng);
    ng = lg > 0.0 ? ng / lg : vec3(0.0, 0.0, 1.0);
    float ls = length(ns);
    ns = ls > 0.0 ? ns / ls : ng;
    vec2 uv = w * vec2(a.position.w, a.normal.w) + u * vec2(b.position.w, b.normal.w) +
              v * vec2(c.position.w, c.normal.w);
    g.pos_prim = vec4(pos, uintBitsToFloat(p));
    g.n_mat = vec4(ns, uintBitsToFloat(prim_material[p]));
    g.ng_u = vec4(ng, uv.x);
    g.wo_v = vec4(-dir, uv.y);
    gpoints[slot] = g;
}
