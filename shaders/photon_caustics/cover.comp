#version 450 core
// The box of light-view texels the specular objects cover (front or back
// surface drawn): photon_caustics narrows its light view to it, so that the
// photon buffer's texels fall on the glass (issue 8: a buffer that adapts
// to the refractors' projected area). Out: min x, min y, max x, max y.
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2D u_front_depth;
uniform sampler2D u_back_depth;
layout(std430) buffer Cover { uint cover[4]; };
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, textureSize(u_front_depth, 0))))
        return;
    if (texelFetch(u_front_depth, p, 0).r >= 1.0 && texelFetch(u_back_depth, p, 0).r >= 1.0)
        return;
    atomicMin(cover[0], uint(p.x));
    atomicMin(cover[1], uint(p.y));
    atomicMax(cover[2], uint(p.x));
    atomicMax(cover[3], uint(p.y));
}
