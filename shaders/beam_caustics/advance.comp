#version 450 core
// One thread between the stages of beam_caustics: turns the counters the
// last stage appended with into the next stage's indirect arguments, so
// the refinement never waits for the CPU.
#include "beam_caustics/beams.glsl"
layout(local_size_x = 1) in;
uniform int u_mode; // 0: the next level's cells; 1: the beam builder; 2: the bounding volumes' draw
void main()
{
    if (u_mode == 0) {
        uint n = min(counters[COUNT_NEXT], uint(u_capacity));
        counters[COUNT_IN] = n;
        counters[COUNT_NEXT] = 0u;
        counters[COUNT_DISPATCH] = (n + 63u) / 64u;
        counters[COUNT_DISPATCH + 1] = 1u;
        counters[COUNT_DISPATCH + 2] = 1u;
    } else if (u_mode == 1) {
        uint n = min(counters[COUNT_KEPT], uint(u_capacity));
        counters[COUNT_KEPT] = n;
        counters[COUNT_BUILD] = (n + 63u) / 64u;
        counters[COUNT_BUILD + 1] = 1u;
        counters[COUNT_BUILD + 2] = 1u;
    } else {
        uint n = min(counters[COUNT_BEAMS], uint(u_beam_capacity));
        counters[COUNT_BEAMS] = n;
        counters[COUNT_DRAW] = n * 24u; // 8 triangles a beam: base, top, two per side
        counters[COUNT_DRAW + 1] = 1u;
        counters[COUNT_DRAW + 2] = 0u;
        counters[COUNT_DRAW + 3] = 0u;
    }
}
