#!/usr/bin/env bash
# The glTF loader's cost for one large texture (issue 22, docs/gltf.md): wall time and peak
# memory (maximum resident set) of vsgl_render loading a quad whose base colour is an N^2 RGBA
# PNG of noise (compresses poorly, as photographs do), against the same quad with a 1^2 texture,
# median of RUNS runs each. The render itself is 64x36 without indirect light, so the difference
# is the loading. Usage: scripts/load_bench.sh [N (default 8192)] [RUNS (default 3)]; run after
# scripts/build.sh on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-8192}"
runs="${2:-3}"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT

# A quad facing +Z under a spot, textured by image.png; a PNG written with Python's zlib.
python3 - "$dir" "$size" <<'PY'
import json, os, random, struct, sys, zlib
out, n = sys.argv[1], int(sys.argv[2])
def png(path, n):
    rng = random.Random(1)
    with open(path, "wb") as f:
        def chunk(tag, body):
            f.write(struct.pack(">I", len(body)) + tag + body
                    + struct.pack(">I", zlib.crc32(tag + body) & 0xFFFFFFFF))
        f.write(b"\x89PNG\r\n\x1a\n")
        chunk(b"IHDR", struct.pack(">IIBBBBB", n, n, 8, 6, 0, 0, 0))
        z = zlib.compressobj(1)
        data = b""
        row = rng.randbytes(4 * n)
        for y in range(n):
            data += z.compress(b"\0" + row[(y * 4) % (4 * n):] + row[:(y * 4) % (4 * n)])
            if len(data) > 1 << 24:
                chunk(b"IDAT", data)
                data = b""
        chunk(b"IDAT", data + z.flush())
        chunk(b"IEND", b"")
def gltf(name, image):
    pos = struct.pack("<12f", -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0)
    uv = struct.pack("<8f", 0, 1, 1, 1, 1, 0, 0, 0)
    idx = struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    buf = pos + uv + idx
    import base64
    g = {"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
         "buffers": [{"byteLength": len(buf), "uri": "data:application/octet-stream;base64,"
                      + base64.b64encode(buf).decode()}],
         "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                         {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                         {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                        "min": [-1, -1, 0], "max": [1, 1, 0]},
                       {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                       {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
         "images": [{"uri": image}], "textures": [{"source": 0}],
         "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1},
                                     "indices": 2, "material": 0}]}],
         "extensions": {"KHR_lights_punctual": {"lights": [
             {"type": "spot", "intensity": 20, "spot": {"outerConeAngle": 0.7}}]}},
         "nodes": [{"mesh": 0}, {"extensions": {"KHR_lights_punctual": {"light": 0}},
                                 "translation": [0, 0, 3]}],
         "scenes": [{"nodes": [0, 1]}], "scene": 0}
    with open(os.path.join(out, name), "w") as f:
        json.dump(g, f)
png(os.path.join(out, "large.png"), n)
png(os.path.join(out, "small.png"), 1)
gltf("large.gltf", "large.png")
gltf("small.gltf", "small.png")
PY

# Median wall seconds and peak MB of vsgl_render on $1 over $runs runs.
measure() {
  local walls=() peaks=()
  for _ in $(seq "$runs"); do
    local t
    t="$( { /usr/bin/time -f '%e %M' ./build/samples/vsgl_render --scene "$1" --width 64 \
            --height 36 --frames 1 --no-indirect --out "$dir/out" >/dev/null; } 2>&1 | tail -1)"
    walls+=("${t% *}")
    peaks+=("${t#* }")
  done
  local wall peak
  wall="$(printf '%s\n' "${walls[@]}" | sort -g | sed -n "$(( (runs + 1) / 2 ))p")"
  peak="$(printf '%s\n' "${peaks[@]}" | sort -g | sed -n "$(( (runs + 1) / 2 ))p")"
  echo "$wall $((peak / 1024))"
}

read -r smallWall smallPeak <<<"$(measure "$dir/small.gltf")"
read -r largeWall largePeak <<<"$(measure "$dir/large.gltf")"
echo "| texture | PNG size | vsgl_render wall (s, median of $runs) | peak memory (MB) |"
echo "|---|---|---|---|"
echo "| 1^2 | $(stat -c %s "$dir/small.png") B | $smallWall | $smallPeak |"
echo "| ${size}^2 | $(( $(stat -c %s "$dir/large.png") / 1048576 )) MB | $largeWall | $largePeak |"
awk -v s="$size" -v w="$largeWall" -v w0="$smallWall" -v m="$largePeak" -v m0="$smallPeak" \
  'BEGIN { printf "loading the %d^2 texture: %.2f s and %d MB more\n", s, w - w0, m - m0 }'
