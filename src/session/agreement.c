/* Hit agreement of a session's technique with Embree, per ray type: the
 * harness of the tests gpu/dirt_hits and gpu/mmrt_hits on the session's
 * frame, camera and structure, so a program reports the tests' figures.
 * Each engine traces and judges its batches (engine_ops.agree). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "dirt/log.h"
#include "ref/raytypes.h"
#include "ref/ref.h"
#include "dirt/session.h"
#include "session/engine.h"
#include "session/session_internal.h"

bool dirt_session_hit_agreement(dirt_session *s, int width, int height, uint32_t seed,
                                dirt_session_agreement *out)
{
    session_begin();
    memset(out, 0, sizeof(*out));
    for (int t = 0; t < DIRT_RAY_TYPES; t++) {
        out->fraction[t] = NAN;
        out->ms[t] = -1;
    }
    const engine_ops *ops = NULL;
    engine_env env;
    engine *e = session_built_engine(s, &ops, &env);
    if (!e || !ops->agree || width < 1 || height < 1) {
        DIRT_ERROR("hit agreement needs a built dirt or mmrt session and a size");
        /* An engine that can agree but is not built yet is not ready; one
         * that cannot has no such figure. */
        const engine_ops *own = session_engines[dirt_session_get_opts(s)->engine];
        return session_fail(width < 1 || height < 1 ? DIRT_SESSION_ERR_ARGUMENT
                            : own->agree                ? DIRT_SESSION_ERR_NOT_READY
                                                        : DIRT_SESSION_ERR_UNSUPPORTED);
    }
    dirt_camera cam = *env.cam;
    dirt_ref_accel *accel = dirt_ref_accel_create(env.frame, NULL);
    if (!accel)
        return session_fail(DIRT_SESSION_ERR_RENDER);
    dirt_gbuffer g;
    memset(&g, 0, sizeof(g));
    bool ok = dirt_gbuffer_build(accel, env.scene, env.frame, &cam, width, height, &g);
    size_t cap = (size_t)width * height;
    engine_agree b = {.accel = accel};
    b.rays = ok ? malloc(cap * sizeof(*b.rays)) : NULL;
    b.hits = ok ? malloc(cap * sizeof(*b.hits)) : NULL;
    b.ref = ok ? malloc(cap * sizeof(*b.ref)) : NULL;
    b.occluded = ok ? malloc(cap) : NULL;
    ok = ok && b.rays && b.hits && b.ref && b.occluded;
    /* Primary rays come first: MMRT's trace of them reports the thickness. */
    for (int t = DIRT_RAY_PRIMARY; ok && t < DIRT_RAY_TYPES; t++) {
        b.type = (enum dirt_ray_type)t;
        b.count = dirt_rays_generate(&g, &cam, b.type, seed, b.rays);
        ok = ops->agree(e, &env, &b);
        if (!ok)
            break;
        out->ms[t] = b.ms;
        out->clock = b.clock;
        out->aborted += b.aborted;
        out->rays[t] = b.count;
        out->same[t] = b.same;
        out->fraction[t] = b.count ? (double)b.same / (double)b.count : NAN;
    }
    out->thickness = b.thickness;
    free(b.rays);
    free(b.hits);
    free(b.ref);
    free(b.occluded);
    dirt_gbuffer_free(&g);
    dirt_ref_accel_destroy(accel);
    return ok || session_fail(DIRT_SESSION_ERR_RENDER);
}
