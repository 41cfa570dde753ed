"""Writes the glTF test scenes and their OBJ twins with trimesh (an independent glTF writer).

Run from this folder: python make_gltf.py  (needs trimesh and numpy; the versions used are
written to generated.txt).

- scene.glb: a smooth icosphere (vertex normals) and a box under a parent node with a
  rotation, a non-uniform scale and a translation, materials `red` and `blue`
  (baseColorFactor). scene_sphere.obj / scene_box.obj: the same two meshes with the node
  transforms applied here (numpy, float64) and glTF's frame turned into the renderer's
  (z negated), with their vertex normals (by the inverse transpose).
- tri.gltf + tri.bin: one triangle with an external buffer (for the missing-buffer test).
"""
import json
import numpy as np
import trimesh
from trimesh.transformations import rotation_matrix, translation_matrix, scale_matrix, concatenate_matrices

FLIP = np.diag([1.0, 1.0, -1.0, 1.0])


def material(name, rgb):
    return trimesh.visual.material.PBRMaterial(
        name=name, baseColorFactor=[*rgb, 1.0], metallicFactor=0.0, roughnessFactor=1.0)


sphere = trimesh.creation.icosphere(subdivisions=2, radius=0.6)
sphere.visual = trimesh.visual.TextureVisuals(material=material("red", [0.7, 0.15, 0.1]))
box = trimesh.creation.box(extents=[0.8, 0.5, 0.6])
box.visual = trimesh.visual.TextureVisuals(material=material("blue", [0.1, 0.2, 0.6]))

scene = trimesh.Scene()
parent = concatenate_matrices(translation_matrix([0.2, -0.1, -0.3]),
                              rotation_matrix(0.4, [0, 1, 0]))
scene.graph.update(frame_to="parent", frame_from="world", matrix=parent)
sphere_m = concatenate_matrices(translation_matrix([-0.5, 0.1, 0.0]), scale_matrix(1.1))
box_m = concatenate_matrices(translation_matrix([0.6, -0.2, 0.2]),
                             rotation_matrix(0.7, [1, 0.3, 0]),
                             np.diag([1.2, 0.9, 1.0, 1.0]))
scene.add_geometry(sphere, node_name="sphere", geom_name="sphere", parent_node_name="parent",
                   transform=sphere_m)
scene.add_geometry(box, node_name="box", geom_name="box", parent_node_name="parent",
                   transform=box_m)
scene.export("scene.glb", include_normals=True)

for name, mesh, m in [("sphere", sphere, sphere_m), ("box", box, box_m)]:
    # positions by the node matrices, normals (the ones the GLB carries) by their inverse
    # transpose, both then into the renderer's frame (z negated); computed here in float64
    world = concatenate_matrices(FLIP, parent, m)
    v = (world @ np.c_[mesh.vertices, np.ones(len(mesh.vertices))].T).T[:, :3]
    n = (np.linalg.inv(world[:3, :3]).T @ mesh.vertex_normals.T).T
    n /= np.linalg.norm(n, axis=1)[:, None]
    with open(f"scene_{name}.obj", "w") as f:
        f.write("# written by make_gltf.py\n")
        f.writelines(f"v {a:.9g} {b:.9g} {c:.9g}\n" for a, b, c in v)
        f.writelines(f"vn {a:.9g} {b:.9g} {c:.9g}\n" for a, b, c in n)
        f.writelines(f"f {a+1}//{a+1} {b+1}//{b+1} {c+1}//{c+1}\n" for a, b, c in mesh.faces)

# one triangle with its buffer in tri.bin
pos = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype="<f4")
open("tri.bin", "wb").write(pos.tobytes())
doc = {
    "asset": {"version": "2.0", "generator": "make_gltf.py"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "buffers": [{"byteLength": 36, "uri": "tri.bin"}],
}
open("tri.gltf", "w").write(json.dumps(doc, indent=1) + "\n")
open("generated.txt", "w").write(f"trimesh {trimesh.__version__}, numpy {np.__version__}\n")
