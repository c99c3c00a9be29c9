/* DIRT engine: a human-readable summary of a scene (dirt-render --info). */
#include "scene/scene_internal.h"

#include "dirt/log.h"

#include <math.h>
#include <stdio.h>

/* Width of the label column. */
#define LABEL "%-11s"

static const double rad_to_deg = 57.29577951308232;

static bool is_emissive(const dirt_material *m)
{
    return (m->emissive[0] > 0.0f || m->emissive[1] > 0.0f || m->emissive[2] > 0.0f) &&
           m->emissive_strength > 0.0f;
}

/* "s" unless exactly one. */
static const char *plural(size_t n)
{
    return n == 1 ? "" : "s";
}

static const char *node_name(const dirt_scene *s, int node)
{
    return node >= 0 && (size_t)node < s->num_nodes ? s->nodes[node].name : "";
}

static void print_box(FILE *f, const float mn[3], const float mx[3])
{
    fprintf(f, "(%g, %g, %g) .. (%g, %g, %g), size %g x %g x %g", (double)mn[0],
            (double)mn[1], (double)mn[2], (double)mx[0], (double)mx[1], (double)mx[2],
            (double)(mx[0] - mn[0]), (double)(mx[1] - mn[1]), (double)(mx[2] - mn[2]));
}

static void print_camera(FILE *f, const dirt_scene *s, size_t i, const dirt_camera_def *c)
{
    fprintf(f, "  %zu  '%s'  ", i, c->name);
    if (c->type == DIRT_CAMERA_ORTHOGRAPHIC)
        fprintf(f, "orthographic  xmag %g  ymag %g", (double)c->xmag, (double)c->ymag);
    else if (c->aspect > 0.0f)
        fprintf(f, "perspective  yfov %.4g deg  aspect %.4g", c->yfov * rad_to_deg,
                (double)c->aspect);
    else
        fprintf(f, "perspective  yfov %.4g deg  aspect of the image", c->yfov * rad_to_deg);
    fprintf(f, "  near %g  far ", (double)c->znear);
    if (c->zfar > 0.0f)
        fprintf(f, "%g", (double)c->zfar);
    else
        fprintf(f, "infinite");
    fprintf(f, "  node %d '%s'\n", c->node, node_name(s, c->node));
}

static void print_light(FILE *f, const dirt_scene *s, size_t i, const dirt_light_def *l)
{
    static const char *const types[] = {"directional", "point", "spot"};
    bool dir = l->type == DIRT_LIGHT_DIRECTIONAL;
    fprintf(f, "  %zu  '%s'  %s  colour (%g, %g, %g)  intensity %g %s", i, l->name,
            (unsigned)l->type < 3 ? types[l->type] : "?", (double)l->color[0],
            (double)l->color[1], (double)l->color[2], (double)l->intensity,
            dir ? "lx" : "cd");
    if (!dir) {
        if (l->range > 0.0f)
            fprintf(f, "  range %g", (double)l->range);
        else
            fprintf(f, "  range infinite");
    }
    if (l->type == DIRT_LIGHT_SPOT)
        fprintf(f, "  cone %.4g..%.4g deg", l->inner_cone * rad_to_deg,
                l->outer_cone * rad_to_deg);
    fprintf(f, "  node %d '%s'\n", l->node, node_name(s, l->node));
}

bool dirt_scene_print_info(const dirt_scene *s, void *out)
{
    FILE *f = out;
    if (!s || !f) {
        DIRT_ERROR("dirt_scene_print_info: no scene or no output");
        return false;
    }
    /* Rest pose bounds first: the only step that can fail before writing. */
    dirt_eval_opts rest = {.clip = -1};
    float mn[3], mx[3];
    if (!dirt_scene_clip_bounds(s, &rest, mn, mx))
        return false;

    size_t prims = 0;
    for (size_t m = 0; m < s->num_meshes; m++)
        prims += s->meshes[m].num_prims;
    size_t emissive_materials = 0, emitter_triangles = 0;
    for (size_t m = 0; m < s->num_materials; m++)
        emissive_materials += is_emissive(&s->materials[m]);
    for (size_t i = 0; i < s->num_instances; i++) {
        const scene_mesh *mesh = &s->meshes[s->instances[i].mesh];
        for (size_t p = 0; p < mesh->num_prims; p++) {
            uint32_t mat = mesh->prims[p].material;
            if (mat < s->num_materials && is_emissive(&s->materials[mat]))
                emitter_triangles += mesh->prims[p].num_triangles;
        }
    }

    fprintf(f, LABEL "'%s'\n", "scene", s->name);
    fprintf(f, LABEL "%zu\n", "triangles", s->num_triangles);
    fprintf(f, LABEL "%zu (%zu primitive%s, %zu instance%s)\n", "meshes", s->num_meshes, prims,
            plural(prims), s->num_instances, plural(s->num_instances));
    fprintf(f, LABEL "%zu\n", "nodes", s->num_nodes);
    fprintf(f, LABEL "%zu\n", "materials", s->num_materials);
    fprintf(f, LABEL "%zu\n", "textures", s->num_textures);
    fprintf(f, LABEL "%zu triangle%s, %zu emissive material%s\n", "emitters",
            emitter_triangles, plural(emitter_triangles), emissive_materials,
            plural(emissive_materials));
    fprintf(f, LABEL "%zu\n", "cameras", s->num_cameras);
    for (size_t i = 0; i < s->num_cameras; i++)
        print_camera(f, s, i, &s->cameras[i]);
    fprintf(f, LABEL "%zu\n", "lights", s->num_lights);
    for (size_t i = 0; i < s->num_lights; i++)
        print_light(f, s, i, &s->lights[i]);
    fprintf(f, LABEL "%zu\n", "clips", s->num_clips);
    bool ok = true;
    for (size_t i = 0; i < s->num_clips; i++) {
        const scene_clip *c = &s->clips[i];
        float cmn[3], cmx[3];
        dirt_eval_opts o = {.clip = (int)i};
        fprintf(f, "  %zu  '%s'  %g s  %zu channel%s  bounds ", i, c->name,
                (double)c->duration, c->num_channels, plural(c->num_channels));
        if (dirt_scene_clip_bounds(s, &o, cmn, cmx)) {
            print_box(f, cmn, cmx);
        } else {
            fprintf(f, "unavailable");
            ok = false;
        }
        fputc('\n', f);
    }
    fprintf(f, LABEL, "bounds");
    print_box(f, mn, mx);
    fprintf(f, " (rest pose)\n");
    if (ferror(f)) {
        DIRT_ERROR("dirt_scene_print_info: cannot write the summary of '%s'", s->name);
        return false;
    }
    return ok;
}
