#version 450 core
// The impostor's texel: the object's depth along the axis, measured from
// the rectangle's plane through its centre (Hu & Qin Fig. 12, 16).
in vec3 v_world;
uniform vec3 u_impostor_center;
uniform vec3 u_impostor_axis;
layout(location = 0) out vec4 o_depth;
void main()
{
    o_depth = vec4(dot(v_world - u_impostor_center, u_impostor_axis), 0.0, 0.0, 1.0);
}
