#version 450 core
// The bounding volume of each beam (§4.3), pulled from the beam buffer: 8
// triangles, base and top and two per side (the side's diagonal from the
// builder's choice), wound outwards so that culling front faces leaves
// each pixel one fragment per beam.
#include "common/frame.glsl"
#include "beam_caustics/beams.glsl"
flat out int v_beam;
void main()
{
    int beam = gl_VertexID / 24, k = gl_VertexID % 24, tri = k / 3, j = k % 3;
    Beam b = beams[beam];
    vec3 V[3] = vec3[3](b.v[0].xyz, b.v[1].xyz, b.v[2].xyz);
    vec3 T[3] = vec3[3](b.top[0].xyz, b.top[1].xyz, b.top[2].xyz);
    vec3 p[3];
    if (tri == 0) {
        p = V;
    } else if (tri == 1) {
        p = T;
    } else {
        int e = (tri - 2) / 2, a = e, c = (e + 1) % 3;
        bool second = ((tri - 2) & 1) == 1;
        bool diagonal = b.info.y < 0.5 && ((uint(b.info.z + 0.5) >> uint(e)) & 1u) == 1u;
        if (!diagonal) // the diagonal a - c'
            p = second ? vec3[3](V[a], T[c], T[a]) : vec3[3](V[a], V[c], T[c]);
        else           // the diagonal c - a'
            p = second ? vec3[3](V[c], T[c], T[a]) : vec3[3](V[a], V[c], T[a]);
    }
    vec3 middle = (V[0] + V[1] + V[2] + T[0] + T[1] + T[2]) / 6.0;
    if (dot(cross(p[1] - p[0], p[2] - p[0]), p[0] - middle) < 0.0) {
        vec3 s = p[1];
        p[1] = p[2];
        p[2] = s;
    }
    gl_Position = u_view_proj * vec4(p[j], 1.0);
    v_beam = beam;
}
