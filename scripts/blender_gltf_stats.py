# What a Blender user sees after File > Import > glTF: imports each file given after "--" into an
# empty scene with Blender's own importer and prints one line, "BLENDER_STATS {json}", with the
# visible mesh objects, their vertices and the world bounds (Blender's frame: Z up, metres).
#
#   blender -b --factory-startup --python-exit-code 1 --python scripts/blender_gltf_stats.py -- a.glb
import json
import sys

import numpy

# Debian bookworm's numpy 1.24 removed the numpy.bool alias that Blender 3.4's glTF importer uses.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

import bpy  # noqa: E402  (after the numpy fix)

files = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
for path in files:
    result = bpy.ops.import_scene.gltf(filepath=path)
    if "FINISHED" not in result:
        raise SystemExit("import failed: " + path)

meshes = [o for o in bpy.context.scene.objects if o.type == "MESH" and o.visible_get()]
lo, hi = numpy.full(3, numpy.inf), numpy.full(3, -numpy.inf)
vertices = 0
for o in meshes:
    count = len(o.data.vertices)
    vertices += count
    co = numpy.empty(count * 3)
    o.data.vertices.foreach_get("co", co)
    local = numpy.c_[co.reshape(-1, 3), numpy.ones(count)]
    world = local @ numpy.array(o.matrix_world).T
    lo, hi = numpy.minimum(lo, world[:, :3].min(axis=0)), numpy.maximum(hi, world[:, :3].max(axis=0))
print("BLENDER_STATS " + json.dumps({"meshes": len(meshes), "vertices": vertices, "min": lo.tolist(), "max": hi.tolist()}))
