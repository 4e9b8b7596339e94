#version 450 core
// Cube maps store distance to the light over the map's range; 2D maps only
// need the depth buffer. A cut-out (alphaMode MASK) casts no shadow.
#include "common/material.glsl"
in vec3 v_world;
#ifdef SHADOW_DISTANCE
uniform vec3 u_light_position;
uniform float u_range;
out vec4 o_distance;
#endif
void main()
{
    if (material_cut_out())
        discard;
#ifndef SHADOW_DISTANCE
    if (u_alpha_blend == 1)
        discard; // a 2D map's filter carries it (shadow_map.c)
#endif
#ifdef SHADOW_DISTANCE
    o_distance = vec4(length(v_world - u_light_position) / u_range, 0.0, 0.0, 1.0);
#endif
}
