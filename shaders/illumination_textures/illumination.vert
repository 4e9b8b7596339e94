#version 450 core
// §4.2, Fig. 4: a vertex Q of an intersection triangle between an
// illumination volume and a virtual plane, with the intensity
// L_in cos(theta) F_t S / (S_0 cos(delta)) (eq. 3 without cos(gamma)) and
// the direction of the light arriving there; times what the panes of
// thin-walled glass between the light and the glass let through, where the
// pass reads the light's shadow map (its pane filter at the volume's entry
// into the glass, a_entry; issue 50).
#include "illumination_textures/virtual_camera.glsl"
#include "common/shadows.glsl"
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_intensity;
layout(location = 2) in vec3 a_direction;
layout(location = 3) in vec3 a_entry;
layout(location = 4) in vec3 a_to_light;
uniform int u_light; // the light's first entry in the frame's GPU light list
out vec3 v_intensity;
out vec3 v_direction;
void main()
{
    v_intensity = a_intensity * pane_filter(u_light, a_entry, a_to_light, a_to_light);
    v_direction = a_direction;
    gl_Position = vec4(vc_uv(a_position) * 2.0 - 1.0, 0.0, 1.0);
}
