# vksky <-> Blender (issue 28): export the active camera and sun lamp to a vksky scene (and the flags that place the
# same camera for `vksky --composite`), and import a vksky environment map as the world with the matching sun lamp.
#
# Install as an add-on (Edit > Preferences > Add-ons > Install... this file): File > Export > "vksky scene (.json)"
# and File > Import > "vksky environment map (.exr)". Or from a script / background Blender:
#
#   blender -b scene.blend --factory-startup -P tools/blender/vksky_blender.py -- export OUT.json
#   blender -b --factory-startup -P tools/blender/vksky_blender.py -- import MAP.exr [SAVE.blend]
#
# The conventions (docs/aerial_perspective.md "Conventions", the same in every vksky mode): vksky's frame is
# (north, up, east); in Blender's world (Z up) north is +Y and east +X, so an azimuth is measured from +Y toward +X
# (a compass seen from above), the elevation above the XY plane. Blender's equirect lookup puts an environment map's
# azimuth 0 on +Y: a vksky map needs no rotation. A camera with rotation (X, 0, Z) (XYZ Euler) is yaw = -Z,
# pitch = X - 90; a sun lamp with rotation (X, 0, Z) shines from azimuth 180 - Z, elevation 90 - X.
# Distances: Blender units times the scene's unit scale (metres per unit); the ground is the plane z = 0.
bl_info = {
    "name": "vksky scene and sky",
    "author": "vksky",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Export > vksky scene (.json); File > Import > vksky environment map (.exr)",
    "description": "Camera and sun to a vksky scene; a vksky HDRI as the world with its sun lamp",
    "category": "Import-Export",
}

import json
import math
import struct
import sys

import bpy
import mathutils

# --- Conventions -----------------------------------------------------------------------------------------------


def azimuth_elevation(direction):
    """vksky's (azimuth, elevation) in degrees of a Blender world direction (north +Y, east +X, up +Z)."""
    x, y, z = direction.normalized()
    return math.degrees(math.atan2(x, y)), math.degrees(math.asin(max(-1.0, min(1.0, z))))


def direction(azimuth_deg, elevation_deg):
    """The Blender world direction of a vksky (azimuth, elevation)."""
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    return mathutils.Vector((math.cos(el) * math.sin(az), math.cos(el) * math.cos(az), math.sin(el)))


def vertical_fov_deg(scene, cam):
    """The camera's vertical field of view for the scene's image size (Blender's sensor fit rules)."""
    r = scene.render
    w = r.resolution_x * r.pixel_aspect_x
    h = r.resolution_y * r.pixel_aspect_y
    d = cam.data
    fit = d.sensor_fit
    if fit == 'AUTO':
        fit = 'HORIZONTAL' if w >= h else 'VERTICAL'
    sensor = d.sensor_height if (fit == 'VERTICAL' and d.sensor_fit == 'VERTICAL') else d.sensor_width
    half = sensor / (2.0 * d.lens)   # tan of half the angle across the fitted side
    if fit == 'HORIZONTAL':
        half *= h / w
    return math.degrees(2.0 * math.atan(half))


# --- Export ------------------------------------------------------------------------------------------------------


def find_sun(scene):
    suns = [o for o in scene.objects if o.type == 'LIGHT' and o.data.type == 'SUN' and not o.hide_render]
    return suns[0] if suns else None


def export_scene(scene, path):
    """Writes the vksky scene (PATH) and the --composite flags that place the same camera (PATH less .json plus
    .args, one line). Returns the scene as a dict."""
    bpy.context.view_layer.update()   # matrix_world of objects moved by a script since the last update
    cam = scene.camera
    if cam is None or cam.type != 'CAMERA' or cam.data.type != 'PERSP':
        raise RuntimeError("vksky export: the scene needs an active perspective camera")
    unit = scene.unit_settings.scale_length or 1.0   # metres per Blender unit
    m = cam.matrix_world
    forward = -(m.to_3x3() @ mathutils.Vector((0.0, 0.0, 1.0)))
    up = m.to_3x3() @ mathutils.Vector((0.0, 1.0, 0.0))
    yaw, pitch = azimuth_elevation(forward)
    # vksky's camera has no roll: the screen's up is the vertical plane's. Say so when Blender's camera rolls.
    level_up = mathutils.Vector((0.0, 0.0, 1.0)) - forward.normalized() * forward.normalized().z
    roll = math.degrees(up.angle(level_up)) if level_up.length > 1e-9 else 0.0
    fov = vertical_fov_deg(scene, cam)
    pos = m.translation
    out = {
        "description": "exported from Blender %s by tools/blender/vksky_blender.py: camera '%s'%s, world unit %g m; "
                       "composite with the flags in the .args file beside this one" %
                       (bpy.app.version_string, cam.name, " (its roll of %.2f deg is not kept)" % roll
                        if roll > 0.01 else "", unit),
        "camera": {"altitude_km": pos.z * unit / 1000.0, "yaw_deg": yaw, "pitch_deg": pitch, "fov_deg": fov},
        "output": {"width": scene.render.resolution_x * scene.render.resolution_percentage // 100,
                   "height": scene.render.resolution_y * scene.render.resolution_percentage // 100},
    }
    args = ["--camera-position", "%.9g,%.9g,%.9g" % tuple(pos), "--yaw", "%.9g" % yaw, "--pitch", "%.9g" % pitch,
            "--fov", "%.9g" % fov, "--world-unit", "%.9g" % unit, "--world-up", "z"]
    sun = find_sun(scene)
    if sun is not None:
        to_sun = sun.matrix_world.to_3x3() @ mathutils.Vector((0.0, 0.0, 1.0))   # a sun shines along its -Z
        az, el = azimuth_elevation(to_sun)
        out["sun"] = {"azimuth_deg": az, "elevation_deg": el}
        args += ["--sun-azimuth", "%.9g" % az, "--sun-elevation", "%.9g" % el]
    with open(path, "w") as f:
        json.dump(out, f, indent=2)
        f.write("\n")
    base = path[:-5] if path.lower().endswith(".json") else path
    with open(base + ".args", "w") as f:
        f.write(" ".join(args) + "\n")
    return out


# --- Import ------------------------------------------------------------------------------------------------------


def read_exr_header(path):
    """The first part's header attributes of an OpenEXR file: {name: (type, raw bytes)}."""
    attrs = {}
    with open(path, "rb") as f:
        data = f.read(1 << 20)
    if data[:4] != b"\x76\x2f\x31\x01":
        raise RuntimeError("%s: not an OpenEXR file" % path)
    i = 8
    while i < len(data) and data[i] != 0:
        name_end = data.index(b"\0", i)
        type_end = data.index(b"\0", name_end + 1)
        size = struct.unpack_from("<i", data, type_end + 1)[0]
        start = type_end + 5
        attrs[data[i:name_end].decode()] = (data[name_end + 1:type_end].decode(), data[start:start + size])
        i = start + size
    return attrs


def sky_sun(attrs):
    """(azimuth, elevation, illuminance at the camera or None) of a vksky map's sun, from its header."""
    if "vksky:sunDirection" in attrs:
        n, u, e = struct.unpack("<3f", attrs["vksky:sunDirection"][1])   # vksky's (north, up, east)
        az, el = azimuth_elevation(mathutils.Vector((e, n, u)))
    elif "vksky:scene" in attrs:
        sun = json.loads(attrs["vksky:scene"][1].decode()).get("sun", {})
        if "azimuth_deg" not in sun:
            raise RuntimeError("the map's vksky:scene gives its sun by date and place: no angles to read")
        az, el = sun["azimuth_deg"], sun["elevation_deg"]
    else:
        raise RuntimeError("not a vksky map: no vksky:sunDirection or vksky:scene attribute")
    lux = None
    if "vksky:sunIlluminanceAtCamera" in attrs:
        r, g, b = struct.unpack("<3f", attrs["vksky:sunIlluminanceAtCamera"][1])
        lux = 0.2126 * r + 0.7152 * g + 0.0722 * b
    return az, el, lux


def import_sky(scene, path):
    """The map as the world (Environment Texture, equirect, no rotation: the conventions agree) and a sun lamp
    'vksky sun' from its header (rotation X = 90 - elevation, Z = 180 - azimuth; strength the luminance of the
    illuminance at the camera, in the map's units). Returns the lamp."""
    attrs = read_exr_header(path)
    az, el, lux = sky_sun(attrs)
    world = scene.world or bpy.data.worlds.new("vksky")
    scene.world = world
    world.use_nodes = True
    nodes, links = world.node_tree.nodes, world.node_tree.links
    nodes.clear()
    env = nodes.new("ShaderNodeTexEnvironment")
    env.image = bpy.data.images.load(path, check_existing=True)
    env.projection = 'EQUIRECTANGULAR'
    bg = nodes.new("ShaderNodeBackground")
    out = nodes.new("ShaderNodeOutputWorld")
    links.new(env.outputs["Color"], bg.inputs["Color"])
    links.new(bg.outputs["Background"], out.inputs["Surface"])
    lamp = bpy.data.objects.get("vksky sun")
    if lamp is None:
        lamp = bpy.data.objects.new("vksky sun", bpy.data.lights.new("vksky sun", 'SUN'))
        scene.collection.objects.link(lamp)
    lamp.rotation_mode = 'XYZ'
    lamp.rotation_euler = (math.radians(90.0 - el), 0.0, math.radians(180.0 - az))
    if lux is not None:
        lamp.data.energy = lux
    return lamp


# --- Add-on ------------------------------------------------------------------------------------------------------

try:
    from bpy_extras.io_utils import ExportHelper, ImportHelper

    class VKSKY_OT_export(bpy.types.Operator, ExportHelper):
        """Export the active camera and sun lamp to a vksky scene"""
        bl_idname = "export_scene.vksky"
        bl_label = "Export vksky scene"
        filename_ext = ".json"

        def execute(self, context):
            export_scene(context.scene, self.filepath)
            return {'FINISHED'}

    class VKSKY_OT_import(bpy.types.Operator, ImportHelper):
        """Import a vksky environment map as the world, with its sun lamp"""
        bl_idname = "import_scene.vksky"
        bl_label = "Import vksky sky"
        filename_ext = ".exr"

        def execute(self, context):
            import_sky(context.scene, self.filepath)
            return {'FINISHED'}

    def _menu_export(self, context):
        self.layout.operator(VKSKY_OT_export.bl_idname, text="vksky scene (.json)")

    def _menu_import(self, context):
        self.layout.operator(VKSKY_OT_import.bl_idname, text="vksky environment map (.exr)")

    def register():
        bpy.utils.register_class(VKSKY_OT_export)
        bpy.utils.register_class(VKSKY_OT_import)
        bpy.types.TOPBAR_MT_file_export.append(_menu_export)
        bpy.types.TOPBAR_MT_file_import.append(_menu_import)

    def unregister():
        bpy.types.TOPBAR_MT_file_export.remove(_menu_export)
        bpy.types.TOPBAR_MT_file_import.remove(_menu_import)
        bpy.utils.unregister_class(VKSKY_OT_import)
        bpy.utils.unregister_class(VKSKY_OT_export)
except ImportError:   # a Blender without bpy_extras: the functions still work from scripts
    pass


def main(argv):
    args = argv[argv.index("--") + 1:] if "--" in argv else []
    if len(args) >= 2 and args[0] == "export":
        export_scene(bpy.context.scene, args[1])
    elif len(args) >= 2 and args[0] == "import":
        import_sky(bpy.context.scene, args[1])
        if len(args) >= 3:
            bpy.ops.wm.save_as_mainfile(filepath=args[2])
    elif args:
        print("usage: blender -b [FILE.blend] -P vksky_blender.py -- export OUT.json | import MAP.exr [SAVE.blend]",
              file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main(sys.argv)
