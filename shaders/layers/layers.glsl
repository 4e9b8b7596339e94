// Depth layers (Chaudhari 2008): the view they were taken from and the
// slice of a depth between a pixel's bounds (§3.3). Mirrors
// src/passes/helpers/layers.c.
// The set's view, one block the set uploads once a build and every
// program that reads it binds (issue 54; struct layer_view_params).
layout(std140) uniform LayerView {
    mat4 u_layer_view;
    mat4 u_layer_proj;
    mat4 u_layer_inv_view;
    mat4 u_layer_inv_proj;
    ivec2 u_layer_size;   // texels
    int u_voxels;         // slices per pixel (a multiple of 128)
    int u_layers;         // layers kept per pixel (at most 32)
    int u_exact_depth;
};

// The slice of eye depth d between the pixel's bounds [zmin, zmax]: the
// grid is per pixel (§3.3's "distorted grid"), so it is as fine as the
// object is thin there.
int layer_slice(float d, float zmin, float zmax)
{
    float span = zmax - zmin;
    float t = span > 0.0 ? (d - zmin) / span : 0.0;
    return clamp(int(t * float(u_voxels)), 0, u_voxels - 1);
}
