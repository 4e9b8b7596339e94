/* Texture units, image units and SSBO/UBO binding points, by name: the one
 * list the C side binds with, mirrored by shaders/common/bindings.glsl
 * (tests/cli/bindings_test.sh fails when the two differ). Units are reused
 * across passes (a pass binds what it needs before it draws); the frame's
 * uniform block and the environment stay bound for every pass. */
#ifndef CAUSTICA_BINDINGS_H
#define CAUSTICA_BINDINGS_H

/* Shared by every pass */
#define BINDING_FRAME 0                     /* uniform block Frame (common/frame.glsl) */
#define UNIT_ENVIRONMENT 15                 /* samplerCube u_environment, bound for every pass */
#define UNIT_IMAGE 0                        /* the image a fullscreen pass reads (tonemap, common/copy.frag) */

/* Material textures (common/material.glsl), bound by renderer_draw_objects */
#define MATERIAL_UNIT_BASE_COLOR 16
#define MATERIAL_UNIT_NORMAL 17
#define MATERIAL_UNIT_EMISSIVE 18

/* Morphs and deformers (deform/deform.comp) */
#define DEFORM_SSBO_BASE_POSITIONS 0
#define DEFORM_SSBO_BASE_NORMALS 1
#define DEFORM_SSBO_TARGET_POSITIONS 2
#define DEFORM_SSBO_TARGET_NORMALS 3
#define DEFORM_SSBO_OUT_POSITIONS 4
#define DEFORM_SSBO_OUT_NORMALS 5

/* shade (SHADE_MAX_SHADOWS and SHADE_MAX_CAUSTICS units each) */
#define SHADE_UNIT_SHADOW_2D 1              /* 1..4 */
#define SHADE_UNIT_SHADOW_CUBE 5            /* 5..8 */
#define SHADE_UNIT_CAUSTICS 9               /* 9..12 */

/* refraction */
#define REFRACTION_UNIT_FRONT_NORMAL 1
#define REFRACTION_UNIT_BACK_NORMAL 2
#define REFRACTION_UNIT_FRONT_DEPTH 3
#define REFRACTION_UNIT_BACK_DEPTH 4
#define REFRACTION_UNIT_INPUT_DEPTH 7      /* the input image's depth (lookup = "scene") */
#define REFRACTION_UNIT_BEHIND 5           /* the diffuse scene behind the glass, drawn by the pass (lookup = "scene") */
#define REFRACTION_SSBO_THICKNESS 4         /* Wyman's per-vertex d_N */

/* Impostors of nearby geometry (impostors.glsl, refraction and photon_caustics) */
#define IMPOSTOR_SSBO 5
#define IMPOSTOR_UNIT_DEPTH 6
#define IMPOSTOR_UNIT_COLOR 8

/* The distance map around the refractors (distance_map.c, distance_map/lookup.glsl; refraction) */
#define DISTANCE_MAP_UNIT_COLOR 11
#define DISTANCE_MAP_UNIT_DISTANCE 12
#define DISTANCE_MAP_UNIT_COLOR_BEHIND 13
#define DISTANCE_MAP_UNIT_DISTANCE_BEHIND 14

/* photon_caustics */
#define PHOTON_UNIT_FRONT_NORMAL 1
#define PHOTON_UNIT_BACK_NORMAL 2
#define PHOTON_UNIT_FRONT_DEPTH 3
#define PHOTON_UNIT_BACK_DEPTH 4
#define PHOTON_UNIT_FRONT_MATERIAL 5
#define PHOTON_UNIT_PHOTONS 0
#define PHOTON_UNIT_FLUX 1
#define PHOTON_IMAGE_COUNTS 0
#define PHOTON_IMAGE_CAUSTICS 1
#define PHOTON_UNIT_CAUSTICS 7
#define PHOTON_SSBO_WINDOWS 6                /* per receiver: the box its photons landed in */
#define PHOTON_SSBO_COVER 7                  /* the light view's texels the specular objects cover */

/* caustic_volumes */
#define VOLUMES_SSBO_POSITIONS 0
#define VOLUMES_SSBO_NORMALS 1
#define VOLUMES_SSBO_VOLUMES 3
#define VOLUMES_UNIT_POSITIONS 0
#define VOLUMES_UNIT_NORMALS 1

/* Depth layers (passes/layers.c, shaders/layers/): layered_refraction and layered_caustics */
#define LAYERS_UNIT_BOUNDS 1
#define LAYERS_UNIT_BITS 2
#define LAYERS_UNIT_DEPTH 3
#define LAYERS_UNIT_NORMAL 4
#define LAYERS_UNIT_INFO 5
#define LAYERS_IMAGE_DEPTH 0
#define LAYERS_IMAGE_NORMAL 1
#define LAYERS_IMAGE_INFO 2
#define LAYERS_SSBO_RANGES 6
#define LAYERS_SSBO_MATERIALS 7
#define LAYERED_UNIT_SCENE 9                /* the scene a ray leaving the refractors sees (colour) */
#define LAYERED_UNIT_SCENE_DEPTH 10         /* ... and its depth */
#define LAYERED_UNIT_RECEIVER_NORMAL 11     /* layered_caustics: the receivers seen by the camera */
#define LAYERED_IMAGE_FLUX 3                /* layered_caustics: r32ui array, fixed-point flux per channel */
#define LAYERED_IMAGE_HITS 4                /* layered_caustics: where each photon lands (world xyz, w = 1) */
#define LAYERED_IMAGE_PHOTONS 5             /* layered_caustics: the flux each photon carries */

/* illumination_textures */
#define ILLUM_UNIT_TARGET 1                 /* the virtual camera's normal map and depth */
#define ILLUM_UNIT_TEXTURES 2               /* the illumination textures, one layer per virtual plane */

/* sliced_refraction */
#define SLICED_UNIT_SCENE 1                 /* the camera's image of the scene (without the glass) */
#define SLICED_UNIT_SCENE_DEPTH 2           /* ... and its depth */
#define SLICED_UNIT_SLICES 3                /* the sliced object images */
#define SLICED_SSBO_EXITS 4                 /* per glass vertex: the viewing ray leaving the object */

/* water_surface */
#define SURFACE_UNIT_SCENE 0
#define SURFACE_UNIT_DEPTH 1
#define SURFACE_UNIT_POSITION 2

/* The scene's participating medium (graph/medium_gpu.c, common/medium.glsl) */
#define MEDIUM_UNIT_DENSITY 19

/* beam_caustics */
#define BEAMS_UNIT_DISTANCE 20              /* the distance impostor of the receivers (a cube map) */
#define BEAMS_UNIT_SCENE_DEPTH 21           /* the camera's receivers: depth */
#define BEAMS_UNIT_SCENE_NORMAL 22          /* ... and normal */
#define BEAMS_SSBO_VERTICES 8               /* per lattice vertex: the traced edge rays */
#define BEAMS_SSBO_CELLS 9                  /* the refinement's cell lists and counters */
#define BEAMS_SSBO_BEAMS 10                 /* the beams: vertices, directions, area function, flux */
#define BEAMS_SSBO_COUNTERS 11              /* counters, indirect dispatch and draw arguments */
#define BEAMS_SSBO_ADJACENCY 12             /* per lattice vertex: the beams that have it as a corner */

/* volume_light (the colour it attenuates at UNIT_IMAGE) */
#define VOLUME_LIGHT_UNIT_DEPTH 13
#define VOLUME_LIGHT_UNIT_ADD 23            /* 23..26: radiance images added (volume caustics) */

#endif
