#version 450 core
// Initial pass of Hu & Qin Fig. 4: the outward world normal of the front-
// or back-facing surface (w = Wyman's interpolated d_N), and its depth.
in vec3 v_normal;
in float v_thickness;
layout(location = 0) out vec4 o_normal;
void main()
{
    o_normal = vec4(normalize(v_normal), v_thickness);
}
