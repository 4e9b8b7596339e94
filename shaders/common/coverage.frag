#version 450 core
// Coverage for an EXR's alpha (src/graph/renderer.c, renderer_coverage):
// 1 wherever an object's surface is in the pixel, the background 0.
out vec4 o_coverage;
void main()
{
    o_coverage = vec4(1.0);
}
