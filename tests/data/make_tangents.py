# Blender 3.4 (blender -b --python tests/data/make_tangents.py): meshes whose
# normal map's tangents Blender computes by MikkTSpace and exports, each
# twice: with TANGENT (the truth) and without (what caustica makes its own
# from: scene/mesh_tangents.c). tests/unit/test_tangents.c compares them.
#   tangents_mirror_*.glb  a UV sphere whose texture is mirrored across x = 0
#                          (MikkTSpace splits the seam's vertices)
#   tangents_folds_*.glb   Suzanne, triangulated, its texture projected along
#                          y, folding wherever the surface turns away
# Both are triangulated in Blender first: MikkTSpace splits a quad along its
# own diagonal, which a glTF file (triangles) does not record.
import os
import bpy

HERE = os.path.dirname(os.path.abspath(__file__))


def material():
    mat = bpy.data.materials.new("normal_mapped")
    mat.use_nodes = True
    nt = mat.node_tree
    img = nt.nodes.new("ShaderNodeTexImage")
    img.image = bpy.data.images.load(os.path.join(HERE, "normal_flat.png"))
    img.image.colorspace_settings.name = "Non-Color"
    nm = nt.nodes.new("ShaderNodeNormalMap")
    nt.links.new(img.outputs["Color"], nm.inputs["Color"])
    nt.links.new(nm.outputs["Normal"], nt.nodes["Principled BSDF"].inputs["Normal"])
    return mat


def project_uvs(mesh, scale):
    uv = mesh.uv_layers.active.data if mesh.uv_layers else mesh.uv_layers.new(name="UVMap").data
    for poly in mesh.polygons:
        for li in poly.loop_indices:
            v = mesh.vertices[mesh.loops[li].vertex_index].co
            uv[li].uv = (0.5 + scale * abs(v.x), 0.5 + scale * v.z)


def finish(name):
    ob = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    bpy.ops.mesh.quads_convert_to_tris()
    bpy.ops.object.mode_set(mode="OBJECT")
    ob.data.materials.append(material())
    for tangents, suffix in ((True, "with"), (False, "without")):
        bpy.ops.export_scene.gltf(filepath=os.path.join(HERE, f"tangents_{name}_{suffix}.glb"), export_format="GLB",
                                  export_tangents=tangents, export_normals=True, export_texcoords=True,
                                  export_materials="EXPORT", use_selection=True)


bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_uv_sphere_add(segments=24, ring_count=12, radius=1)
project_uvs(bpy.context.active_object.data, 0.45)
finish("mirror")

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.mesh.primitive_monkey_add(size=1.0)
project_uvs(bpy.context.active_object.data, 0.4)
finish("folds")
