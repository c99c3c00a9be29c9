/* The path tracer's half of the engines that trace through a structure
 * (dirt, mmrt): the accumulation, its image and display, its stats. Such
 * an engine's state begins with an engine_pt, so these functions serve as
 * its operations (engine.h) directly. */
#ifndef DIRT_SESSION_ENGINE_PT_H
#define DIRT_SESSION_ENGINE_PT_H

#include "integrator/pathtrace.h"
#include "session/engine.h"

typedef struct engine_pt {
    dirt_pt *pt;
    const dirt_tracer *tracer;  /* of the current build; NULL before it */
    dirt_image *img;            /* the accumulation read back */
    bool img_current;           /* img holds the current accumulation */
    bool fresh;                 /* restarted: the next samples reset it */
} engine_pt;

/* Makes the path tracer (its programs compiled). False after logging. */
bool engine_pt_init(engine_pt *p, const engine_env *env);
void engine_pt_finish(engine_pt *p);
/* The structure is remade: no tracer, no image until the next build. */
void engine_pt_drop(engine_pt *p);

/* Operations of engine.h on an engine whose state begins with an engine_pt. */
void engine_pt_restart(engine *e);
bool engine_pt_add_samples(engine *e, const engine_env *env, int count, engine_progress_fn progress,
                           void *user, dirt_session_stats *st, int *samples);
bool engine_pt_advance(engine *e, const engine_env *env, double budget_ms,
                       dirt_session_stats *st, int *samples, bool *completed);
double engine_pt_part(const engine *e, const engine_env *env);
const dirt_image *engine_pt_image(engine *e, const engine_env *env, dirt_session_stats *st);
uint32_t engine_pt_display_texture(engine *e, const engine_env *env);
void engine_pt_late_times(engine *e, const engine_env *env, bool wait, dirt_session_stats *st);
bool engine_pt_write_graph_dot(const engine *e, const char *path);

#endif
