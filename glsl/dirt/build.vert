#version 450 core
// DIRT build passes: the geometry shader pulls the triangle's vertices from
// the vertex buffer by primitive id, so the vertex stage does nothing.
void main()
{
}
