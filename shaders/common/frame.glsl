// Per-frame data shared by every pass: one std140 block (mirrored by struct
// renderer_frame_uniforms in src/graph/renderer.h) and the environment cube
// map, both at units the renderer reserves (renderer_create) and keeps bound.
struct GpuLight {
    vec4 position;   // xyz, w = kind: 0 point, 1 directional, 2 spot
    vec4 direction;  // xyz (direction light travels / spot axis), w = cos(outer)
    vec4 intensity;  // rgb, w = cos(inner)
};

layout(std140) uniform Frame {
    mat4 u_view;
    mat4 u_proj;
    mat4 u_view_proj;
    mat4 u_inv_view_proj;
    vec4 u_camera_pos;  // w = time in seconds
    vec4 u_viewport;    // width, height, 1/width, 1/height
    vec4 u_background;  // rgb, w = 1 when an environment map is bound
    vec4 u_ambient;
    ivec4 u_counts;     // x = number of lights, y = frame
    GpuLight u_lights[32];
};

uniform samplerCube u_environment;

const float PI = 3.14159265358979;

// An orthographic projection has no perspective divide (its [2][3] is 0,
// a perspective one's -1): c.camera { ortho = { width = W } }.
bool camera_is_ortho() { return u_proj[2][3] == 0.0; }
vec3 camera_forward() { return -vec3(u_view[0][2], u_view[1][2], u_view[2][2]); }

// The unit direction in which the camera sees world point p: from the eye,
// or the one direction every ray of an orthographic camera has.
vec3 view_direction(vec3 p) { return camera_is_ortho() ? camera_forward() : normalize(p - u_camera_pos.xyz); }
// How far the light from world point p travels to the camera: to the eye,
// or to the image plane of an orthographic camera.
float view_distance(vec3 p)
{
    return camera_is_ortho() ? max(dot(p - u_camera_pos.xyz, camera_forward()), 0.0) : length(p - u_camera_pos.xyz);
}

// Eye-space distance (along the view axis) of a window depth d in [0, 1].
float view_depth(float d)
{
    float z = d * 2.0 - 1.0;
    if (camera_is_ortho())
        return (u_proj[3][2] - z) / u_proj[2][2]; // z_ndc = P22 z_eye + P32
    return u_proj[3][2] / (z + u_proj[2][2]);
}

// Radiance arriving from direction `dir` (world space) from far away
// (bilinear within a face, as the reference's lookup).
vec3 environment_radiance(vec3 dir)
{
    return u_background.w > 0.5 ? textureLod(u_environment, dir, 0.0).rgb : u_background.rgb;
}

// Sample (i, j) of an nx x ny grid over a pixel, as offsets in [-0.5, 0.5]
// along the pixel's two screen derivatives (the box filters over a pixel's
// footprint: environment_radiance_grad, the caustic mapping).
vec2 pixel_grid_point(int i, int j, int nx, int ny)
{
    return (vec2(i, j) + 0.5) / vec2(nx, ny) - 0.5;
}

// The same, averaged over the directions one pixel's rays spread across
// (gx, gy: the direction's change to the next pixel in x and y): the pixel's
// mean instead of one texel picked at its centre, where a curved refractor
// minifies the environment (issue 8: the isolated pixels along a sphere's
// rim). A grid of up to 4 x 4 bilinear lookups along the two gradients, as
// many along each as the half-texels it spans: a box filter over the pixel,
// as anisotropic as the spread (a mip level, isotropic, blurred a rim's thin
// squeeze across both axes: measured worse against the pixel means). A
// spread wider than about a tenth of a radian (a quad straddling a
// silhouette or a total internal reflection, where the difference is not a
// pixel's spread) is clamped to it.
vec3 environment_radiance_grad(vec3 dir, vec3 gx, vec3 gy)
{
    if (u_background.w <= 0.5)
        return u_background.rgb;
    const float MAX_SPREAD = 0.1;
    // a neighbour that is a helper invocation off the surface may hold no
    // direction at all (NaN): then no spread along that axis
    gx = dot(gx, gx) < 1e6 ? gx : vec3(0.0);
    gy = dot(gy, gy) < 1e6 ? gy : vec3(0.0);
    gx *= min(1.0, MAX_SPREAD / max(length(gx), 1e-12));
    gy *= min(1.0, MAX_SPREAD / max(length(gy), 1e-12));
    float texel = 1.5708 / float(textureSize(u_environment, 0).x); // radians, at a face's centre
    int nx = clamp(int(ceil(2.0 * length(gx) / texel)), 1, 4), ny = clamp(int(ceil(2.0 * length(gy) / texel)), 1, 4);
    vec3 sum = vec3(0.0);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            vec2 g = pixel_grid_point(i, j, nx, ny);
            sum += textureLod(u_environment, dir + g.x * gx + g.y * gy, 0.0).rgb;
        }
    return sum / float(nx * ny);
}
