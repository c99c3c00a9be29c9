/* DIRT engine: the 3-vector of the CPU light-transport code (the
 * operations, in GLSL's order, are in src/core/vec3.h). */
#ifndef DIRT_VEC_H
#define DIRT_VEC_H

typedef struct dirt_vec3 {
    float x, y, z;
} dirt_vec3;

#endif
