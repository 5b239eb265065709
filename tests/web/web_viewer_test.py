# SPDX-License-Identifier: MIT
"""The web viewer (build-web/, scripts/web.sh) in headless Chromium against the desktop viewer.

For each shared asset (../shared/assets/*.glb), raw and baked by `tangent bake`, an OBJ (the
demo torus written as one: the page reads OBJ, PLY and OFF as tangent bake does) and the demo
scene (a .gltf whose .bin and textures the page fetches beside it): the page
(index.html?url=...) reaches state "ready", and its frames of the lit, tangent, handedness and
error views, the split compare view and the tangent-frame glyphs match tangent-view --screenshot of the same file, camera and size (llvmpipe under
Xvfb) within the tolerance below. A truncated .glb, a missing URL and a meshopt-compressed file
reach "error: ..." naming the file, an unknown view "error: ..." naming it; every shader variant of --check-shaders links under WebGL2; the page's "bake tangents"
gives the bytes `tangent bake` writes for the same file, and its list of checks the report
`tangent check --format json` gives. Opened with no options, the page takes tangent-view's
defaults for its rasteriser (check_defaults: on SwiftShader no MSAA and no PCF; the same default
frame and auto exposure as tangent-view's default screenshot). Load and frame times are
printed (and written to OUT/times.json).

Tolerance. The two renderers are different software rasterisers (SwiftShader through ANGLE,
Mesa's llvmpipe) running the same GLSL with the same inputs: they differ in rounding of
interpolants and texture filtering (a few levels of 255 per channel over whole surfaces),
in which pixels a triangle's edge covers, and in shadow-map depth comparison at the shadow's
edge (single pixels that differ a lot). So: a pixel differs when a channel is off by more than
12 of 255 (5 %), and at most 1 % of the pixels may differ, with a mean difference of at most
1.5 of 255. Measured here (Chromium 156's SwiftShader against Mesa 22's llvmpipe, 320x240, both
shared assets raw and baked, four views): at most 0.11 % of the pixels differ and the mean is at
most 0.14, so the limits leave a factor of about ten for other versions of either. Comparing
each view with another one (--break, which must fail) gives 17 % of the pixels and means of
15-19: every pixel the asset covers.
"""
import argparse
import base64
import json
import pathlib
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import urllib.parse

HERE = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "browser")]
import chromium  # noqa: E402  (tests/browser/chromium.py: the one Chromium driver of the browser tests)
from frames import CHANNEL_TOLERANCE, MAX_DIFFERING, MAX_MEAN, SIZE, compare, desktop_screenshot, read_png, report, write_png  # noqa: E402

# What is compared: tangent-view options, the same on both sides.
VIEWS = {"lit": "--view lit", "tangent": "--view tangent", "handedness": "--view handedness", "error": "--view error",
         "split": "--view lit --compare fresh", "glyphs": "--view tangent --glyphs"}
# Tangent-frame glyphs are one-pixel lines: which pixels a line covers is where the two
# rasterisers differ most (measured: up to 0.92 % of the pixels, mean 1.09).
LIMITS = {"glyphs": (0.03, 3.0)}


SOFTWARE_RASTERISERS = ("llvmpipe", "softpipe", "SwiftShader")  # viewer/main.cpp's softwareRasteriser


def check_defaults(chrome, base, file, site, args, out):
    """The page opened with nothing but the file and the size takes the desktop viewer's defaults for
    its rasteriser: on SwiftShader (a software rasteriser, as llvmpipe is for tangent-view under
    Xvfb) no MSAA (the canvas's WebGL context made without antialiasing) and no PCF, and its default
    frame (the lit view, auto exposure) matches tangent-view's default screenshot, with the same
    exposure (the factor that puts a white surface facing the key light at 0.76). Returns failures."""
    failures = []
    page = chrome.open(base + "index.html?" + urllib.parse.urlencode({"url": str(file.relative_to(site)), "size": f"{SIZE[0]}x{SIZE[1]}"}))
    state = page.wait_state()
    if state != "ready":
        page.close()
        return [f"defaults: {file.name}: page state {state!r}, not ready"]
    status = page.evaluate("call.status()")
    antialias = page.evaluate("Module.ctx.getContextAttributes().antialias")
    width, height, web = page.read_pixels()
    page.close()
    software = any(name in status["renderer"] for name in SOFTWARE_RASTERISERS)
    print(f"defaults: the page's WebGL is {status['renderer']!r} ({'software' if software else 'hardware'}): "
          f"MSAA {status['msaaSamples']} (canvas antialias {antialias}), PCF radius {status['pcfRadius']}, exposure {status['exposure']:.4g}")
    expected = (0, False, 0) if software else (4, True, 1)
    if (status["msaaSamples"], antialias, status["pcfRadius"]) != expected:
        failures.append(f"defaults: MSAA {status['msaaSamples']}, antialias {antialias}, PCF {status['pcfRadius']} on "
                        f"{status['renderer']!r}; the desktop viewer's defaults there are MSAA {expected[0]}, PCF {expected[2]}")
    # tangent-view's own defaults: no --msaa, no --pcf, no --exposure.
    desktop_png = out / f"{file.stem}.defaults.desktop.png"
    command = [args.xvfb_run, "-a", "-s", "-screen 0 1280x1024x24", args.tangent_view, str(file), "--screenshot", str(desktop_png),
               "--size", f"{SIZE[0]}x{SIZE[1]}"]
    result = subprocess.run(command, capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        return failures + [f"defaults: {' '.join(command)}: {result.stderr}"]
    desktop_exposure = float(result.stdout.split("exposure ")[1].split(",")[0])
    _, _, desk = read_png(desktop_png)
    write_png(out / f"{file.stem}.defaults.web.png", width, height, web)
    differing, mean = compare(web, desk)
    print(f"defaults: frame {differing * 100:.2f} % of pixels differ by > {CHANNEL_TOLERANCE}, mean {mean:.2f}; "
          f"exposure {status['exposure']:.4g} in the page, {desktop_exposure:.4g} in tangent-view")
    if differing > MAX_DIFFERING or mean > MAX_MEAN:
        failures.append(f"defaults: the page's default frame differs from tangent-view's: {differing * 100:.2f} % of pixels, mean {mean:.2f}")
    if abs(status["exposure"] - desktop_exposure) > 1e-3 * desktop_exposure:
        failures.append(f"defaults: auto exposure {status['exposure']} in the page, {desktop_exposure} in tangent-view")
    return failures


def write_obj(gltf, obj):
    """The first primitive of `gltf` (float POSITION, NORMAL, TEXCOORD_0 and indices, packed) as
    an OBJ with v, vt (bottom-left origin: v flipped) and vn per vertex and one v/vt/vn face per
    triangle."""
    doc = json.loads(gltf.read_text())
    data = (gltf.parent / doc["buffers"][0]["uri"]).read_bytes()
    primitive = doc["meshes"][0]["primitives"][0]

    def read(index, width):
        accessor = doc["accessors"][index]
        view = doc["bufferViews"][accessor["bufferView"]]
        start = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
        code = {5126: "f", 5123: "H", 5125: "I"}[accessor["componentType"]]
        values = struct.unpack_from(f"<{accessor['count'] * width}{code}", data, start)
        return [values[i:i + width] for i in range(0, len(values), width)]

    attributes = primitive["attributes"]
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in read(attributes["POSITION"], 3)]
    lines += [f"vt {u!r} {1.0 - v!r}" for u, v in read(attributes["TEXCOORD_0"], 2)]
    lines += [f"vn {x!r} {y!r} {z!r}" for x, y, z in read(attributes["NORMAL"], 3)]
    corners = [i + 1 for (i,) in read(primitive["indices"], 1)]
    lines += ["f " + " ".join(f"{c}/{c}/{c}" for c in corners[t:t + 3]) for t in range(0, len(corners), 3)]
    obj.write_text("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build-web", required=True, help="scripts/web.sh's output folder")
    parser.add_argument("--tangent-view", required=True)
    parser.add_argument("--tangent", required=True)
    parser.add_argument("--xvfb-run", default="xvfb-run")
    parser.add_argument("--assets", required=True, help="folder of .glb files")
    parser.add_argument("--demo", help="data/demo: its scene.gltf (a .gltf with a .bin and textures beside it) is compared too")
    parser.add_argument("--out", required=True, help="folder for the screenshots and times.json")
    parser.add_argument("--break", dest="broken", action="store_true",
                        help="compare each web view with the desktop's next view: must fail (checks the check)")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    assets = sorted(pathlib.Path(args.assets).glob("*.glb"))
    if not assets:
        print(f"no .glb in {args.assets}")
        return 1

    # The page and the files it loads, served from one folder.
    site = pathlib.Path(tempfile.mkdtemp(prefix="tangent-web-site-"))
    for name in ("index.html", "tangent-view.js", "tangent-view.wasm"):
        shutil.copy(pathlib.Path(args.build_web) / name, site / name)
    files = []
    for asset in assets:
        shutil.copy(asset, site / asset.name)
        baked = site / (asset.stem + ".baked.glb")
        subprocess.run([args.tangent, "bake", str(asset), str(baked)], check=True, capture_output=True)
        files += [site / asset.name, baked]
    if args.demo:
        write_obj(pathlib.Path(args.demo) / "torus.gltf", site / "torus.obj")
        files.append(site / "torus.obj")
        shutil.copytree(args.demo, site / "demo")
        files.append(site / "demo" / "scene.gltf")  # last: check_defaults opens it
    (site / "broken.glb").write_bytes((site / assets[0].name).read_bytes()[:200])
    refusals = [("broken.glb", ["broken.glb"]), ("missing.glb", ["missing.glb"]),
                (assets[0].name + "&view=no-such-view", ["--view: 'no-such-view' is not lit"])]
    if shutil.which("gltfpack"):  # a meshopt-compressed copy: refused by name, not a crash
        subprocess.run(["gltfpack", "-i", str(assets[0]), "-o", str(site / "meshopt.glb"), "-c"], check=True, capture_output=True)
        refusals.append(("meshopt.glb", ["meshopt.glb", "EXT_meshopt_compression"]))

    failures, times = [], {}
    with chromium.serve(site) as base, chromium.Browser(timeout=300) as chrome:
        for file in files:
            query = urllib.parse.urlencode({"url": str(file.relative_to(site)), "size": f"{SIZE[0]}x{SIZE[1]}", "msaa": "0"})
            start = time.monotonic()
            page = chrome.open(base + "index.html?" + query)
            state = page.wait_state()
            load_ms = (time.monotonic() - start) * 1000
            if state != "ready":
                failures.append(f"{file.name}: page state {state!r}, not ready")
                page.close()
                continue
            frame_ms = page.evaluate("Module._tangent_web_frame_ms(10)")
            times[file.name] = {"load_ms": round(load_ms), "frame_ms": round(frame_ms, 2)}
            print(f"{file.name}: ready after {load_ms:.0f} ms (navigation to first frame), median frame {frame_ms:.1f} ms")
            if not file.name.endswith(".baked.glb"):
                # "bake tangents" in the page: the same bytes as `tangent bake` of the same file.
                reference = site / "cli-baked" / (file.stem + ".glb")
                reference.parent.mkdir(exist_ok=True)
                subprocess.run([args.tangent, "bake", str(file), str(reference)], check=True, capture_output=True)
                baked = page.evaluate("""(() => { const b = bake(); if (!b) return null;
                    let s = ""; for (let i = 0; i < b.length; i += 32768) s += String.fromCharCode.apply(null, b.subarray(i, i + 32768));
                    return btoa(s); })()""")
                if baked is None:
                    failures.append(f"{file.name}: baking in the page failed: " + page.evaluate("document.getElementById('message').textContent"))
                else:
                    same = base64.b64decode(baked) == reference.read_bytes()
                    print(f"  bake in the page: {len(base64.b64decode(baked))} bytes, {'identical to' if same else 'DIFFERENT from'} tangent bake's")
                    if not same:
                        (out / f"{file.stem}.page-baked.glb").write_bytes(base64.b64decode(baked))
                        failures.append(f"{file.name}: the page's bake differs from tangent bake's (both in {out})")
                        shutil.copy(reference, out / f"{file.stem}.cli-baked.glb")
            # The page's list of `tangent check` findings: the report `tangent check --format json` gives.
            page_check = page.evaluate("check()")
            cli = subprocess.run([args.tangent, "check", "--format", "json", str(file)], capture_output=True, text=True)
            cli_check = json.loads(cli.stdout)["files"][0]
            findings = sum(len(p["findings"]) for p in cli_check["primitives"])
            same = page_check["primitives"] == cli_check["primitives"] and page_check["status"] == cli_check["status"]
            print(f"  check in the page: {page_check['status']}, {findings} finding(s), {'the same as' if same else 'DIFFERENT from'} tangent check's")
            if not same:
                failures.append(f"{file.name}: the page's check differs from tangent check --format json:\n{json.dumps(page_check)[:2000]}\n"
                                f"{json.dumps(cli_check)[:2000]}")
            names = list(VIEWS)
            for index, view in enumerate(names):
                error = page.evaluate(f"Module.ccall('tangent_web_options', 'string', ['string'], ['{VIEWS[view]} --msaa 0'])")
                if error:
                    failures.append(f"{file.name}: {VIEWS[view]}: {error}")
                    continue
                width, height, web = page.read_pixels()
                write_png(out / f"{file.stem}.{view}.web.png", width, height, web)
                reference = VIEWS[names[(index + 1) % len(names)]] if args.broken else VIEWS[view]
                _, _, desk = desktop_screenshot(args.tangent_view, args.xvfb_run, file, reference.split(),
                                                out / f"{file.stem}.{view}.desktop.png")
                differing, mean = compare(web, desk)
                max_differing, max_mean = LIMITS.get(view, (MAX_DIFFERING, MAX_MEAN))
                verdict = "ok" if differing <= max_differing and mean <= max_mean else "DIFFERS"
                print(f"  {view:<11} {differing * 100:5.2f} % of pixels differ by > {CHANNEL_TOLERANCE}, mean {mean:.2f}: {verdict}")
                if verdict != "ok":
                    failures.append(f"{file.name} {VIEWS[view]}: {differing * 100:.2f} % of pixels differ (limit "
                                    f"{max_differing * 100} %), mean {mean:.2f} (limit {max_mean}); see {out}")
            if file == files[0]:
                linked = page.evaluate("Module._tangent_web_check_shaders()")
                print(f"--check-shaders under WebGL2: {linked} programs linked")
                if linked <= 0:
                    failures.append("shader variants do not link under WebGL2: " + "\n".join(page.console[-20:]))
            page.close()

        for name, expected in refusals:
            url, _, extra = name.partition("&")
            page = chrome.open(base + "index.html?" + urllib.parse.urlencode({"url": url, "size": "64x64"}) + (f"&{extra}" if extra else ""))
            state = page.wait_state()
            print(f"{name}: {state}")
            if not state.startswith("error: ") or not all(word in state for word in expected):
                failures.append(f"{name}: page state {state!r}, expected 'error: ...' naming {', '.join(expected)}")
            page.close()
        failures += check_defaults(chrome, base, files[-1], site, args, out)
    shutil.rmtree(site, ignore_errors=True)
    (out / "times.json").write_text(json.dumps(times, indent=1) + "\n")
    return report(failures, args.broken)


if __name__ == "__main__":
    sys.exit(main())
