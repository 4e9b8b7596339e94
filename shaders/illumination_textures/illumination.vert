#version 450 core
// §4.2, Fig. 4: a vertex Q of an intersection triangle between an
// illumination volume and a virtual plane, with the intensity
// L_in cos(theta) F_t S / (S_0 cos(delta)) (eq. 3 without cos(gamma)) and
// the direction of the light arriving there.
#include "illumination_textures/virtual_camera.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_intensity;
layout(location = 2) in vec3 a_direction;
out vec3 v_intensity;
out vec3 v_direction;
void main()
{
    v_intensity = a_intensity;
    v_direction = a_direction;
    gl_Position = vec4(vc_uv(a_position) * 2.0 - 1.0, 0.0, 1.0);
}
