#include "dirt/mip.h"

void dirt_mip_dispatch(GLuint program, const dirt_view_set *set)
{
    glUseProgram(program);
    for (int d = 1; d < set->num_levels; d++) {
        int w = 0, h = 0;
        for (int i = 0; i < set->count; i++) {
            const dirt_view *v = &set->views[i];
            int lw = (v->tiles_x + (1 << d) - 1) >> d, lh = (v->tiles_y + (1 << d) - 1) >> d;
            w = lw > w ? lw : w;
            h = lh > h ? lh : h;
        }
        /* Level d reads level d - 1 written by the previous dispatch. */
        if (d > 1)
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glUniform1i(0, d);
        glDispatchCompute((GLuint)(w + 7) / 8, (GLuint)(h + 7) / 8, (GLuint)set->count);
    }
    glUseProgram(0);
}
