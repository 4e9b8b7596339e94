#version 450 core
// The camera under water (issue 8, Fig. 28): everything it sees directly
// lies at the end of a path through the water, absorbed over its length
// (Beer-Lambert, as the reference's medium): the input image times
// exp(-c d), d the path's length to the camera, where the input has a position. The surface, drawn
// over it, absorbs its own path (surface.frag).
#include "common/frame.glsl"
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
uniform sampler2D u_image;
uniform sampler2D u_scene_position;
uniform vec3 u_absorption;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 c = texelFetch(u_image, px, 0).rgb;
    vec4 q = texelFetch(u_scene_position, px, 0);
    if (q.w > 0.0)
        c *= exp(-u_absorption * view_distance(q.xyz));
    o_color = vec4(c, 1.0);
}
