# SPDX-License-Identifier: MIT
"""A .glb is one self-contained file, as pipelines expect (glTF-Transform and gltfpack embed):
`tangent bake scene.gltf out.glb` and `-o -` carry the input's external images and buffers
inside the one BIN chunk, byte for byte; `--keep-external` keeps images as files beside the
output, as before; a .gltf output is what it always was. Outputs are checked with the Khronos
validator (tests/node, installed by scripts/test.sh)."""
import base64
import json
import pathlib
import shutil
import struct
import subprocess

from conftest import skip_or_fail
from test_outputs import PNG, glb_bytes, grid, snapshot, tangent, temporaries, write

SOURCE = pathlib.Path(__file__).resolve().parents[2]
DEMO = SOURCE / "data" / "demo"
NODE_DIR = SOURCE / "tests" / "node"
# A 2x2 baseline JPEG (IPython's tests/2x2.jpg, 331 bytes).
JPEG = base64.b64decode(
    "/9j/4AAQSkZJRgABAQAAAQABAAD/2wBDAAgGBgcGBQgHBwcJCQgKDBQNDAsLDBkSEw8UHRofHh0aHBwgJC4nICIsIxwcKDcpLDAxNDQ0Hyc5"
    "PTgyPC4zNDL/wAALCAACAAIBAREA/8QAHwAAAQUBAQEBAQEAAAAAAAAAAAECAwQFBgcICQoL/8QAtRAAAgEDAwIEAwUFBAQAAAF9AQIDAAQR"
    "BRIhMUEGE1FhByJxFDKBkaEII0KxwRVS0fAkM2JyggkKFhcYGRolJicoKSo0NTY3ODk6Q0RFRkdISUpTVFVWV1hZWmNkZWZnaGlqc3R1dnd4"
    "eXqDhIWGh4iJipKTlJWWl5iZmqKjpKWmp6ipqrKztLW2t7i5usLDxMXGx8jJytLT1NXW19jZ2uHi4+Tl5ufo6erx8vP09fb3+Pn6/9oACAEB"
    "AAA/ACv/2Q==")


def khronos_valid(*paths):
    """Runs the Khronos glTF validator on each file: 0 errors required."""
    if shutil.which("node") is None or not (NODE_DIR / "node_modules" / "gltf-validator").is_dir():
        skip_or_fail(f"gltf-validator is not installed in {NODE_DIR} (scripts/test.sh runs npm ci)")
    done = subprocess.run(["node", str(NODE_DIR / "validate.mjs"), *map(str, paths)], capture_output=True, timeout=300)
    assert done.returncode == 0, (done.stdout + done.stderr).decode(errors="replace")


def glb_parts(path):
    """(JSON document, BIN chunk) of a .glb."""
    data = pathlib.Path(path).read_bytes()
    magic, version, length = struct.unpack_from("<III", data, 0)
    assert (magic, version, length) == (0x46546C67, 2, len(data)), path
    json_length, kind = struct.unpack_from("<II", data, 12)
    assert kind == 0x4E4F534A
    doc = json.loads(data[20:20 + json_length])
    bin_chunk = b""
    if 20 + json_length < len(data):
        bin_length, kind = struct.unpack_from("<II", data, 20 + json_length)
        assert kind == 0x004E4942
        bin_chunk = data[28 + json_length:28 + json_length + bin_length]
    return doc, bin_chunk


def image_bytes(doc, bin_chunk, index):
    view = doc["bufferViews"][doc["images"][index]["bufferView"]]
    start = view.get("byteOffset", 0)
    return bin_chunk[start:start + view["byteLength"]]


def assert_self_contained(doc, bin_chunk):
    """No uri anywhere, one buffer that is the BIN chunk, every bufferView inside it and
    4-byte aligned."""
    assert len(doc["buffers"]) == 1, doc["buffers"]
    assert "uri" not in doc["buffers"][0]
    assert doc["buffers"][0]["byteLength"] <= len(bin_chunk)
    for image in doc.get("images", []):
        assert "uri" not in image and "bufferView" in image and "mimeType" in image, image
    for view in doc["bufferViews"]:
        assert view["buffer"] == 0 and view.get("byteOffset", 0) % 4 == 0, view
        assert view.get("byteOffset", 0) + view["byteLength"] <= doc["buffers"][0]["byteLength"], view


def scene_with_external_files(folder):
    """A grid whose vertex data is in mesh.bin, its indices in a data: URI buffer, a PNG normal
    map (mimeType declared) and a JPEG base colour (no mimeType) in tex/; returns its path."""
    doc, blob = grid(6)
    indices_at = doc["bufferViews"][3]["byteOffset"]
    vertices, indices = blob[:indices_at], blob[indices_at:]
    doc["bufferViews"][3] = {"buffer": 1, "byteLength": len(indices), "target": 34963}
    doc["buffers"] = [{"uri": "mesh.bin", "byteLength": len(vertices)},
                      {"uri": "data:application/octet-stream;base64," + base64.b64encode(indices).decode(),
                       "byteLength": len(indices)}]
    doc["samplers"] = [{"magFilter": 9729, "minFilter": 9987, "wrapS": 33648, "wrapT": 33071}]
    doc["textures"] = [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}]
    doc["images"] = [{"uri": "tex/n.png", "mimeType": "image/png", "name": "normal", "extras": {"author": "tests"}},
                     {"uri": "tex/base%20colour.jpg"}]
    doc["materials"][0]["pbrMetallicRoughness"] = {"baseColorTexture": {"index": 1}}
    doc["materials"][0]["extras"] = {"kept": True}
    write(folder / "mesh.bin", vertices)
    write(folder / "tex" / "n.png", PNG)
    write(folder / "tex" / "base colour.jpg", JPEG)
    return write(folder / "scene.gltf", json.dumps(doc, indent=1).encode())


def test_a_glb_embeds_external_images_and_buffers_byte_for_byte(tmp_path):
    asset = scene_with_external_files(tmp_path / "in")
    before = snapshot(tmp_path / "in")
    done = tangent("bake", asset, tmp_path / "out" / "scene.glb")
    assert done.returncode == 0, done.stderr
    assert snapshot(tmp_path / "out").keys() == {"scene.glb"}  # nothing beside it
    assert temporaries(tmp_path) == []
    assert snapshot(tmp_path / "in") == before
    khronos_valid(tmp_path / "out" / "scene.glb")
    doc, bin_chunk = glb_parts(tmp_path / "out" / "scene.glb")
    assert_self_contained(doc, bin_chunk)
    assert image_bytes(doc, bin_chunk, 0) == PNG and image_bytes(doc, bin_chunk, 1) == JPEG
    assert doc["images"][0] == {"mimeType": "image/png", "name": "normal", "extras": {"author": "tests"}, "bufferView":
                                doc["images"][0]["bufferView"]}
    assert doc["images"][1]["mimeType"] == "image/jpeg"  # from its bytes: it declared none
    # What bake did not change is kept: samplers, textures, material extras.
    assert doc["samplers"] == [{"magFilter": 9729, "minFilter": 9987, "wrapS": 33648, "wrapT": 33071}]
    assert doc["textures"] == [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}]
    assert doc["materials"][0]["extras"] == {"kept": True}
    assert any("TANGENT" in p["attributes"] for m in doc["meshes"] for p in m["primitives"])
    assert tangent("check", tmp_path / "out" / "scene.glb").returncode == 0
    # The same self-contained file with the output moved anywhere: nothing refers outside it.
    moved = tmp_path / "elsewhere" / "moved.glb"
    moved.parent.mkdir()
    shutil.move(tmp_path / "out" / "scene.glb", moved)
    assert tangent("info", moved).returncode == 0


def test_dash_o_streams_the_demo_as_one_glb(tmp_path):
    streamed = tangent("bake", DEMO / "demo.gltf", "-o", "-")
    assert streamed.returncode == 0, streamed.stderr
    assert streamed.stdout[:4] == b"glTF"
    out = write(tmp_path / "streamed.glb", streamed.stdout)
    khronos_valid(out)
    doc, bin_chunk = glb_parts(out)
    assert_self_contained(doc, bin_chunk)
    source = json.loads((DEMO / "demo.gltf").read_bytes())
    for index, image in enumerate(source["images"]):
        assert image_bytes(doc, bin_chunk, index) == (DEMO / image["uri"]).read_bytes(), image
    # Byte for byte what -o FILE writes.
    assert tangent("bake", DEMO / "demo.gltf", "-o", tmp_path / "file.glb", "--quiet").returncode == 0
    assert (tmp_path / "file.glb").read_bytes() == streamed.stdout
    assert temporaries(tmp_path) == []


def test_keep_external_copies_images_beside_the_glb_as_before(tmp_path):
    asset = scene_with_external_files(tmp_path / "in")
    done = tangent("bake", asset, "-o", tmp_path / "out" / "scene.glb", "--keep-external")
    assert done.returncode == 0, done.stderr
    assert snapshot(tmp_path / "out").keys() == {"scene.glb", "tex/n.png", "tex/base colour.jpg"}
    assert (tmp_path / "out" / "tex" / "n.png").read_bytes() == PNG
    assert (tmp_path / "out" / "tex" / "base colour.jpg").read_bytes() == JPEG
    khronos_valid(tmp_path / "out" / "scene.glb")
    doc, _ = glb_parts(tmp_path / "out" / "scene.glb")
    assert [image.get("uri") for image in doc["images"]] == ["tex/n.png", "tex/base%20colour.jpg"]
    assert all("bufferView" not in image for image in doc["images"])
    assert len(doc["buffers"]) == 1 and "uri" not in doc["buffers"][0]  # buffers are always embedded
    # A stream cannot carry the copies: refused, nothing on standard output.
    streamed = tangent("bake", asset, "-o", "-", "--keep-external")
    assert streamed.returncode == 1 and streamed.stdout == b""
    assert b"refers to external files" in streamed.stderr, streamed.stderr


def test_a_gltf_output_keeps_its_images_external_whatever_the_option(tmp_path):
    asset = scene_with_external_files(tmp_path / "in")
    for name, extra in (("plain", []), ("kept", ["--keep-external"])):
        done = tangent("bake", asset, "-o", tmp_path / name / "scene.gltf", *extra)
        assert done.returncode == 0, done.stderr
        assert snapshot(tmp_path / name).keys() == {"scene.gltf", "scene.bin", "tex/n.png", "tex/base colour.jpg"}
        doc = json.loads((tmp_path / name / "scene.gltf").read_bytes())
        assert [image.get("uri") for image in doc["images"]] == ["tex/n.png", "tex/base%20colour.jpg"]
        assert "mimeType" not in doc["images"][1]
    assert snapshot(tmp_path / "plain") == snapshot(tmp_path / "kept")
    khronos_valid(tmp_path / "plain" / "scene.gltf")


def test_image_types_come_from_the_declared_mime_type_else_the_bytes(tmp_path):
    doc, blob = grid(4)
    webp = b"RIFF\x1a\0\0\0WEBPVP8L" + bytes(14)
    ktx2 = b"\xabKTX 20\xbb\r\n\x1a\n" + bytes(20)
    doc["images"] = [{"uri": "a.webp"}, {"uri": "b.ktx2"}, {"uri": "c.bin", "mimeType": "image/png"},
                     {"uri": "data:image/png;base64," + base64.b64encode(PNG).decode()}]
    doc["textures"] = [{"source": i} for i in range(4)]
    write(tmp_path / "in" / "a.webp", webp)
    write(tmp_path / "in" / "b.ktx2", ktx2)
    write(tmp_path / "in" / "c.bin", b"declared, so taken as it is")
    asset = write(tmp_path / "in" / "in.gltf", json.dumps({**doc, "buffers": [{"uri": "in.bin", "byteLength": len(blob)}]}).encode())
    write(tmp_path / "in" / "in.bin", blob)
    done = tangent("bake", asset, "-o", tmp_path / "out.glb")
    assert done.returncode == 0, done.stderr
    out, bin_chunk = glb_parts(tmp_path / "out.glb")
    assert_self_contained(out, bin_chunk)
    assert [image["mimeType"] for image in out["images"]] == ["image/webp", "image/ktx2", "image/png", "image/png"]
    expected = [webp, ktx2, b"declared, so taken as it is", PNG]
    assert [image_bytes(out, bin_chunk, i) for i in range(4)] == expected


def test_an_image_of_no_known_type_and_no_mime_type_is_refused_naming_it(tmp_path):
    doc, blob = grid(4)
    doc["images"] = [{"uri": "n.png", "mimeType": "image/png"}, {"uri": "unknown.dat"}]
    doc["textures"] = [{"source": 0}, {"source": 1}]
    write(tmp_path / "in" / "n.png", PNG)
    write(tmp_path / "in" / "unknown.dat", b"not an image anyone knows")
    write(tmp_path / "in" / "in.bin", blob)
    asset = write(tmp_path / "in" / "in.gltf", json.dumps({**doc, "buffers": [{"uri": "in.bin", "byteLength": len(blob)}]}).encode())
    (tmp_path / "out").mkdir()
    done = tangent("bake", asset, "-o", tmp_path / "out" / "o.glb")
    assert done.returncode == 1, done.stderr
    assert f"{asset}: /images/1: has no mimeType".encode() in done.stderr, done.stderr
    assert snapshot(tmp_path / "out") == {} and temporaries(tmp_path) == []
    # Kept external it is only copied, as before.
    done = tangent("bake", asset, "-o", tmp_path / "out" / "o.glb", "--keep-external")
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "out" / "unknown.dat").read_bytes() == b"not an image anyone knows"


def test_images_are_read_only_where_the_loader_allows(tmp_path):
    # An image one folder up: refused as loading refuses it, embedded with --asset-root.
    doc, blob = grid(4)
    doc["images"] = [{"uri": "../n.png"}]
    write(tmp_path / "n.png", PNG)
    write(tmp_path / "scene" / "in.bin", blob)
    asset = write(tmp_path / "scene" / "in.gltf",
                  json.dumps({**doc, "buffers": [{"uri": "in.bin", "byteLength": len(blob)}]}).encode())
    done = tangent("bake", asset, "-o", tmp_path / "out" / "o.glb")
    assert done.returncode == 1 and b"asset root" in done.stderr, done.stderr
    assert not (tmp_path / "out" / "o.glb").exists()
    done = tangent("bake", asset, "-o", tmp_path / "out" / "o.glb", "--asset-root", tmp_path)
    assert done.returncode == 0, done.stderr
    out, bin_chunk = glb_parts(tmp_path / "out" / "o.glb")
    assert_self_contained(out, bin_chunk)
    assert image_bytes(out, bin_chunk, 0) == PNG
    assert snapshot(tmp_path / "out").keys() == {"o.glb"}


def test_a_tree_is_baked_again_when_keep_external_changes(tmp_path):
    # The option changes a .glb output, so the manifest records it: a re-run with it bakes again.
    tree, out = tmp_path / "tree", tmp_path / "out"
    doc, blob = grid(4)  # its image: a data: URI
    uri = doc["images"][0]["uri"]
    write(tree / "a.glb", glb_bytes(doc, blob))
    assert tangent("bake", tree, "--recursive", "--out-dir", out).returncode == 0
    embedded, bin_chunk = glb_parts(out / "a.glb")
    assert_self_contained(embedded, bin_chunk)
    assert image_bytes(embedded, bin_chunk, 0) == PNG
    again = tangent("bake", tree, "--recursive", "--out-dir", out)
    assert again.stdout.decode().splitlines()[0].endswith(": unchanged"), again.stdout
    done = tangent("bake", tree, "--recursive", "--out-dir", out, "--keep-external")
    assert done.returncode == 0, done.stderr
    assert done.stdout.decode().splitlines()[0].endswith(": baked"), done.stdout
    assert glb_parts(out / "a.glb")[0]["images"] == [{"uri": uri, "mimeType": "image/png"}]
