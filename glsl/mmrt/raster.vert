#version 450 core
// MMRT depth bounds and store passes: the geometry stage pulls each
// triangle's vertices from the vertex buffer by primitive id, so the vertex
// stage does nothing.
void main()
{
}
