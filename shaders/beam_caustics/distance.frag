#version 450 core
// The distance impostor's faces: each texel the distance from the centre
// to the nearest receiver in its direction, over the range.
in vec3 v_world;
uniform vec3 u_center;
uniform float u_range;
out vec4 o_distance;
void main() { o_distance = vec4(length(v_world - u_center) / u_range, 0.0, 0.0, 1.0); }
