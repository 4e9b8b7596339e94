// One caustic volume (std430): the generator triangle's corners, the unit
// refracted light rays at them, the rays' ends below the deepest receiver,
// and the light power through the triangle (rgb) with its area (w).
struct CausticVolume {
    vec4 top[3];
    vec4 dir[3];
    vec4 bottom[3];
    vec4 flux;
};
layout(std430) buffer Volumes { CausticVolume volumes[]; };
