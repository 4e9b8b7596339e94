#version 450 core
// The first surface of every object, glass, water and mirrors included, for
// an EXR render (src/graph/renderer.c, renderer_first_surface): coverage
// (its alpha), the distance along the camera's view axis (its Z, as
// compositors read it: the same measure as a depth layer) and the object's
// id + 1 (its objectId), where depth testing leaves the nearest surface.
#include "common/frame.glsl"
in vec3 v_world;
uniform int u_object_id;
out vec4 o_surface;
void main()
{
    float along_view = -(u_view * vec4(v_world, 1.0)).z;
    o_surface = vec4(1.0, along_view, float(u_object_id + 1), 1.0);
}
