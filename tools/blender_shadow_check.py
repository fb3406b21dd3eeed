"""Does a vksky HDRI light a scene? (issue 32; docs/units.md "The HDRI in Blender")

    blender -b --factory-startup -P tools/blender_shadow_check.py -- SKY.exr OUT.exr

Cycles (CPU, 64 samples) renders a white Lambertian plane under SKY.exr as the world (strength 1, nothing else) with a
2 m pole at the origin, seen from above by an orthographic camera over [-5, 5] m; the sun of the map (east, +X in
Blender, docs/environment_maps.md) casts the pole's shadow toward -X. Prints the mean of a lit patch, of a patch in
the shadow and their ratio: the sky alone gives ~1, a sun carrying its power gives the ratio of (sun + sky) to sky
illuminance on the plane (several, at 30 deg elevation)."""
import sys

import bpy

args = sys.argv[sys.argv.index("--") + 1:]
sky_path, out_path = args[0], args[1]
scene = bpy.context.scene
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o, do_unlink=True)
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 64
scene.cycles.use_denoising = False
scene.render.resolution_x = scene.render.resolution_y = 100
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "32"
scene.view_settings.view_transform = "Standard"

world = scene.world or bpy.data.worlds.new("World")
scene.world = world
world.use_nodes = True
nodes = world.node_tree.nodes
env = nodes.new("ShaderNodeTexEnvironment")
env.image = bpy.data.images.load(sky_path)
bg = nodes["Background"]
bg.inputs["Strength"].default_value = 1.0
world.node_tree.links.new(env.outputs["Color"], bg.inputs["Color"])
world.cycles.sampling_method = "MANUAL"
world.cycles.sample_map_resolution = 1024

white = bpy.data.materials.new("white")
white.use_nodes = True
white.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.8, 0.8, 0.8, 1.0)
white.node_tree.nodes["Principled BSDF"].inputs["Specular"].default_value = 0.0
bpy.ops.mesh.primitive_plane_add(size=10.0, location=(0, 0, 0))
bpy.context.object.data.materials.append(white)
bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0, 0, 1.0), scale=(0.25, 0.25, 1.0))
bpy.context.object.data.materials.append(white)

bpy.ops.object.camera_add(location=(0, 0, 20), rotation=(0, 0, 0))
cam = bpy.context.object
cam.data.type = "ORTHO"
cam.data.ortho_scale = 10.0
scene.camera = cam
scene.render.filepath = out_path
bpy.ops.render.render(write_still=True)

img = bpy.data.images.load(out_path)
w, h = img.size
px = list(img.pixels)


def mean(x0, x1, y0, y1):
    """Mean luminance over the plane's patch [x0, x1] x [y0, y1] metres (+X right, +Y up in the image)."""
    s, n = 0.0, 0
    for j in range(h):
        y = (j + 0.5) / h * 10.0 - 5.0
        if not y0 <= y <= y1:
            continue
        for i in range(w):
            x = (i + 0.5) / w * 10.0 - 5.0
            if x0 <= x <= x1:
                k = 4 * (j * w + i)
                s += 0.2126 * px[k] + 0.7152 * px[k + 1] + 0.0722 * px[k + 2]
                n += 1
    return s / n


lit = mean(1.0, 3.0, 1.0, 3.0)
shadow = mean(-2.6, -1.0, -0.15, 0.15)
print("blender_shadow_check: lit %.6g shadow %.6g ratio %.3f" % (lit, shadow, lit / shadow))
