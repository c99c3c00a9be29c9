#include "views/hiz.h"

#include "common/layout.h"
#include "gl/program.h"

GLuint views_hiz_program(void)
{
    return gl_program_compute("views/hiz.comp", NULL, 0);
}

void views_hiz_dispatch(GLuint program, const dirt_view_set *set)
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
        glUniform1i(DIRT_LOC_MIP_LEVEL, d);
        glDispatchCompute((GLuint)DIRT_GROUPS_2D(w), (GLuint)DIRT_GROUPS_2D(h), (GLuint)set->count);
    }
    glUseProgram(0);
}
