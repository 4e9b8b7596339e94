#version 450 core
// A glass object's front surface, with each vertex's viewing ray through
// the object from the light transport table (exit point, direction and
// transmittance, written for this frame by the CPU).
#include "common/frame.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
struct Exit { vec4 position; vec4 direction; vec4 transmittance; }; // w of position: 1 where a path exists
layout(std430) readonly buffer Exits { Exit exits[]; };
out vec3 v_world;
out vec3 v_normal;
out vec3 v_exit_position;
out vec3 v_exit_direction;
out vec3 v_transmittance;
out float v_valid;
void main()
{
    vec4 w = u_model * vec4(a_position, 1.0);
    v_world = w.xyz;
    v_normal = mat3(u_normal_matrix) * a_normal;
    Exit e = exits[gl_VertexID];
    v_exit_position = e.position.xyz;
    v_exit_direction = e.direction.xyz;
    v_transmittance = e.transmittance.rgb;
    v_valid = e.position.w;
    gl_Position = u_view_proj * w;
}
