# SPDX-License-Identifier: MIT
# blender_fixtures.py - the glTF test files of `strand import`, written by
# Blender's own glTF exporter, and what Blender itself evaluates.
#
#   blender -b --factory-startup -P tools/blender_fixtures.py -- OUTDIR
#
# (make blender-fixtures). Builds each test scene, exports it twice (every
# frame sampled, and as keyframes), and writes OUTDIR/<scene>.blender.csv:
# the world position of every object and bone at every frame, in glTF's
# axes (Y up: Blender's (x, y, z) is glTF's (x, z, -y)).
import math
import sys

import bpy
from mathutils import Vector

FPS = 24
OUT = sys.argv[sys.argv.index("--") + 1]


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    s = bpy.context.scene
    s.render.fps = FPS
    s.render.fps_base = 1
    s.frame_start = 0
    return s


def empty(name, parent=None, loc=(0, 0, 0)):
    o = bpy.data.objects.new(name, None)
    bpy.context.scene.collection.objects.link(o)
    o.parent = parent
    o.location = loc
    return o


def key(o, frame, **kw):
    for attr, value in kw.items():
        setattr(o, attr, value)
        o.keyframe_insert(data_path=attr, frame=frame)


def hierarchy(s):
    """A chain of objects, a long spin and a scaled parent with rotating children."""
    s.frame_end = 96
    base = empty("Base")
    arm = empty("Arm.001", base, (1.0, 0, 0.5))
    tip = empty("Tip", arm, (0, 0.8, 0))
    key(base, 0, location=(0, 0, 0), rotation_euler=(0, 0, 0))
    key(base, 40, location=(0.5, -0.25, 0.2), rotation_euler=(0, 0, math.radians(90)))
    key(base, 96, location=(-0.3, 0.4, 0), rotation_euler=(math.radians(20), 0, math.radians(-30)))
    key(arm, 0, rotation_euler=(0, 0, 0))
    key(arm, 60, rotation_euler=(math.radians(45), math.radians(10), 0))
    key(tip, 0, location=(0, 0.8, 0), scale=(1, 1, 1))
    key(tip, 96, location=(0, 1.2, 0.1), scale=(1.5, 1, 0.5))
    spin = empty("Spinner", None, (2, 0, 0))
    spin.rotation_mode = "QUATERNION"
    blade = empty("Blade", spin, (0.5, 0, 0))
    for f in range(0, 97, 8):
        a = math.radians(15 * f)  # 5 turns over 96 frames, a key every 8
        key(spin, f, rotation_quaternion=(math.cos(a / 2), 0, 0, math.sin(a / 2)))
    for fc in spin.animation_data.action.fcurves:
        for kp in fc.keyframe_points:
            kp.interpolation = "LINEAR"
    scaled = empty("Scaled", None, (0, 2, 0))
    scaled.scale = (2, 0.5, 1)
    kid = empty("Kid", scaled, (0.5, 0.5, 0))
    key(kid, 0, rotation_euler=(0, 0, 0))
    key(kid, 48, rotation_euler=(0, math.radians(60), math.radians(30)))
    key(kid, 96, rotation_euler=(0, 0, math.radians(-45)))
    step = empty("Stepper", None, (0, 0, 1))
    key(step, 0, location=(0, 0, 1))
    key(step, 30, location=(0, 0.5, 1))
    key(step, 70, location=(0.5, 0.5, 1))
    for fc in step.animation_data.action.fcurves:
        for kp in fc.keyframe_points:
            kp.interpolation = "CONSTANT"


def armature(s):
    """An armature of three bones posed over time, an empty on the last bone."""
    s.frame_end = 72
    data = bpy.data.armatures.new("Rig")
    arm = bpy.data.objects.new("Rig", data)
    s.collection.objects.link(arm)
    bpy.context.view_layer.objects.active = arm
    bpy.ops.object.mode_set(mode="EDIT")
    prev = None
    for i, name in enumerate(["Hip", "Knee", "Ankle"]):
        b = data.edit_bones.new(name)
        b.head = Vector((0, 0, 1.0 - 0.4 * i))
        b.tail = Vector((0, 0.05, 0.6 - 0.4 * i))
        if prev:
            b.parent = prev
            b.use_connect = True
        prev = b
    bpy.ops.object.mode_set(mode="POSE")
    for i, pb in enumerate(arm.pose.bones):
        pb.rotation_mode = "QUATERNION"
        for f, deg in ((0, 0), (24, 30 + 10 * i), (48, -20), (72, 0)):
            a = math.radians(deg)
            pb.rotation_quaternion = (math.cos(a / 2), math.sin(a / 2), 0, 0)
            pb.keyframe_insert("rotation_quaternion", frame=f)
    bpy.ops.object.mode_set(mode="OBJECT")
    key(arm, 0, location=(0, 0, 0))
    key(arm, 72, location=(0.5, 0, 0))


# tests/import/urdf/arm.urdf's joints as `strand import` puts them (axes in
# the rest pose's coordinates), which the robot scene's empties follow in
# glTF's axes: Blender's axis is (x, -z, y) of glTF's (x, y, z)
ARM_JOINTS = (
    ("pan", "revolute", (0, 0, 1)),
    ("lift", "revolute", (-0.50953628660839789, 0.81023918587025623, 0.28962947762551555)),
    ("reach", "prismatic", (0.78764701433531426, 0.30370217994739307, 0.53607570986183151)),
)


def robot(s):
    """Empties named after the arm's joints, each turning about or sliding
    along its joint's axis, to drive the URDF's joints by name."""
    s.frame_end = 48
    values = {}
    for name, kind, a in ARM_JOINTS:
        b = Vector((a[0], -a[2], a[1]))
        o = empty(name)
        o.rotation_mode = "QUATERNION"
        for f in range(0, 49, 4):
            if kind == "revolute":
                deg = (400 if name == "pan" else 60) * math.sin(math.pi * f / 96.0)
                h = math.radians(deg) / 2
                o.rotation_quaternion = (math.cos(h), b.x * math.sin(h), b.y * math.sin(h),
                                         b.z * math.sin(h))
                o.keyframe_insert("rotation_quaternion", frame=f)
            else:
                deg = 0.25 * f / 48.0
                o.location = b * deg
                o.keyframe_insert("location", frame=f)
            values[(name, f)] = deg
        for fc in o.animation_data.action.fcurves:
            for kp in fc.keyframe_points:
                kp.interpolation = "LINEAR"
    return values


def joint_values(s, name):
    """The joints' values at every frame as Blender evaluates the empties."""
    with open("%s/%s.blender.csv" % (OUT, name), "w") as out:
        out.write("frame," + ",".join("%s.%s" % (n, "angle" if k == "revolute" else "position")
                                      for n, k, a in ARM_JOINTS) + "\n")
        prev = {}
        for f in range(s.frame_start, s.frame_end + 1):
            s.frame_set(f)
            vals = []
            for n, kind, a in ARM_JOINTS:
                o = s.objects[n]
                b = Vector((a[0], -a[2], a[1]))
                if kind == "revolute":
                    q = o.matrix_world.to_quaternion()
                    v = Vector((q.x, q.y, q.z))
                    deg = math.degrees(2 * math.atan2(v.dot(b), q.w))
                    if n in prev:  # continuous: the turn nearest the last frame's
                        deg = prev[n] + math.remainder(deg - prev[n], 360.0)
                    prev[n] = deg
                    vals.append(deg)
                else:
                    vals.append(o.matrix_world.translation.dot(b))
            out.write("%d," % f + ",".join("%.9g" % v for v in vals) + "\n")


def positions(s, name):
    rows = []
    cols = None
    for f in range(s.frame_start, s.frame_end + 1):
        s.frame_set(f)
        vals = []
        names = []
        for o in sorted(s.objects, key=lambda o: o.name):
            w = o.matrix_world.translation
            names.append(o.name)
            vals.append((w.x, w.z, -w.y))
            if o.type == "ARMATURE":
                for pb in o.pose.bones:
                    h = o.matrix_world @ pb.head
                    names.append(pb.name)
                    vals.append((h.x, h.z, -h.y))
        if cols is None:
            cols = names
        rows.append((f, vals))
    with open("%s/%s.blender.csv" % (OUT, name), "w") as out:
        out.write("frame," + ",".join("%s.%s" % (n, c) for n in cols for c in "xyz") + "\n")
        for f, vals in rows:
            out.write("%d," % f + ",".join("%.9g" % v for p in vals for v in p) + "\n")


def export(name, sampled, fmt):
    ext = "glb" if fmt == "GLB" else "gltf"
    path = "%s/%s.%s.%s" % (OUT, name, "sampled" if sampled else "keys", ext)
    bpy.ops.export_scene.gltf(filepath=path,
                              export_format=fmt, export_animations=True,
                              export_force_sampling=sampled, export_nla_strips=False,
                              export_optimize_animation_size=False, export_frame_range=True,
                              export_def_bones=False, export_apply=False, export_cameras=False,
                              export_lights=False)


for name, build in (("hierarchy", hierarchy), ("armature", armature)):
    s = reset()
    build(s)
    export(name, True, "GLB")
    export(name, False, "GLTF_EMBEDDED")
    positions(s, name)
s = reset()
robot(s)
s.frame_set(0)  # the nodes' rest transforms: the pose of every joint at 0
export("robot", True, "GLB")
joint_values(s, "robot")
print("blender_fixtures: written to", OUT)
