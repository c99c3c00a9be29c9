// Triangle helpers that more than one pass must compute to the same bits.

// Unit geometric normal of triangle (a, b, c) in winding order; +z for a
// degenerate triangle. Fetch (its shading-normal fallback), MMRT's shading
// point and Shade's vertex all use this one expression.
vec3 dirt_geometric_normal(vec3 a, vec3 b, vec3 c)
{
    vec3 ng = cross(b - a, c - a);
    float lg = length(ng);
    return lg > 0.0 ? ng / lg : vec3(0.0, 0.0, 1.0);
}
