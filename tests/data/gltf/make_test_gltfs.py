#!/usr/bin/env python3
"""Regenerates the small glTF files used by tests/unit/test_gltf_loader.cpp.

The JSON is written out by hand below; only the binary buffers (base64 data URIs) and the 2x2
PNG need a program, and the Draco bitstream Debian's draco_encoder (package draco), which this
script runs when it is installed. Run from anywhere: python3 tests/data/gltf/make_test_gltfs.py
"""
import base64
import json
import math
import os
import shutil
import struct
import subprocess
import tempfile
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

FLOAT, U8, U16, U32 = 5126, 5121, 5123, 5125


class Buffer:
    """One buffer with one bufferView per accessor."""

    def __init__(self):
        self.data = b""
        self.views = []
        self.accessors = []

    def add(self, fmt, values, component, kind, count, normalized=False, minmax=None):
        while len(self.data) % 4:
            self.data += b"\0"
        raw = struct.pack("<" + fmt * len(values), *values)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(raw)})
        self.data += raw
        accessor = {"bufferView": len(self.views) - 1, "componentType": component,
                    "count": count, "type": kind}
        if normalized:
            accessor["normalized"] = True
        if minmax:
            accessor["min"], accessor["max"] = minmax
        self.accessors.append(accessor)
        return len(self.accessors) - 1

    def positions(self, points):
        flat = [c for p in points for c in p]
        lo = [min(p[i] for p in points) for i in range(3)]
        hi = [max(p[i] for p in points) for i in range(3)]
        return self.add("f", flat, FLOAT, "VEC3", len(points), minmax=(lo, hi))

    def vec3(self, vectors):
        return self.add("f", [c for v in vectors for c in v], FLOAT, "VEC3", len(vectors))

    def vec2(self, vectors):
        return self.add("f", [c for v in vectors for c in v], FLOAT, "VEC2", len(vectors))

    def indices(self, values, component=U16):
        fmt = {U8: "B", U16: "H", U32: "I"}[component]
        return self.add(fmt, values, component, "SCALAR", len(values))

    def write_into(self, gltf):
        gltf["buffers"] = [{"byteLength": len(self.data),
                            "uri": "data:application/octet-stream;base64,"
                                   + base64.b64encode(self.data).decode()}]
        gltf["bufferViews"] = self.views
        gltf["accessors"] = self.accessors


def lights_extension(lights):
    return {"KHR_lights_punctual": {"lights": lights}}


def light_node(index, **transform):
    node = {"extensions": {"KHR_lights_punctual": {"light": index}}}
    node.update(transform)
    return node


POINT_LIGHT = {"type": "point", "name": "bulb", "intensity": 5.0}
TRIANGLE = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]  # CCW seen from +Z


def base_gltf():
    return {"asset": {"version": "2.0", "generator": "make_test_gltfs.py"},
            "extensionsUsed": ["KHR_lights_punctual"]}


def save(name, gltf):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


def triangle_mesh(buffer, with_normals=True, mode=None, material=None):
    attributes = {"POSITION": buffer.positions(TRIANGLE)}
    if with_normals:
        attributes["NORMAL"] = buffer.vec3([(0.0, 0.0, 1.0)] * 3)
    primitive = {"attributes": attributes}
    if mode is not None:
        primitive["mode"] = mode
    if material is not None:
        primitive["material"] = material
    return {"name": "triangle", "primitives": [primitive]}


def triangle_spot():
    """Non-indexed triangle, a material, a spot light and a perspective camera."""
    b = Buffer()
    mesh = triangle_mesh(b, material=0)
    mesh["primitives"][0]["attributes"]["TEXCOORD_0"] = b.vec2([(0, 0), (1, 0), (0, 1)])
    g = base_gltf()
    g["materials"] = [{"name": "paint", "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1.0],
                                                "metallicFactor": 0.25,
                                                "roughnessFactor": 0.4}}]
    g["meshes"] = [mesh]
    g["cameras"] = [{"name": "cam", "type": "perspective",
                     "perspective": {"yfov": 0.7, "znear": 0.1, "aspectRatio": 1.5}}]
    g["extensions"] = lights_extension(
        [{"type": "spot", "name": "spot", "color": [1.0, 0.9, 0.8], "intensity": 20.0,
          "range": 10.0, "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.5}}])
    g["nodes"] = [{"mesh": 0}, light_node(0, translation=[0.0, 0.0, 2.0]),
                  {"camera": 0, "translation": [0.0, 0.0, 5.0]}]
    g["scenes"] = [{"nodes": [0, 1, 2]}]
    g["scene"] = 0
    b.write_into(g)
    save("triangle_spot.gltf", g)


def hierarchy():
    """Parent with TRS (translate (1,2,3), 90 deg about +Y, scale 2), children: the triangle
    (translated by (1,0,0)), a light (default -Z direction) and an orthographic camera. No
    'scenes': every root node is drawn. Node 4 is a root too, with a matrix transform."""
    b = Buffer()
    g = base_gltf()
    g["meshes"] = [triangle_mesh(b)]
    g["cameras"] = [{"type": "orthographic",
                     "orthographic": {"xmag": 2.0, "ymag": 1.5, "znear": 0.5, "zfar": 50.0}}]
    g["extensions"] = lights_extension([POINT_LIGHT])
    s = math.sqrt(0.5)
    g["nodes"] = [
        {"name": "parent", "translation": [1.0, 2.0, 3.0], "rotation": [0.0, s, 0.0, s],
         "scale": [2.0, 2.0, 2.0], "children": [1, 2, 3]},
        {"name": "child", "translation": [1.0, 0.0, 0.0], "mesh": 0},
        light_node(0, name="lamp"),
        {"name": "ortho", "camera": 0},
        # Column-major translation by (0, 0, -10): a second instance of the triangle.
        {"name": "by matrix", "mesh": 0,
         "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -10, 1]},
    ]
    b.write_into(g)
    save("hierarchy.gltf", g)


def no_normals():
    """Indexed (u16) tent without normals: two faces of different areas meet at a ridge whose
    vertices are duplicated (same positions, separate vertices)."""
    b = Buffer()
    # Face A: x from -2 to 0, rises to the ridge at x = 0, y = 1. Face B: x from 0 to 1.
    points = [(-2.0, 0.0, 0.0), (-2.0, 0.0, -1.0), (0.0, 1.0, 0.0), (0.0, 1.0, -1.0),  # A
              (0.0, 1.0, 0.0), (0.0, 1.0, -1.0), (1.0, 0.0, 0.0), (1.0, 0.0, -1.0)]  # B
    indices = [0, 2, 1, 1, 2, 3, 4, 6, 5, 5, 6, 7]
    g = base_gltf()
    g["meshes"] = [{"name": "tent", "primitives": [
        {"attributes": {"POSITION": b.positions(points)}, "indices": b.indices(indices, U16)}]}]
    g["extensions"] = lights_extension([POINT_LIGHT])
    g["nodes"] = [{"mesh": 0}, light_node(0, translation=[0.0, 3.0, 0.0])]
    g["scenes"] = [{"nodes": [0, 1]}]
    b.write_into(g)
    save("no_normals.gltf", g)


def strip_fan():
    """A u8-indexed triangle strip and a non-indexed fan, both a unit square facing +Z."""
    b = Buffer()
    square = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)]
    fan = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)]
    g = base_gltf()
    g["meshes"] = [{"name": "strips", "primitives": [
        {"attributes": {"POSITION": b.positions(square)}, "indices": b.indices([0, 1, 2, 3], U8),
         "mode": 5},
        {"attributes": {"POSITION": b.positions(fan)}, "mode": 6}]}]
    g["extensions"] = lights_extension([POINT_LIGHT])
    g["nodes"] = [{"mesh": 0}, light_node(0, translation=[0.0, 0.0, 3.0])]
    b.write_into(g)
    save("strip_fan.gltf", g)


def mirrored():
    """The +Z-facing triangle under scale (-1, 1, 1)."""
    b = Buffer()
    g = base_gltf()
    g["meshes"] = [triangle_mesh(b)]
    g["extensions"] = lights_extension([POINT_LIGHT])
    g["nodes"] = [{"mesh": 0, "scale": [-1.0, 1.0, 1.0]}, light_node(0, translation=[0, 0, 3.0])]
    g["scenes"] = [{"nodes": [0, 1]}]
    b.write_into(g)
    save("mirrored.gltf", g)


def png_rgba(rows):
    """An RGBA PNG from rows (top to bottom) of (r, g, b, a) byte tuples."""
    raw = b"".join(b"\0" + bytes(c for texel in row for c in texel) for row in rows)

    def chunk(tag, body):
        return (struct.pack(">I", len(body)) + tag + body
                + struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF))

    header = struct.pack(">IIBBBBB", len(rows[0]), len(rows), 8, 6, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw))
            + chunk(b"IEND", b""))


def png_2x2():
    """RGBA 2x2: red, green / blue, white (rows top to bottom), all opaque."""
    return png_rgba([[(255, 0, 0, 255), (0, 255, 0, 255)], [(0, 0, 255, 255), (255, 255, 255, 255)]])


def textured():
    """Triangle with normalized-u16 UVs; base colour and metallic-roughness textures that go
    through two glTF textures to images 1 and 0 (checks the texture -> image mapping)."""
    with open(os.path.join(HERE, "checker2x2.png"), "wb") as f:
        f.write(png_2x2())
    b = Buffer()
    mesh = triangle_mesh(b, material=0)
    mesh["primitives"][0]["attributes"]["TEXCOORD_0"] = b.add(
        "H", [0, 0, 65535, 0, 0, 65535], U16, "VEC2", 3, normalized=True)
    g = base_gltf()
    g["images"] = [{"uri": "checker2x2.png"},
                   {"uri": "data:image/png;base64," + base64.b64encode(png_2x2()).decode()}]
    g["samplers"] = [{"wrapS": 33071}]
    g["textures"] = [{"source": 1, "sampler": 0}, {"source": 0}]
    g["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                "metallicRoughnessTexture": {"index": 1}}}]
    g["meshes"] = [mesh]
    g["extensions"] = lights_extension([POINT_LIGHT])
    g["nodes"] = [{"mesh": 0}, light_node(0, translation=[0, 0, 3.0])]
    b.write_into(g)
    save("textured.gltf", g)


def quad(buffer, half, height, uv_scale=1.0):
    """A square of side 2 half in the plane y = height facing +Y, texture coordinates 0..uv_scale
    across it (v down the image: along +z)."""
    points = [(-half, height, -half), (half, height, -half), (half, height, half),
              (-half, height, half)]
    uvs = [(0.0, 0.0), (uv_scale, 0.0), (uv_scale, uv_scale), (0.0, uv_scale)]
    return {"attributes": {"POSITION": buffer.positions(points),
                           "NORMAL": buffer.vec3([(0.0, 1.0, 0.0)] * 4),
                           "TEXCOORD_0": buffer.vec2(uvs)},
            "indices": buffer.indices([0, 2, 1, 0, 3, 2], U16)}


def alpha_mask():
    """A green 6 x 6 m floor (y = 0) under a 4 x 4 m screen (y = 1) of alphaMode MASK whose base
    colour texture is a 4 x 4 checker of opaque and fully transparent 1 m cells, lit by a spot
    2 m above the screen pointing down, seen by a camera from the side: the light reaches the
    floor through the holes only, in the RSM as in the direct light."""
    b = Buffer()
    opaque, hole = (230, 230, 230, 255), (230, 230, 230, 0)
    checker = [[opaque if (x + y) % 2 == 0 else hole for x in range(4)] for y in range(4)]
    g = base_gltf()
    g["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png_rgba(checker)).decode()}]
    g["textures"] = [{"source": 0}]
    g["materials"] = [
        {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.7, 0.1, 1.0],
                                                   "metallicFactor": 0.0}},
        {"name": "screen", "doubleSided": True, "alphaMode": "MASK", "alphaCutoff": 0.5,
         "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}]
    floor = quad(b, 3.0, 0.0)
    floor["material"] = 0
    screen = quad(b, 2.0, 1.0)
    screen["material"] = 1
    g["meshes"] = [{"name": "floor", "primitives": [floor]},
                   {"name": "screen", "primitives": [screen]}]
    g["cameras"] = [{"name": "side", "type": "perspective",
                     "perspective": {"yfov": 0.9, "znear": 0.1}}]
    s = math.sqrt(0.5)
    g["extensions"] = lights_extension(
        [{"type": "spot", "name": "spot", "intensity": 60.0,
          "spot": {"innerConeAngle": 0.4, "outerConeAngle": 0.5}}])
    # The light turned -90 degrees about +X (its -Z to -Y); the camera 20 degrees down.
    down = math.radians(-20.0) / 2
    g["nodes"] = [{"mesh": 0}, {"mesh": 1},
                  light_node(0, translation=[0.0, 3.0, 0.0], rotation=[-s, 0.0, 0.0, s]),
                  {"camera": 0, "translation": [0.0, 2.2, 5.5],
                   "rotation": [math.sin(down), 0.0, 0.0, math.cos(down)]}]
    g["scenes"] = [{"nodes": [0, 1, 2, 3]}]
    g["scene"] = 0
    b.write_into(g)
    save("alpha_mask.gltf", g)


def bad_files():
    def simple(name, mutate):
        b = Buffer()
        g = base_gltf()
        g["meshes"] = [triangle_mesh(b)]
        g["extensions"] = lights_extension([dict(POINT_LIGHT)])
        g["nodes"] = [{"mesh": 0}, light_node(0, translation=[0, 0, 3.0])]
        b.write_into(g)
        mutate(g, b)
        save(name, g)

    def points(g, b):
        g["meshes"][0]["primitives"][0]["mode"] = 0

    def no_lights(g, b):
        del g["extensions"]
        del g["extensionsUsed"]
        g["nodes"] = g["nodes"][:1]

    def bad_spot(g, b):
        g["extensions"] = lights_extension(
            [{"type": "spot", "name": "badspot",
              "spot": {"innerConeAngle": 0.6, "outerConeAngle": 0.5}}])

    def index_out_of_range(g, b):
        g["meshes"][0]["primitives"][0]["indices"] = b.indices([0, 1, 5], U16)
        b.write_into(g)

    def short_buffer(g, b):
        g["accessors"][0]["count"] = 6  # the view holds 3 VEC3 floats (36 bytes)
        g["accessors"][1]["count"] = 6

    def missing_texture(g, b):
        g["images"] = [{"uri": "does_not_exist.png"}]
        g["textures"] = [{"source": 0}]
        g["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        g["meshes"][0]["primitives"][0]["material"] = 0

    def missing_buffer(g, b):
        g["buffers"][0]["uri"] = "does_not_exist.bin"

    simple("bad_points.gltf", points)
    simple("no_lights.gltf", no_lights)
    simple("bad_spot_cone.gltf", bad_spot)
    simple("bad_index_out_of_range.gltf", index_out_of_range)
    simple("bad_short_buffer.gltf", short_buffer)
    simple("bad_missing_texture.gltf", missing_texture)
    simple("bad_missing_buffer.gltf", missing_buffer)


# KHR_draco_mesh_compression: a 5 x 5 grid on a tilted plane, 32 triangles, one normal and a UV
# per vertex, compressed losslessly (no quantization) by draco_encoder into draco_grid.drc. Its
# accessors carry no bufferView; the extension names the bitstream's attribute ids, which
# draco_encoder gives in the order of the OBJ's elements: positions 0, texture coordinates 1,
# normals 2.
DRACO_GRID_NORMAL = (0.0, 2.0 / math.sqrt(5.0), 1.0 / math.sqrt(5.0))


def draco_grid():
    if shutil.which("draco_encoder") is None:
        print("draco_encoder not found (apt-get install draco): draco_grid.drc kept as it is")
    else:
        lines = [f"v {x * 0.25:g} {-0.125 * y:g} {0.25 * y:g}" for y in range(5) for x in range(5)]
        lines += [f"vt {x / 4:g} {y / 4:g}" for y in range(5) for x in range(5)]
        lines.append("vn %.9f %.9f %.9f" % DRACO_GRID_NORMAL)
        for y in range(4):
            for x in range(4):
                i = y * 5 + x + 1
                for a, b, c in ((i, i + 5, i + 1), (i + 1, i + 5, i + 6)):
                    lines.append(f"f {a}/{a}/1 {b}/{b}/1 {c}/{c}/1")
        with tempfile.TemporaryDirectory() as tmp:
            obj = os.path.join(tmp, "grid.obj")
            with open(obj, "w") as f:
                f.write("\n".join(lines) + "\n")
            subprocess.run(["draco_encoder", "-i", obj, "-o", os.path.join(HERE, "draco_grid.drc"),
                            "-qp", "0", "-qt", "0", "-qn", "0", "-cl", "7"],
                           check=True, stdout=subprocess.DEVNULL)
    size = os.path.getsize(os.path.join(HERE, "draco_grid.drc"))
    gltf = {"asset": {"version": "2.0", "generator": "make_test_gltfs.py"},
            "extensionsUsed": ["KHR_draco_mesh_compression"],
            "extensionsRequired": ["KHR_draco_mesh_compression"],
            "buffers": [{"uri": "draco_grid.drc", "byteLength": size}],
            "bufferViews": [{"buffer": 0, "byteLength": size}],
            "accessors": [
                {"componentType": U32, "count": 96, "type": "SCALAR"},
                {"componentType": FLOAT, "count": 25, "type": "VEC3",
                 "min": [0.0, -0.5, 0.0], "max": [1.0, 0.0, 1.0]},
                {"componentType": FLOAT, "count": 25, "type": "VEC3"},
                {"componentType": FLOAT, "count": 25, "type": "VEC2"}],
            "meshes": [{"name": "grid", "primitives": [{
                "attributes": {"POSITION": 1, "NORMAL": 2, "TEXCOORD_0": 3}, "indices": 0,
                "extensions": {"KHR_draco_mesh_compression": {
                    "bufferView": 0,
                    "attributes": {"POSITION": 0, "TEXCOORD_0": 1, "NORMAL": 2}}}}]}],
            "nodes": [{"mesh": 0}],
            "scenes": [{"nodes": [0]}],
            "scene": 0}
    save("draco_grid.gltf", gltf)


if __name__ == "__main__":
    triangle_spot()
    hierarchy()
    no_normals()
    strip_fan()
    mirrored()
    textured()
    alpha_mask()
    bad_files()
    draco_grid()
