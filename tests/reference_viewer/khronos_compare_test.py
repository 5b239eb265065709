# SPDX-License-Identifier: MIT
"""ctest reference.khronos_sample_viewer: tangent-view against a renderer no one here wrote, the
Khronos glTF Sample Viewer's engine (npm @khronosgroup/gltf-viewer, pinned in tests/node) in
headless Chromium, on the scenes of `tangent-make-data --materials`.

Both draw each scene from the same camera (tangent-view's --camera front framing, written into a
copy of the file as a glTF camera for the engine), with the file's one KHR_lights_punctual sun,
no shadows, no image-based light and no tone mapping, at the same exposure. What is compared is
what the tangent frame decides, measured on each image in linear luminance:
- KHR_materials_anisotropy (the brushed disc, lit and seen head-on, the direction texture
  dropped): the highlight's principal axis (second moments of the bright pixels, the measure of
  tests/viewer/materials_test.cpp) at two anisotropyRotation values, and how far it turns
  between them; the disc as made (its circular direction texture, its sun from the upper
  right): the correlation of the two pictures' luminance;
- KHR_materials_clearcoat (the sphere whose clearcoat normal map reads TEXCOORD_1 through a
  rotated KHR_texture_transform): the relief its normal map puts into the coat, as the image
  with the map minus the image without it, correlated between the renderers; and the smooth
  coat's highlight position.
Each comparison is also run on our renders of frames made wrong on purpose (TANGENT's w flipped,
TANGENT turned 10 degrees about the normal), which it must reject: the measure is seen to tell a
wrong frame from a right one.

Usage: khronos_compare_test.py --tangent-view BIN --make-data BIN --xvfb-run BIN --out DIR
Writes the renders and side-by-side PNGs (left tangent-view, right the Sample Viewer) into DIR.
Exits 0 when all agree, 1 otherwise; 77 (skipped) where chromium is not installed (1 under CI=true).
"""
import argparse
import base64
import json
import math
import os
import pathlib
import shutil
import struct
import subprocess
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
SOURCE = HERE.parent.parent
sys.path.insert(0, str(SOURCE / "tests" / "browser"))
sys.path.insert(0, str(SOURCE / "tests" / "web"))
import chromium  # noqa: E402
import frames  # noqa: E402  (PNG reading and writing)

SIZE = 240
FIELD_OF_VIEW_Y = 40.0  # degrees: tangent-view's (viewer/camera.hpp, OrbitCamera::kFieldOfViewY)
# Exposure for both (no tone mapping): the disc's highlight peaks below 1 in both renderers, so
# that its shape is not cut flat by clipping; the sphere's coat highlight may clip (it is small).
DISC_EXPOSURE = 0.15
SPHERE_EXPOSURE = 0.5
OUR_OPTIONS = ["--camera", "front", "--size", f"{SIZE}x{SIZE}", "--no-shadows", "--no-ibl", "--tone-map", "none", "--msaa", "0"]
# Both clear to tangent-view's background, (0.16, 0.17, 0.19): bluer than any pixel of these grey
# and red scenes, so that it tells the object's pixels in either image.
BACKGROUND = (41, 43, 48)

# Tolerances, chosen from measurements (Debian 12: tangent-view on Mesa llvmpipe, the engine on
# Chromium's SwiftShader; the numbers each run prints). Each comparison also runs on our renders
# of frames made wrong on purpose (CONTROL_TURN_DEG, and w flipped), which it must reject.
# The highlight axes agreed to 0.01 deg at both rotations, and a TANGENT turned by 2 / 5 / 10 deg
# moved our axis by 2.0 / 5.0 / 10.0 deg: 1.5 deg keeps a 30-fold margin over the renderers'
# difference and rejects any turn of 2 deg or more.
AXIS_TOLERANCE_DEG = 1.5
MIN_ELONGATION = 1.5  # measured 5.14 in both; materials_test.cpp's isotropic highlight stays below 1.3
CONTROL_TURN_DEG = 10.0
# The objects' boxes matched to the pixel; 2 px allows rasterisation rules to differ.
SILHOUETTE_TOLERANCE_PX = 2
# The made disc's luminance (circular direction texture, sun from the upper right) correlated
# 0.9999 between the renderers; ours with w flipped 0.55 with theirs, with TANGENT turned 10 deg
# 0.96 (a turn of a circular field changes less of the picture than a turn of one direction).
PICTURE_MIN_CORRELATION = 0.98
# The clearcoat relief (image with the map minus without), dominated by the glints of the sharp
# coat highlight, correlated 0.85 between the renderers (what is left, most likely: glints a pixel
# apart, and our --no-ibl sky term, which the coat reflects and the engine's IBL-off frame
# lacks); our relief with TANGENT turned by 2 / 5 / 10 deg correlated 0.80 / 0.64 / 0.58 with
# theirs, with w flipped 0.37. 0.75 passes the renderers' agreement with a 0.1 margin and rejects
# turns of 5 deg and more.
RELIEF_MIN_CORRELATION = 0.75
# The smooth coat's highlight centroid matched to 0.0 px: the light, camera and coat agree.
HIGHLIGHT_POSITION_TOLERANCE_PX = 1.5


def skip_or_fail(message):
    """tests/support/skip_or_fail.sh's rule: skipped (77), or a failure under CI=true."""
    print(message)
    if os.environ.get("CI") == "true":
        print("CI=true, so a missing input is a failure")
        sys.exit(1)
    sys.exit(77)


# --- the scenes ---------------------------------------------------------------------------------

def front_camera_distance(lo, hi, aspect=1.0):
    """tangent-view's --camera front distance for the bounds lo..hi (OrbitCamera::frame: every
    corner inside the frame, plus 5%); the camera sits on +z above the centre looking along -z."""
    tan_y = math.tan(math.radians(FIELD_OF_VIEW_Y) / 2)
    tan_x = tan_y * aspect
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    needed = 0.0
    for corner in range(8):
        p = [hi[k] if corner >> k & 1 else lo[k] for k in range(3)]
        q = [p[k] - centre[k] for k in range(3)]
        needed = max(needed, q[2] + abs(q[0]) / tan_x, q[2] + abs(q[1]) / tan_y)
    return centre, needed * 1.05


def with_camera(doc):
    """A copy of doc with a glTF camera placed as tangent-view's front camera (the scene's mesh
    bounds from the POSITION accessors' min/max; the scenes here have untransformed meshes)."""
    doc = json.loads(json.dumps(doc))
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    for mesh in doc["meshes"]:
        for primitive in mesh["primitives"]:
            accessor = doc["accessors"][primitive["attributes"]["POSITION"]]
            lo = [min(a, b) for a, b in zip(lo, accessor["min"])]
            hi = [max(a, b) for a, b in zip(hi, accessor["max"])]
    centre, distance = front_camera_distance(lo, hi)
    radius = math.dist(lo, hi) / 2
    doc.setdefault("cameras", []).append({"type": "perspective", "perspective": {
        "yfov": math.radians(FIELD_OF_VIEW_Y), "aspectRatio": 1.0,
        "znear": max(distance - 3 * radius, distance * 1e-3), "zfar": distance + 3 * radius}})
    doc["nodes"].append({"name": "FrontCamera", "camera": len(doc["cameras"]) - 1,
                         "translation": [centre[0], centre[1], centre[2] + distance]})
    doc["scenes"][doc.get("scene", 0)]["nodes"].append(len(doc["nodes"]) - 1)
    return doc


def disc(made, rotation):
    """The brushed disc lit and seen head-on (the sun's node rotation removed: it shines along
    -z), one anisotropy direction (the texture dropped), turned by `rotation` radians."""
    doc = json.loads((made / "anisotropy_disc.gltf").read_text())
    for node in doc["nodes"]:
        if "extensions" in node:
            node.pop("rotation", None)
    anisotropy = doc["materials"][0]["extensions"]["KHR_materials_anisotropy"]
    anisotropy["anisotropyRotation"] = rotation
    anisotropy.pop("anisotropyTexture")
    return doc


def turned_tangents(folder, name, doc, degrees):
    """Writes folder/name.gltf and .bin: doc (whose buffer is in folder) with every TANGENT
    turned by `degrees` about its vertex's NORMAL (float VEC3/VEC4 accessors, as made): a frame
    wrong by that much, for the controls."""
    doc = json.loads(json.dumps(doc))
    data = bytearray((folder / doc["buffers"][0]["uri"]).read_bytes())
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))

    def floats(accessor, components):
        view = doc["bufferViews"][accessor["bufferView"]]
        stride = view.get("byteStride", 4 * components)
        start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
        return [start + i * stride for i in range(accessor["count"])]

    for mesh in doc["meshes"]:
        for primitive in mesh["primitives"]:
            attributes = primitive["attributes"]
            normals = floats(doc["accessors"][attributes["NORMAL"]], 3)
            tangents = floats(doc["accessors"][attributes["TANGENT"]], 4)
            for n_at, t_at in zip(normals, tangents):
                n = struct.unpack_from("<3f", data, n_at)
                t = struct.unpack_from("<3f", data, t_at)
                cross = (n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0])
                along = sum(a * b for a, b in zip(n, t))
                turned = [t[k] * c + cross[k] * s + n[k] * along * (1 - c) for k in range(3)]
                struct.pack_into("<3f", data, t_at, *turned)
    doc["buffers"][0]["uri"] = f"{name}.bin"
    (folder / f"{name}.bin").write_bytes(bytes(data))
    (folder / f"{name}.gltf").write_text(json.dumps(doc, indent=1))
    return folder / f"{name}.gltf"


def sphere(made, edit=None):
    """The clearcoat sphere as made (its sun from above right of the camera), edited."""
    doc = json.loads((made / "clearcoat_sphere.gltf").read_text())
    if edit:
        edit(doc["materials"][0]["extensions"]["KHR_materials_clearcoat"])
    return doc


# --- the two renderers --------------------------------------------------------------------------

def render_ours(args, scene, png, extra=()):
    command = [args.xvfb_run, "-a", "-s", "-screen 0 1280x1024x24", args.tangent_view, str(scene), *OUR_OPTIONS,
               *extra, "--screenshot", str(png)]
    result = subprocess.run(command, capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}:\n{result.stdout}{result.stderr}")
    return frames.read_png(png)


def build_page(page_dir):
    if not shutil.which("node"):
        print("node is not installed (scripts/install-deps.sh installs it): it builds the Sample Viewer's page")
        sys.exit(1)
    node_modules = SOURCE / "tests" / "node" / "node_modules"
    if not (node_modules / "@khronosgroup" / "gltf-viewer").is_dir() or not (node_modules / "esbuild").is_dir():
        print(f"{node_modules}: @khronosgroup/gltf-viewer or esbuild is not installed: run scripts/test.sh "
              "(it runs npm ci in tests/node)")
        sys.exit(1)
    subprocess.run(["node", str(HERE / "build_page.mjs"), str(page_dir)], check=True, timeout=120)
    # The engine needs an environment even with image-based light off: a small flat grey one
    # (Radiance RGBE, flat scanlines). Its sheen table (lut_sheen_E.png, which the package does
    # not ship; only sheen reads it) a placeholder.
    rgbe = bytes([128, 128, 128, 129]) * (16 * 8)
    (page_dir / "environment.hdr").write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n" + rgbe)
    frames.write_png(page_dir / "lut_sheen_E.png", 1, 1, b"\xff\xff\xff\xff")


def render_khronos(page, url, exposure, png):
    """The engine's frame of the glTF at url (relative to the page) as width, height, RGBA."""
    data = page.evaluate(f"renderScene({json.dumps(url)}, {exposure})")
    png.write_bytes(base64.b64decode(data.split(",", 1)[1]))
    return frames.read_png(png)


# --- measures -----------------------------------------------------------------------------------

def srgb_to_linear(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


SRGB = [srgb_to_linear(i / 255) for i in range(256)]
GAMMA_22 = [(i / 255) ** 2.2 for i in range(256)]  # the engine's linearTosRGB is pow(c, 1 / 2.2)


def luminance(image, background, decode):
    """Linear luminance per pixel, rows top first; None where the clear colour shows."""
    width, height, rgba = image
    out = []
    for p in range(width * height):
        r, g, b = rgba[4 * p], rgba[4 * p + 1], rgba[4 * p + 2]
        if max(abs(r - background[0]), abs(g - background[1]), abs(b - background[2])) <= 2:
            out.append(None)
        else:
            out.append(0.2126 * decode[r] + 0.7152 * decode[g] + 0.0722 * decode[b])
    return out


def ours(image):
    return luminance(image, BACKGROUND, SRGB)


def theirs(image):
    return luminance(image, BACKGROUND, GAMMA_22)


def silhouette(lum):
    """The object's bounding box in pixels: (x0, y0, x1, y1)."""
    xs = [p % SIZE for p, v in enumerate(lum) if v is not None]
    ys = [p // SIZE for p, v in enumerate(lum) if v is not None]
    return (min(xs), min(ys), max(xs), max(ys)) if xs else (0, 0, 0, 0)


def bright_axis(lum):
    """The principal axis of the bright region (materials_test.cpp's brightAxis): the pixels
    above the midpoint between the object's median and peak luminance, weighted by how far
    above; (angle in degrees from the image's +x towards its top in (-90, 90], the ratio of the
    axes' standard deviations, the centroid (x, y down), the peak luminance)."""
    values = sorted(v for v in lum if v is not None)
    threshold = (values[len(values) // 2] + values[-1]) / 2
    weights = [(p % SIZE + 0.5, SIZE - (p // SIZE + 0.5), v - threshold) for p, v in enumerate(lum)
               if v is not None and v > threshold]
    total = sum(w for _, _, w in weights)
    mx = sum(x * w for x, _, w in weights) / total
    my = sum(y * w for _, y, w in weights) / total
    sxx = sum(w * (x - mx) ** 2 for x, _, w in weights)
    syy = sum(w * (y - my) ** 2 for _, y, w in weights)
    sxy = sum(w * (x - mx) * (y - my) for x, y, w in weights)
    degrees = 0.5 * math.degrees(math.atan2(2 * sxy, sxx - syy))
    mean, spread = (sxx + syy) / 2, math.sqrt((sxx - syy) ** 2 / 4 + sxy ** 2)
    return degrees, math.sqrt((mean + spread) / max(mean - spread, 1e-12)), (mx, SIZE - my), values[-1]


def axis_difference(a, b):
    """a - b as lines (modulo 180 degrees), in (-90, 90]."""
    d = math.fmod(a - b, 180.0)
    if d > 90:
        d -= 180
    if d <= -90:
        d += 180
    return d


def relief(with_map, without_map):
    """What the clearcoat normal map changes: luminance with it minus without it, per pixel
    (None off the object in either)."""
    return [None if a is None or b is None else a - b for a, b in zip(with_map, without_map)]


def correlation(a, b):
    """Pearson correlation over the pixels both have."""
    pairs = [(x, y) for x, y in zip(a, b) if x is not None and y is not None]
    n = len(pairs)
    mx, my = sum(x for x, _ in pairs) / n, sum(y for _, y in pairs) / n
    sxy = sum((x - mx) * (y - my) for x, y in pairs)
    sxx = sum((x - mx) ** 2 for x, _ in pairs)
    syy = sum((y - my) ** 2 for _, y in pairs)
    return sxy / math.sqrt(sxx * syy) if sxx > 0 and syy > 0 else 0.0


def side_by_side(left, right, png):
    """The two frames beside each other (left tangent-view, right the Sample Viewer)."""
    (w, h, a), (_, _, b) = left, right
    rows = b"".join(a[y * w * 4:(y + 1) * w * 4] + b[y * w * 4:(y + 1) * w * 4] for y in range(h))
    frames.write_png(png, 2 * w, h, rows)


# --- the test -----------------------------------------------------------------------------------

def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--tangent-view", required=True)
    parser.add_argument("--make-data", required=True)
    parser.add_argument("--xvfb-run", required=True)
    parser.add_argument("--out", required=True, type=pathlib.Path)
    args = parser.parse_args()
    if not chromium.find_chromium():
        skip_or_fail("chromium is not installed (scripts/install-deps.sh installs Debian's chromium): "
                     "the Khronos Sample Viewer comparison not run")
    start = time.monotonic()
    out = args.out
    shutil.rmtree(out, ignore_errors=True)
    made, page_dir = out / "made", out / "page"
    subprocess.run([args.make_data, "--materials", str(made)], check=True, capture_output=True, timeout=120)
    build_page(page_dir)

    # The scenes both renderers draw: name -> (glTF, exposure).
    rotations = {"disc_rotation_0.3": 0.3, "disc_rotation_1.1": 1.1}
    scenes = {name: (disc(made, rotation), DISC_EXPOSURE) for name, rotation in rotations.items()}
    scenes["disc_as_made"] = (json.loads((made / "anisotropy_disc.gltf").read_text()), DISC_EXPOSURE)
    scenes["sphere_coated"] = (sphere(made), SPHERE_EXPOSURE)
    scenes["sphere_smooth_coat"] = (sphere(made, lambda coat: coat.pop("clearcoatNormalTexture")), SPHERE_EXPOSURE)
    our_images, their_images = {}, {}
    for name, (doc, exposure) in scenes.items():
        (made / f"{name}.gltf").write_text(json.dumps(doc, indent=1))
        (made / f"{name}.khronos.gltf").write_text(json.dumps(with_camera(doc), indent=1))
        our_images[name] = render_ours(args, made / f"{name}.gltf", out / f"{name}.ours.png", ["--exposure", str(exposure)])
    # The controls, ours only: each scene with a wrong frame, which each comparison must reject:
    # TANGENT's w negated (the bitangent mirrored), and TANGENT turned 10 degrees about the normal.
    controls = {}
    for name in ("disc_rotation_0.3", "disc_as_made", "sphere_coated"):
        doc, exposure = scenes[name]
        controls[(name, "w flipped")] = render_ours(args, made / f"{name}.gltf", out / f"control_{name}_w_flipped.png",
                                                    ["--exposure", str(exposure), "--negate-w"])
        turned = turned_tangents(made, f"control_{name}_turned", doc, CONTROL_TURN_DEG)
        controls[(name, f"TANGENT turned {CONTROL_TURN_DEG} deg")] = render_ours(
            args, turned, out / f"control_{name}_turned.png", ["--exposure", str(exposure)])
    ours_time = time.monotonic() - start
    with chromium.serve(out) as url, chromium.Browser(timeout=120) as browser:
        page = browser.open(url + f"page/index.html?size={SIZE}")
        state = page.wait_for("document.body.dataset.state", 120)
        if state != "ready":
            print(f"FAIL: the Sample Viewer page: {state}\n  " + "\n  ".join(page.console))
            return 1
        for name, (_, exposure) in scenes.items():
            their_images[name] = render_khronos(page, f"../made/{name}.khronos.gltf", exposure, out / f"{name}.khronos.png")
    for name in scenes:
        side_by_side(our_images[name], their_images[name], out / f"{name}.side_by_side.png")
    print(f"rendered {len(scenes) + len(controls)} tangent-view frames ({ours_time:.0f} s) and {len(scenes)} Sample Viewer "
          f"frames; side by side (left tangent-view, right the Sample Viewer) in {out}")

    failures = []

    def check(ok, message):
        print(("ok    " if ok else "FAIL  ") + message)
        if not ok:
            failures.append(message)

    lum = {name: (ours(our_images[name]), theirs(their_images[name])) for name in scenes}
    control_lum = {key: ours(image) for key, image in controls.items()}
    # The same camera: the object covers the same pixels (to a pixel or two of rasterisation;
    # measured: the same box to the pixel).
    for name, (a, b) in lum.items():
        sa, sb = silhouette(a), silhouette(b)
        worst = max(abs(p - q) for p, q in zip(sa, sb))
        check(worst <= SILHOUETTE_TOLERANCE_PX, f"{name}: the object's box {sa} here, {sb} in the Sample Viewer "
              f"(off by {worst} px, at most {SILHOUETTE_TOLERANCE_PX})")

    # Anisotropy: the highlight's axis in each renderer, and its turn between the rotations.
    axes = {}
    for name, rotation in rotations.items():
        a, b = (bright_axis(x) for x in lum[name])
        axes[name] = (a[0], b[0])
        print(f"{name}: highlight axis {a[0]:.2f} deg (elongation {a[1]:.2f}, peak {a[3]:.2f}) here, "
              f"{b[0]:.2f} deg ({b[1]:.2f}, peak {b[3]:.2f}) in the Sample Viewer; the extension's direction "
              f"{math.degrees(rotation):.2f} deg")
        check(min(a[1], b[1]) > MIN_ELONGATION, f"{name}: the highlight is stretched in both (elongation > {MIN_ELONGATION})")
        check(abs(axis_difference(a[0], b[0])) <= AXIS_TOLERANCE_DEG,
              f"{name}: the axes agree within {AXIS_TOLERANCE_DEG} deg ({axis_difference(a[0], b[0]):+.2f})")
    small, large = rotations
    turn_ours = axis_difference(axes[large][0], axes[small][0])
    turn_theirs = axis_difference(axes[large][1], axes[small][1])
    check(abs(turn_ours - turn_theirs) <= AXIS_TOLERANCE_DEG,
          f"anisotropyRotation {math.degrees(rotations[small]):.1f} -> {math.degrees(rotations[large]):.1f} deg turns the "
          f"highlight by {turn_ours:+.2f} deg here and {turn_theirs:+.2f} deg in the Sample Viewer (within {AXIS_TOLERANCE_DEG} deg)")
    for wrong in ("w flipped", f"TANGENT turned {CONTROL_TURN_DEG} deg"):
        axis = bright_axis(control_lum[(small, wrong)])[0]
        miss = axis_difference(axis, axes[small][1])
        check(abs(miss) > AXIS_TOLERANCE_DEG, f"control {small}, {wrong}: our axis {axis:.2f} deg, {miss:+.2f} deg off the "
              f"Sample Viewer's: rejected")

    # The made disc (its circular direction texture, its sun from the upper right): the whole
    # picture's luminance, correlated between the renderers.
    picture = correlation(*lum["disc_as_made"])
    check(picture >= PICTURE_MIN_CORRELATION, f"disc_as_made: luminance correlation {picture:.4f} between the renderers "
          f"(at least {PICTURE_MIN_CORRELATION})")
    for wrong in ("w flipped", f"TANGENT turned {CONTROL_TURN_DEG} deg"):
        r = correlation(control_lum[("disc_as_made", wrong)], lum["disc_as_made"][1])
        check(r < PICTURE_MIN_CORRELATION, f"control disc_as_made, {wrong}: correlation {r:.4f}: rejected")

    # Clearcoat: the relief its normal map puts into the coat, and the smooth coat's highlight.
    theirs_relief = relief(lum["sphere_coated"][1], lum["sphere_smooth_coat"][1])
    agreement = correlation(relief(lum["sphere_coated"][0], lum["sphere_smooth_coat"][0]), theirs_relief)
    check(agreement >= RELIEF_MIN_CORRELATION, f"sphere_coated: the clearcoat normal map's relief correlates {agreement:.3f} "
          f"between the renderers (at least {RELIEF_MIN_CORRELATION})")
    for wrong in ("w flipped", f"TANGENT turned {CONTROL_TURN_DEG} deg"):
        r = correlation(relief(control_lum[("sphere_coated", wrong)], lum["sphere_smooth_coat"][0]), theirs_relief)
        check(r < RELIEF_MIN_CORRELATION, f"control sphere_coated, {wrong}: relief correlation {r:.3f}: rejected")
    a, b = (bright_axis(x) for x in lum["sphere_smooth_coat"])
    offset = math.dist(a[2], b[2])
    check(offset <= HIGHLIGHT_POSITION_TOLERANCE_PX, f"sphere_smooth_coat: the coat's highlight at ({a[2][0]:.1f}, {a[2][1]:.1f}) "
          f"here, ({b[2][0]:.1f}, {b[2][1]:.1f}) in the Sample Viewer: {offset:.1f} px apart (at most {HIGHLIGHT_POSITION_TOLERANCE_PX})")
    print(f"done in {time.monotonic() - start:.0f} s")
    if failures:
        print(f"{len(failures)} comparison(s) failed; the images are in {out}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
