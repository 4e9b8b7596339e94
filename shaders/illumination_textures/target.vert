#version 450 core
// The targets seen by the virtual camera (§4.2; illumination_textures) and
// those drawn into a sliced object image (Iwasaki et al. [13];
// sliced_refraction): world position and normal, projected by vc_clip.
#include "illumination_textures/virtual_camera.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat4 u_normal_matrix;
out vec3 v_world;
out vec3 v_normal;
void main()
{
    v_world = (u_model * vec4(a_position, 1.0)).xyz;
    v_normal = mat3(u_normal_matrix) * a_normal;
    gl_Position = vc_clip(v_world);
}
