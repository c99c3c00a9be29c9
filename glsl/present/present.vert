#version 450 core
// The window's presentation (src/gl/present.c): one triangle covering the
// viewport, which present.c sets to the destination rectangle.

void main()
{
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
