# SPDX-License-Identifier: MIT
"""Every material feature that reads the tangent frame makes a primitive need TANGENT (issue
64's "consumers of the frame"): the normal texture, KHR_materials_clearcoat's
clearcoatNormalTexture, KHR_materials_anisotropy (a non-zero strength or a texture). bake bakes
them (the Khronos validator reports MESH_PRIMITIVE_NO_TANGENT_SPACE otherwise), from the UV set
and KHR_texture_transform of the first (normal, clearcoat normal, anisotropy); where another
consumer samples another UV set, bake and check warn; info lists every consumer."""
import json
import math
import struct

from test_glb_embed import glb_parts, khronos_valid
from test_outputs import glb_bytes, grid, tangent, write

ROTATION = {"KHR_texture_transform": {"rotation": 0.7, "scale": [2.0, 1.0]}}


def asset(tmp_path, material, name="in.glb", second_uv=False):
    """The reliability grid with `material` (its normalTexture replaced) and, with second_uv, a
    TEXCOORD_1 that is TEXCOORD_0 turned by a quarter (so its frames differ)."""
    doc, blob = grid(5)
    doc["materials"] = [material]
    used = set()
    for key in material.get("extensions", {}):
        used.add(key)
    for info in [material.get("normalTexture")] + [e.get(k) for e in material.get("extensions", {}).values()
                                                    for k in ("clearcoatNormalTexture", "anisotropyTexture")]:
        if info and "KHR_texture_transform" in info.get("extensions", {}):
            used.add("KHR_texture_transform")
    if used:
        doc["extensionsUsed"] = sorted(used)
    if second_uv:
        count = doc["accessors"][2]["count"]
        uvs = struct.unpack_from(f"<{2 * count}f", blob, doc["bufferViews"][2]["byteOffset"])
        turned = [value for k in range(count) for value in (uvs[2 * k + 1], 1 - uvs[2 * k])]
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": 8 * count})
        doc["accessors"].append({"bufferView": len(doc["bufferViews"]) - 1, "componentType": 5126, "count": count, "type": "VEC2"})
        doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = len(doc["accessors"]) - 1
        blob += struct.pack(f"<{2 * count}f", *turned)
        doc["buffers"][0]["byteLength"] = len(blob)
    return write(tmp_path / name, glb_bytes(doc, blob))


def bake(path, out, *args):
    done = tangent("bake", path, "-o", out, "--report", out.with_suffix(".json"), *args)
    assert done.returncode == 0, done.stderr
    return json.loads(out.with_suffix(".json").read_text())[0]["primitives"][0], done


def start_of(doc, accessor):
    """Where a tightly packed accessor's data starts in the BIN chunk."""
    return doc["bufferViews"][accessor["bufferView"]].get("byteOffset", 0) + accessor.get("byteOffset", 0)


def tangents_of(path):
    doc, chunk = glb_parts(path)
    accessor = doc["accessors"][doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"]]
    start = start_of(doc, accessor)
    return chunk[start:start + 16 * accessor["count"]]


def test_clearcoat_normal_texture_alone_is_baked_and_validates(tmp_path):
    source = asset(tmp_path, {"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1,
                                                                           "clearcoatNormalTexture": {"index": 0}}}})
    primitive, _ = bake(source, tmp_path / "out.glb")
    assert primitive["action"] == "baked" and "clearcoatNormalTexture on TEXCOORD_0" in primitive["reason"], primitive
    khronos_valid(tmp_path / "out.glb")
    # The same frames as the same mesh with a normal texture: the consumer changes nothing else.
    plain = asset(tmp_path, {"normalTexture": {"index": 0}}, name="plain.glb")
    bake(plain, tmp_path / "plain-out.glb")
    assert tangents_of(tmp_path / "out.glb") == tangents_of(tmp_path / "plain-out.glb")


def test_clearcoat_texture_transform_turns_the_frame_as_on_a_normal_texture(tmp_path):
    clearcoat = asset(tmp_path, {"extensions": {"KHR_materials_clearcoat": {
        "clearcoatFactor": 1, "clearcoatNormalTexture": {"index": 0, "extensions": ROTATION}}}})
    normal = asset(tmp_path, {"normalTexture": {"index": 0, "extensions": ROTATION}}, name="normal.glb")
    untransformed = asset(tmp_path, {"normalTexture": {"index": 0}}, name="untransformed.glb")
    for path in (clearcoat, normal, untransformed):
        bake(path, path.with_name(path.stem + "-out.glb"))
    turned = tangents_of(tmp_path / "in-out.glb")
    assert turned == tangents_of(tmp_path / "normal-out.glb")
    assert turned != tangents_of(tmp_path / "untransformed-out.glb")


def test_anisotropy_needs_tangents_with_strength_or_texture(tmp_path):
    strong = asset(tmp_path, {"extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.6}}})
    primitive, _ = bake(strong, tmp_path / "strong.glb")
    assert primitive["action"] == "baked" and "anisotropy" in primitive["reason"], primitive
    khronos_valid(tmp_path / "strong.glb")
    textured = asset(tmp_path, {"extensions": {"KHR_materials_anisotropy": {"anisotropyTexture": {"index": 0}}}}, name="t.glb")
    assert bake(textured, tmp_path / "textured.glb")[0]["action"] == "baked"
    off = asset(tmp_path, {"extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0}}}, name="off-in.glb")
    primitive, _ = bake(off, tmp_path / "off.glb")
    assert primitive["action"] == "skipped", primitive


def test_consumers_on_other_uv_sets_warn_in_bake_and_check_and_info_lists_them(tmp_path):
    material = {"normalTexture": {"index": 0},
                "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1, "clearcoatNormalTexture": {"index": 0, "texCoord": 1}},
                               "KHR_materials_anisotropy": {"anisotropyStrength": 0.5}}}
    source = asset(tmp_path, material, second_uv=True)
    primitive, done = bake(source, tmp_path / "out.glb")
    assert primitive["action"] == "baked" and primitive["texCoord"] == 0, primitive
    warning = "clearcoatNormalTexture samples TEXCOORD_1, but TANGENT follows the normalTexture (TEXCOORD_0)"
    assert warning in done.stderr.decode(), done.stderr
    checked = tangent("check", tmp_path / "out.glb", "--format", "json")
    assert checked.returncode == 0, checked.stdout
    [entry] = json.loads(checked.stdout)["files"][0]["primitives"]
    assert any(warning in w for w in entry["warnings"]), entry
    text = tangent("info", source)
    assert b"tangent frame read by: normalTexture (TEXCOORD_0) clearcoatNormalTexture (TEXCOORD_1) anisotropy (TEXCOORD_0)" in text.stdout
    info = tangent("info", source, "--json")
    assert info.returncode == 0, info.stderr
    described = json.loads(info.stdout)["meshes"][0]["primitives"][0]
    assert [(c["consumer"], c["texCoord"]) for c in described["frameConsumers"]] == [
        ("normalTexture", 0), ("clearcoatNormalTexture", 1), ("anisotropy", 0)]
    assert warning in described["frameWarning"]


def test_anisotropy_without_texture_or_uvs_is_left_alone(tmp_path):
    doc, blob = grid(4)
    del doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"]
    doc["materials"] = [{"extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 1}}}]
    doc["extensionsUsed"] = ["KHR_materials_anisotropy"]
    source = write(tmp_path / "in.glb", glb_bytes(doc, blob))
    primitive, _ = bake(source, tmp_path / "out.glb")
    assert primitive["action"] == "skipped" and "no TEXCOORD_0" in primitive["reason"], primitive


def test_a_malformed_clearcoat_texture_is_named(tmp_path):
    source = asset(tmp_path, {"extensions": {"KHR_materials_clearcoat": {"clearcoatNormalTexture": {"index": 0, "texCoord": "1"}}}})
    done = tangent("bake", source, "-o", tmp_path / "out.glb")
    assert done.returncode == 1
    assert b"/materials/0/extensions/KHR_materials_clearcoat/clearcoatNormalTexture/texCoord" in done.stderr, done.stderr
    assert not (tmp_path / "out.glb").exists()


def edited_tangents(source, out, edit):
    """The .glb `source` with each TANGENT (x, y, z, w) replaced by edit(tangent, normal)."""
    doc, chunk = glb_parts(source)
    attributes = doc["meshes"][0]["primitives"][0]["attributes"]
    tangents, normals = doc["accessors"][attributes["TANGENT"]], doc["accessors"][attributes["NORMAL"]]
    count = tangents["count"]
    t = struct.unpack_from(f"<{4 * count}f", chunk, start_of(doc, tangents))
    n = struct.unpack_from(f"<{3 * count}f", chunk, start_of(doc, normals))
    edited = [value for k in range(count) for value in edit(t[4 * k:4 * k + 4], n[3 * k:3 * k + 3])]
    blob = bytearray(chunk)
    struct.pack_into(f"<{4 * count}f", blob, start_of(doc, tangents), *edited)
    return write(out, glb_bytes(doc, bytes(blob)))


def test_check_catches_a_flipped_w_and_a_ten_degree_turn_on_an_anisotropy_only_primitive(tmp_path):
    """A brushed metal without a normal map still reads TANGENT: check judges it as it judges a
    normal-mapped primitive's (handedness for w, reference for the direction)."""
    source = asset(tmp_path, {"extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.8}}})
    bake(source, tmp_path / "baked.glb")

    def findings(path):
        done = tangent("check", path, "--format", "json")
        report = json.loads(done.stdout)
        return done.returncode, {f["check"] for f in report["files"][0]["primitives"][0]["findings"]}

    assert findings(tmp_path / "baked.glb") == (0, set())
    flipped = edited_tangents(tmp_path / "baked.glb", tmp_path / "flipped.glb", lambda t, n: (t[0], t[1], t[2], -t[3]))
    code, checks = findings(flipped)
    assert code == 1 and "handedness" in checks, checks

    def turned(t, n, degrees=10.0):  # about the normal (Rodrigues; t is orthogonal to n)
        c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
        cross = (n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0])
        return (c * t[0] + s * cross[0], c * t[1] + s * cross[1], c * t[2] + s * cross[2], t[3])

    code, checks = findings(edited_tangents(tmp_path / "baked.glb", tmp_path / "turned.glb", turned))
    assert code == 1 and checks == {"reference"}, checks
