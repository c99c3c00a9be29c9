/* Hit agreement of a session's technique with Embree, per ray type: the
 * harness of the tests gpu/dirt_hits and gpu/mmrt_hits on the session's
 * frame, camera and structure, so a program reports the tests' figures. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/ads.h"
#include "dirt/log.h"
#include "mmrt/mmrt.h"
#include "ref/raytypes.h"
#include "ref/ref.h"
#include "dirt/session.h"
#include "session/session_internal.h"

/* gpu/dirt_hits: relative t tolerance for "the same hit" on a shared edge. */
#define AGREE_T_TOL 1e-4
/* gpu/mmrt_hits and the path tracer: MMRT rays start this many thicknesses
 * off the surface. */
#define MMRT_OFFSET_THICKNESSES 3

static bool dirt_agree(const dirt_hit *d, const dirt_ref_hit *e, bool visibility)
{
    bool dh = d->prim != DIRT_HIT_NONE, eh = e->prim != DIRT_REF_MISS;
    if (visibility || !dh || !eh)
        return dh == eh;
    return d->prim == e->prim || fabs(d->t - e->t) <= AGREE_T_TOL * fmax(e->t, 1e-3);
}

bool dirt_session_hit_agreement(dirt_session *s, int width, int height, uint32_t seed,
                                dirt_session_agreement *out)
{
    session_begin();
    memset(out, 0, sizeof(*out));
    for (int t = 0; t < DIRT_RAY_TYPES; t++) {
        out->fraction[t] = NAN;
        out->ms[t] = -1;
    }
    dirt_ads *ads = dirt_session_ads(s);
    dirt_mmrt *mmrt = dirt_session_mmrt(s);
    const dirt_frame *f = dirt_session_frame(s);
    if ((!ads && !mmrt) || !f || width < 1 || height < 1) {
        DIRT_ERROR("hit agreement needs a built dirt or mmrt session and a size");
        enum dirt_engine e = dirt_session_get_opts(s)->engine;
        return session_fail(width < 1 || height < 1 ? DIRT_SESSION_ERR_ARGUMENT
                            : e == DIRT_ENGINE_DIRT || e == DIRT_ENGINE_MMRT
                                ? DIRT_SESSION_ERR_NOT_READY
                                : DIRT_SESSION_ERR_UNSUPPORTED);
    }
    const dirt_session_opts *o = dirt_session_get_opts(s);
    dirt_camera cam = *dirt_session_camera(s);
    dirt_ref_accel *accel = dirt_ref_accel_create(f, NULL);
    if (!accel)
        return session_fail(DIRT_SESSION_ERR_RENDER);
    dirt_gbuffer g;
    memset(&g, 0, sizeof(g));
    bool ok = dirt_gbuffer_build(accel, dirt_session_scene(s), f, &cam, width, height, &g);
    size_t cap = (size_t)width * height;
    dirt_ray *rays = ok ? malloc(cap * sizeof(*rays)) : NULL;
    dirt_hit *hits = ok ? malloc(cap * sizeof(*hits)) : NULL;
    dirt_ref_hit *ref = ok ? malloc(cap * sizeof(*ref)) : NULL;
    unsigned char *occ = ok ? malloc(cap) : NULL;
    ok = ok && rays && hits && ref && occ;
    dirt_mmrt_trace_opts mo = {.march = o->march, .samples = o->march_samples,
                               .hiz_levels = o->hiz_levels, .thickness = o->thickness,
                               .seed = o->seed};
    float thickness = 0;
    for (int t = DIRT_RAY_PRIMARY; ok && t < DIRT_RAY_TYPES; t++) {
        size_t n = dirt_rays_generate(&g, &cam, t, seed, rays);
        bool vis = t == DIRT_RAY_VISIBILITY;
        size_t same = 0;
        if (ads) {
            dirt_trace_stats ts;
            dirt_trace_opts to = {.hiz_levels = o->hiz_levels, .any_hit = vis};
            dirt_ref_intersect(accel, (const dirt_ref_ray *)rays, ref, n, 0);
            ok = dirt_ads_trace(ads, rays, n, hits, &to, &ts);
            for (size_t i = 0; ok && i < n; i++)
                same += dirt_agree(&hits[i], &ref[i], vis);
            out->ms[t] = ts.ms;
            out->clock = ts.clock;
            out->aborted += ts.aborted;
        } else {
            /* Primary rays come first: their trace reports the thickness. */
            for (size_t i = 0; t != DIRT_RAY_PRIMARY && i < n; i++) {
                float len = sqrtf(rays[i].dir[0] * rays[i].dir[0] +
                                  rays[i].dir[1] * rays[i].dir[1] +
                                  rays[i].dir[2] * rays[i].dir[2]);
                rays[i].tmin = MMRT_OFFSET_THICKNESSES * thickness / len;
                if (vis)
                    rays[i].tmax = 1 - MMRT_OFFSET_THICKNESSES * thickness / len;
            }
            dirt_mmrt_trace_stats ts;
            ok = dirt_mmrt_trace_cpu(mmrt, rays, n, hits, &mo, &ts);
            if (t == DIRT_RAY_PRIMARY)
                thickness = ts.thickness;
            if (vis)
                dirt_ref_occluded(accel, (const dirt_ref_ray *)rays, occ, n, 0);
            else
                dirt_ref_intersect(accel, (const dirt_ref_ray *)rays, ref, n, 0);
            for (size_t i = 0; ok && i < n; i++) {
                bool mh = hits[i].prim != DIRT_HIT_NONE;
                if (vis) {
                    same += mh == (occ[i] != 0);
                } else {
                    bool eh = ref[i].prim != DIRT_REF_MISS;
                    same += (!mh && !eh) || (mh && eh && hits[i].prim == ref[i].prim);
                }
            }
            out->ms[t] = ts.ms;
            out->clock = ts.clock;
            out->aborted += ts.aborted;
        }
        out->rays[t] = n;
        out->same[t] = same;
        out->fraction[t] = n ? (double)same / (double)n : NAN;
    }
    out->thickness = thickness;
    free(rays);
    free(hits);
    free(ref);
    free(occ);
    dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
    return ok || session_fail(DIRT_SESSION_ERR_RENDER);
}
