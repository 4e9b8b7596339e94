#version 450 core
// §3.3, first pass: every fragment, no culling or depth test; MAX blending
// keeps (Zmax, -Zmin) per pixel.
in vec3 v_normal;
in float v_depth;
layout(location = 0) out vec4 o_bounds;
void main() { o_bounds = vec4(v_depth, -v_depth, 0.0, 1.0); }
