# In Blender (background): tools/blender/vksky_blender.py imports a vksky equirect map as the world with its sun
# lamp; the lamp must point at the sun disc in the map as Blender itself maps directions onto an equirect image
# (Cycles' direction_to_equirectangular: u = 0.5 - atan2(y, x) / 2pi, v = 0.5 + elevation / pi, rows from the
# bottom), and
# shine from the direction of the scene it was made from (AZIMUTH, ELEVATION, as Blender's sun lamp was set).
#
#   blender -b --factory-startup -P import_check.py -- VKSKY_BLENDER_PY MAP.exr AZIMUTH ELEVATION
import math
import os
import sys

import bpy
import mathutils

args = sys.argv[sys.argv.index("--") + 1:]
sys.path.insert(0, os.path.dirname(os.path.abspath(args[0])))
import vksky_blender  # noqa: E402

scene = bpy.context.scene
lamp = vksky_blender.import_sky(scene, args[1])
bpy.context.view_layer.update()
to_sun = (lamp.matrix_world.to_3x3() @ mathutils.Vector((0.0, 0.0, 1.0))).normalized()
fails = []

# The scene's sun (Blender's lamp, exported): the same direction.
want = vksky_blender.direction(float(args[2]), float(args[3]))
angle = math.degrees(to_sun.angle(want))
print("import_check: the imported lamp is %.4f deg from the exported sun" % angle)
if angle > 0.01:
    fails.append("lamp %.4f deg from the scene's sun" % angle)

# The brightest pixel of the map (the sun disc) where Blender looks it up along the lamp's direction.
img = bpy.data.images.load(args[1], check_existing=True)
w, h = img.size
px = img.pixels[:]   # RGBA floats, bottom row first
best, at = -1.0, (0, 0)
for y in range(h):
    row = y * w * 4
    for x in range(w):
        lum = 0.2126 * px[row + 4 * x] + 0.7152 * px[row + 4 * x + 1] + 0.0722 * px[row + 4 * x + 2]
        if lum > best:
            best, at = lum, (x, y)
x, y, z = to_sun
u = 0.5 - math.atan2(y, x) / (2.0 * math.pi)
v = math.atan2(z, math.hypot(x, y)) / math.pi + 0.5
du = ((u * w - (at[0] + 0.5)) + w / 2) % w - w / 2
dv = v * h - (at[1] + 0.5)
print("import_check: map %dx%d, sun disc at pixel (%d, %d); the lamp looks up (%.2f, %.2f): %.2f px off" %
      (w, h, at[0], at[1], u * w, v * h, math.hypot(du, dv)))
if math.hypot(du, dv) > 1.5:
    fails.append("the lamp is %.2f px from the map's sun disc" % math.hypot(du, dv))
if scene.world.node_tree.nodes.get("Environment Texture") is None:
    fails.append("no Environment Texture in the world")
for f in fails:
    print("FAIL: import_check: " + f)
sys.exit(1 if fails else 0)
