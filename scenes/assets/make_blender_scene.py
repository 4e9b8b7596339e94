# Makes scenes/assets/blender_scene.glb with Blender's own glTF exporter
# (issue 51: Blender as the client), and Blender's render of it through the
# same camera, scenes/assets/blender_scene_cycles.png, which
# tests/lua/gltf_scene_test.lua holds caustica's framing to. Remake both:
#
#   blender -b --python scenes/assets/make_blender_scene.py -- scenes/assets
#
# (Debian's blender 3.4.) The scene: a floor, a glass ball with volume
# absorption, a block of water, a spot light, a camera, a red cube on a
# keyframed path and a green rod bent by a two-bone armature (a skin).
import math
import os
import sys

import bpy

out_dir = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "."
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.render.fps = 24
scene.frame_start, scene.frame_end = 1, 48


def material(name, color, transmission=0.0, ior=1.5, roughness=0.5, volume=None):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes, links = m.node_tree.nodes, m.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*color, 1.0)
    bsdf.inputs["Transmission"].default_value = transmission
    bsdf.inputs["IOR"].default_value = ior
    bsdf.inputs["Roughness"].default_value = roughness
    if volume:
        # KHR_materials_volume: the exporter reads the absorption from a
        # Volume Absorption node and the thickness from a node group named
        # "glTF Material Output"
        colour, density, thickness = volume
        absorb = nodes.new("ShaderNodeVolumeAbsorption")
        absorb.inputs["Color"].default_value = (*colour, 1.0)
        absorb.inputs["Density"].default_value = density
        links.new(absorb.outputs["Volume"], nodes["Material Output"].inputs["Volume"])
        group = bpy.data.node_groups.get("glTF Material Output")
        if group is None:
            group = bpy.data.node_groups.new("glTF Material Output", "ShaderNodeTree")
            group.inputs.new("NodeSocketFloat", "Thickness")
        gnode = nodes.new("ShaderNodeGroup")
        gnode.node_tree = group
        gnode.inputs["Thickness"].default_value = thickness
    return m


def add(obj, mat):
    obj.data.materials.append(mat)
    return obj


bpy.ops.mesh.primitive_plane_add(size=6, location=(0, 0, 0))
floor = add(bpy.context.object, material("Floor", (0.7, 0.7, 0.68), roughness=0.9))
floor.name = "Floor"

bpy.ops.mesh.primitive_uv_sphere_add(radius=0.5, segments=64, ring_count=32, location=(-0.7, 0, 0.5))
ball = add(bpy.context.object, material("Glass", (1, 1, 1), transmission=1.0, ior=1.5, roughness=0.0,
                                        volume=((0.75, 0.9, 1.0), 0.5, 1.0)))
ball.name = "Glass"
bpy.ops.object.shade_smooth()

bpy.ops.mesh.primitive_cube_add(size=1, location=(0.9, 0.2, 0.2))
water = bpy.context.object
water.scale = (0.7, 0.7, 0.2)
add(water, material("Water", (1, 1, 1), transmission=1.0, ior=1.33, roughness=0.0))
water.name = "Water"

# the red cube on a keyframed path
bpy.ops.mesh.primitive_cube_add(size=0.3, location=(0.9, -1.2, 0.15))
mover = add(bpy.context.object, material("Red", (0.8, 0.05, 0.03)))
mover.name = "Mover"
mover.keyframe_insert("location", frame=1)
mover.keyframe_insert("rotation_euler", frame=1)
mover.location = (-0.9, -1.2, 0.15)
mover.rotation_euler = (0, 0, math.radians(90))
mover.keyframe_insert("location", frame=48)
mover.keyframe_insert("rotation_euler", frame=48)

# the green rod and its armature: two bones along +z, the upper one bent
bpy.ops.object.armature_add(enter_editmode=True, location=(0, 1.0, 0))
arm = bpy.context.object
arm.name = "Armature"
bones = arm.data.edit_bones
lower = bones[0]
lower.name = "Lower"
lower.head, lower.tail = (0, 0, 0), (0, 0, 0.6)
upper = bones.new("Upper")
upper.head, upper.tail = (0, 0, 0.6), (0, 0, 1.2)
upper.parent = lower
bpy.ops.object.mode_set(mode="OBJECT")
# a closed tube of 13 rings, so that it bends smoothly
verts, faces, sides, rings = [], [], 24, 13
for r in range(rings):
    z = 1.2 * r / (rings - 1)
    for k in range(sides):
        a = 2 * math.pi * k / sides
        verts.append((0.1 * math.cos(a), 0.1 * math.sin(a), z))
for r in range(rings - 1):
    for k in range(sides):
        a, b = r * sides + k, r * sides + (k + 1) % sides
        faces.append((a, b, b + sides, a + sides))
faces.append(tuple(reversed(range(sides))))
faces.append(tuple((rings - 1) * sides + k for k in range(sides)))
mesh = bpy.data.meshes.new("Rod")
mesh.from_pydata(verts, [], faces)
mesh.update()
rod = bpy.data.objects.new("Rod", mesh)
rod.location = (0, 1.0, 0)
scene.collection.objects.link(rod)
add(rod, material("Green", (0.1, 0.6, 0.15)))
for poly in mesh.polygons:
    poly.use_smooth = True
bpy.ops.object.select_all(action="DESELECT")
rod.select_set(True)
arm.select_set(True)
bpy.context.view_layer.objects.active = arm
bpy.ops.object.parent_set(type="ARMATURE_AUTO")
bpy.ops.object.mode_set(mode="POSE")
pb = arm.pose.bones["Upper"]
pb.rotation_mode = "XYZ"
pb.rotation_euler = (0, 0, 0)
pb.keyframe_insert("rotation_euler", frame=1)
pb.rotation_euler = (math.radians(70), 0, 0)
pb.keyframe_insert("rotation_euler", frame=48)
bpy.ops.object.mode_set(mode="OBJECT")

# the spot light and the camera
bpy.ops.object.light_add(type="SPOT", location=(2.0, -2.0, 4.0))
spot = bpy.context.object
spot.name = "Spot"
spot.data.energy = 1500.0
spot.data.spot_size = math.radians(60)
spot.data.spot_blend = 0.2
spot.rotation_euler = (math.radians(40), 0, math.radians(45))

bpy.ops.object.camera_add(location=(0, -5.0, 3.0))
cam = bpy.context.object
cam.name = "Camera"
cam.data.lens = 35
direction = (0 - 0, 0.0 - (-5.0), 0.4 - 3.0)
cam.rotation_euler = (math.atan2(math.hypot(direction[0], direction[1]), -direction[2]), 0, 0)
scene.camera = cam

scene.render.resolution_x, scene.render.resolution_y = 160, 120
bpy.ops.export_scene.gltf(filepath=os.path.join(out_dir, "blender_scene.glb"), export_format="GLB",
                          export_cameras=True, export_lights=True, export_animations=True, export_skins=True,
                          export_yup=True)

# Blender's own render through the camera at frame 1 (Cycles, on the CPU)
scene.frame_set(1)
scene.render.engine = "CYCLES"
scene.cycles.samples = 32
scene.cycles.use_denoising = False  # Debian's build has no OpenImageDenoise
scene.cycles.device = "CPU"
world = bpy.data.worlds.new("World")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.3
scene.world = world
scene.render.image_settings.file_format = "PNG"
scene.render.filepath = os.path.join(out_dir, "blender_scene_cycles.png")
bpy.ops.render.render(write_still=True)
