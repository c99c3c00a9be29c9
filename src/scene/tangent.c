/* DIRT engine: tangents of a primitive for its normal map when the file has
 * none (scene_prim_generate_tangents, scene_internal.h). glTF recommends
 * MikkTSpace; this is the simpler per-vertex sum of per-triangle UV
 * derivatives, orthogonalised against the vertex normal (the frame is
 * orthogonalised once more at the shading point, doc/light-transport.md
 * "Normal maps"). It equals MikkTSpace's tangent wherever a vertex's
 * triangles share one UV mapping (planar or affinely mapped patches) up to
 * the weighting of the sum. */
#include "scene/scene_internal.h"

#include "dirt/log.h"

#include <math.h>
#include <stdlib.h>

bool scene_prim_generate_tangents(scene_prim *p)
{
    size_t nv = p->num_vertices;
    if (!p->uv || nv == 0)
        return true;
    double (*acc)[9] = calloc(nv, sizeof(*acc)); /* T, B, face normal sums */
    float (*out)[4] = calloc(nv, sizeof(*out));
    if (!acc || !out) {
        free(acc);
        free(out);
        DIRT_ERROR("out of memory generating tangents (%zu vertices)", nv);
        return false;
    }
    for (size_t t = 0; t < p->num_triangles; t++) {
        const uint32_t *ix = &p->indices[3 * t];
        const float *p0 = p->position[ix[0]], *p1 = p->position[ix[1]], *p2 = p->position[ix[2]];
        const float *t0 = p->uv[ix[0]], *t1 = p->uv[ix[1]], *t2 = p->uv[ix[2]];
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = (double)p1[k] - p0[k];
            e2[k] = (double)p2[k] - p0[k];
        }
        double du1 = (double)t1[0] - t0[0], dv1 = (double)t1[1] - t0[1];
        double du2 = (double)t2[0] - t0[0], dv2 = (double)t2[1] - t0[1];
        double r = du1 * dv2 - du2 * dv1;
        double fn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                        e1[0] * e2[1] - e1[1] * e2[0]};
        bool uv_ok = r != 0.0 && isfinite(r);
        for (int c = 0; c < 3; c++) {
            double *a = acc[ix[c]];
            for (int k = 0; k < 3; k++) {
                if (uv_ok) {
                    a[k] += (e1[k] * dv2 - e2[k] * dv1) / r;
                    a[3 + k] += (e2[k] * du1 - e1[k] * du2) / r;
                }
                a[6 + k] += fn[k];
            }
        }
    }
    for (size_t v = 0; v < nv; v++) {
        const double *a = acc[v];
        double n[3] = {a[6], a[7], a[8]};
        if (p->normal)
            for (int k = 0; k < 3; k++)
                n[k] = p->normal[v][k];
        double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double d = 0.0;
        if (nl > 0.0 && isfinite(nl)) {
            for (int k = 0; k < 3; k++)
                n[k] /= nl;
            d = n[0] * a[0] + n[1] * a[1] + n[2] * a[2];
        }
        double tg[3] = {a[0] - n[0] * d, a[1] - n[1] * d, a[2] - n[2] * d};
        double tl = sqrt(tg[0] * tg[0] + tg[1] * tg[1] + tg[2] * tg[2]);
        out[v][3] = 1.0f;
        if (!(tl > 0.0) || !isfinite(tl))
            continue; /* (0, 0, 0, 1) */
        for (int k = 0; k < 3; k++)
            out[v][k] = (float)(tg[k] / tl);
        double c[3] = {n[1] * tg[2] - n[2] * tg[1], n[2] * tg[0] - n[0] * tg[2],
                       n[0] * tg[1] - n[1] * tg[0]};
        if (c[0] * a[3] + c[1] * a[4] + c[2] * a[5] < 0.0)
            out[v][3] = -1.0f;
    }
    free(acc);
    p->tangent = out;
    return true;
}
