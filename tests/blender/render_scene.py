# Seed 004's scene rendered by Blender as a user would (issue 28): camera 218.8 m up, a ground plane, spheres at
# 1-20 km, black world, Film > Transparent, Position and Depth passes, Cycles with 16 samples and the default
# pixel filter (Blackman-Harris, 1.5 px), two view layers (Other: without the spheres) and the compositor on (an
# Exposure node, +1 EV, so Composite.Combined is not the render), saved as one float multilayer EXR. Then the same
# with an opaque film (a bad input), and the camera and sun exported by tools/blender/vksky_blender.py.
#
#   blender -b --factory-startup -P render_scene.py -- OUTDIR VKSKY_BLENDER_PY [WIDTH HEIGHT]
#   OUTDIR/render.exr, OUTDIR/opaque.exr, OUTDIR/scene.json, OUTDIR/scene.args, OUTDIR/spheres.txt
import math
import os
import sys
import time

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
out_dir, addon = args[0], args[1]
width, height = (int(args[2]), int(args[3])) if len(args) >= 4 else (160, 90)
sys.path.insert(0, os.path.dirname(os.path.abspath(addon)))
import vksky_blender  # noqa: E402

for o in list(bpy.data.objects):
    bpy.data.objects.remove(o, do_unlink=True)
scene = bpy.context.scene
scene.unit_settings.scale_length = 1.0

camera_pos = (-3.5, -8.5, 218.8)
cam = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
scene.collection.objects.link(cam)
cam.location = camera_pos
cam.rotation_euler = (math.radians(87.0), 0.0, math.radians(-95.0))   # pitch -3, yaw 95 (seed 004)
cam.data.lens = 50.0
cam.data.clip_start, cam.data.clip_end = 0.1, 1.0e6
scene.camera = cam

bpy.ops.mesh.primitive_plane_add(size=400000.0, location=(0.0, 0.0, 0.0))
ground = bpy.context.object
ground.name = "Ground"
spheres = bpy.data.collections.new("Spheres")
scene.collection.children.link(spheres)
centres = []
yaw = math.radians(95.0)
for d, off in ((1000.0, -6.0), (5000.0, -2.0), (10000.0, 2.0), (20000.0, 6.0)):
    a = yaw + math.radians(off)
    r = 0.03 * d
    c = (camera_pos[0] + d * math.sin(a), camera_pos[1] + d * math.cos(a), r)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=r, location=c, segments=48, ring_count=24)
    s = bpy.context.object
    bpy.ops.object.shade_smooth()
    for coll in s.users_collection:
        coll.objects.unlink(s)
    spheres.objects.link(s)
    centres.append((c, r))
with open(os.path.join(out_dir, "spheres.txt"), "w") as f:
    for c, r in centres:
        f.write("%.6f %.6f %.6f %.6f\n" % (c[0], c[1], c[2], r))

sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN'))
scene.collection.objects.link(sun)
sun.rotation_euler = (math.radians(60.0), 0.0, math.radians(165.0))   # elevation 30, azimuth 15
sun.data.energy = 3.0
world = scene.world or bpy.data.worlds.new("World")
scene.world = world
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0

r = scene.render
r.engine = 'CYCLES'
scene.cycles.device = 'CPU'
scene.cycles.samples = 16
scene.cycles.use_adaptive_sampling = False
scene.cycles.use_denoising = False
scene.cycles.seed = 1
r.threads_mode = 'FIXED'
r.threads = 2
r.resolution_x, r.resolution_y, r.resolution_percentage = width, height, 100
r.film_transparent = True
r.image_settings.file_format = 'OPEN_EXR_MULTILAYER'
r.image_settings.color_depth = '32'
r.image_settings.exr_codec = 'ZIP'

vl = scene.view_layers[0]
vl.name = "ViewLayer"
vl.use_pass_position = True
vl.use_pass_z = True
other = scene.view_layers.new("Other")
other.use_pass_position = True
other.layer_collection.children["Spheres"].exclude = True

scene.use_nodes = True
tree = scene.node_tree
rl = tree.nodes["Render Layers"]
comp = tree.nodes["Composite"]
exposure = tree.nodes.new("CompositorNodeExposure")
exposure.inputs["Exposure"].default_value = 1.0
tree.links.new(rl.outputs["Image"], exposure.inputs["Image"])
tree.links.new(exposure.outputs["Image"], comp.inputs["Image"])

vksky_blender.export_scene(scene, os.path.join(out_dir, "scene.json"))
t0 = time.time()
r.filepath = os.path.join(out_dir, "render.exr")
bpy.ops.render.render(write_still=True)
print("render_scene: %dx%d, 2 view layers, %d samples: %.1f s" % (width, height, scene.cycles.samples,
                                                                   time.time() - t0))
# The same film made opaque, small and fast: what a user gets with Film > Transparent off.
other.use = False
r.film_transparent = False
r.resolution_percentage = 50
scene.cycles.samples = 4
r.filepath = os.path.join(out_dir, "opaque.exr")
bpy.ops.render.render(write_still=True)
