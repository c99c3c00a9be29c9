#include "views/hiz.h"

#include "common/layout.h"
#include "gl/program.h"

bool views_hiz_program(gl_split_program *p, gl_split_layout layout)
{
    const char *paths[] = {"views/hiz.comp", NULL};
    const gl_split_desc *d = &gl_split_depth;
    return gl_split_program_ensure(p, "views/hiz.comp", paths, NULL, 0, &d, &layout, 1);
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
        /* Level d reads level d - 1 written by the previous dispatch (a
         * storage block, or images when the pyramid is split). */
        if (d > 1)
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glUniform1i(DIRT_LOC_MIP_LEVEL, d);
        glDispatchCompute((GLuint)DIRT_GROUPS_2D(w), (GLuint)DIRT_GROUPS_2D(h), (GLuint)set->count);
    }
    glUseProgram(0);
}
