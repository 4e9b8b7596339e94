#version 450 core
// The distance impostor's faces (distance_map_update_distances): each texel
// the distance from the centre to the nearest receiver in its direction.
in vec3 v_world;
uniform vec3 u_center;
out vec4 o_distance;
void main() { o_distance = vec4(length(v_world - u_center), 0.0, 0.0, 1.0); }
