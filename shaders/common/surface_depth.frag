#version 450 core
// The window depth of a surface, kept nearest by min blending: where a
// glass, water or mirror surface a view technique draws shows, for the
// panes of thin-walled glass in front of it (src/passes/helpers/thin_glass_over.c).
layout(location = 0) out vec4 o_depth;
void main() { o_depth = vec4(gl_FragCoord.z); }
