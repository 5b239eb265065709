# SPDX-License-Identifier: MIT
"""The web viewer's page controls in headless Chromium, each used as a person would (clicks,
<select> changes, the timeline, a file input) and judged by the frame it gives, against the desktop
viewer where it has the same option.

1. Clicking a finding frames its triangle. A generated 16x16 grid (a triangle soup, normal
   mapped, TANGENT +x as MikkTSpace gives it for these UVs) with one off-centre triangle's tangents
   turned 90 deg about the normal: `tangent check` must report exactly `reference` on its 3 corners
   (the clean grid must pass, which confirms the hand-made tangents). Clicking the page's finding
   must switch to the error view and the front camera and centre the triangle's magenta (its
   centroid within 10 % of the frame's centre, against off-centre before) at 3x its share
   before; and the frame must match tangent-view --view error --camera front --frame-box BOX, BOX
   being the rule of tangent check --format html's thumbnails worked out here from the triangle's
   corners (its box grown to half-extents of 0.4 * the grid's radius / sqrt 3).
2. The animation picker and timeline: tangent-make-data --animated's skinned asset opened at half
   its animation's duration H (?animation=0&time=H) matches tangent-view --animation 0 --time H;
   then the rest pose and animation 0 chosen in the picker, the timeline set to 0 s and to H: the
   frame at H is the one opened, and differs from the one at 0 s on more than 2 % of the pixels.
   The play button advances the time shown on the timeline.
3. The second file for the split compare: the clean grid loaded, a copy with every tangent turned
   90 deg chosen with the "second file" input: the split tangent view matches tangent-view
   --compare FILE and differs from the split against fresh tangents on the right half only. A
   second file with other triangles is refused with a message naming it. The "options" field's
   words reach tangent-view's option parser.

Usage: page_controls_test.py --build-web DIR --tangent-view EXE --tangent EXE --make-data EXE
       --xvfb-run EXE --out DIR [--break]   (--break: the page's finding click does nothing; must fail)
"""
import argparse
import base64
import json
import math
import pathlib
import shutil
import struct
import subprocess
import sys
import tempfile
import urllib.parse

HERE = pathlib.Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "browser")]
import chromium  # noqa: E402
from frames import SIZE, desktop_screenshot, matches, png_bytes, report, write_png  # noqa: E402

GRID = 16
TURNED_CELL = (12, 3)  # the turned triangle: the first of this cell (column, row), off the centre
MIN_SHARE_GAIN = 3.0
CENTRE_TOLERANCE = 0.10


def grid_triangles(rows=GRID):
    """Corners of a rows x GRID grid on z = 0 over [-1, 1] x [-1, rows/GRID*2 - 1], two triangles per cell
    (counter-clockwise seen from +z), and the triangle index of TURNED_CELL's first."""
    corners = []
    for j in range(rows):
        for i in range(GRID):
            x0, x1 = -1 + 2 * i / GRID, -1 + 2 * (i + 1) / GRID
            y0, y1 = -1 + 2 * j / GRID, -1 + 2 * (j + 1) / GRID
            corners += [(x0, y0), (x1, y0), (x1, y1), (x0, y0), (x1, y1), (x0, y1)]
    return corners, 2 * (TURNED_CELL[1] * GRID + TURNED_CELL[0])


def write_grid(path, turned=(), rows=GRID):
    """The grid as a self-contained .gltf: UV u = (x+1)/2, v = (1-y)/2 (glTF's top-left origin), so
    the texture's up (-v) is +y and MikkTSpace gives T = +x, w = +1; the corners of the triangles in
    `turned` (or all for "all") get T = +y instead."""
    corners, _ = grid_triangles(rows)
    positions, normals, uvs, tangents = bytearray(), bytearray(), bytearray(), bytearray()
    for c, (x, y) in enumerate(corners):
        positions += struct.pack("<3f", x, y, 0)
        normals += struct.pack("<3f", 0, 0, 1)
        uvs += struct.pack("<2f", (x + 1) / 2, (1 - y) / 2)
        turn = turned == "all" or c // 3 in turned
        tangents += struct.pack("<4f", 0 if turn else 1, 1 if turn else 0, 0, 1)
    data = bytes(positions + normals + uvs + tangents)
    n = len(corners)
    views = [(0, 12 * n), (12 * n, 12 * n), (24 * n, 8 * n), (32 * n, 16 * n)]
    gltf = {
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"name": "grid", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "TANGENT": 3},
                                                    "material": 0}]}],
        "materials": [{"normalTexture": {"index": 0}}],
        "textures": [{"source": 0}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(png_bytes(2, 2, bytes((128, 128, 255, 255)) * 4)).decode()}],
        "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": o, "byteLength": l} for o, l in views],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
             "min": [-1, -1, 0], "max": [1, -1 + 2 * rows / GRID, 0]},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5126, "count": n, "type": "VEC4"}],
    }
    path.write_text(json.dumps(gltf))


def magenta(pixels, width, height):
    """The share of the error view's failing-corner magenta, and its centroid as fractions of the frame."""
    count, sx, sy = 0, 0.0, 0.0
    for p in range(width * height):
        if pixels[4 * p] > 200 and pixels[4 * p + 1] < 60 and pixels[4 * p + 2] > 200:
            count += 1
            sx += p % width
            sy += p // width
    if not count:
        return 0.0, None
    return count / (width * height), (sx / count / width, sy / count / height)


def frame_box(corners, triangle):
    """tangent check --format html's framing rule (tangent/framing.hpp), from its description."""
    points = [(x, y, 0.0) for x, y in corners[3 * triangle:3 * triangle + 3]]
    every = [(x, y, 0.0) for x, y in corners]
    lo = [min(p[a] for p in points) for a in range(3)]
    hi = [max(p[a] for p in points) for a in range(3)]
    all_lo = [min(p[a] for p in every) for a in range(3)]
    all_hi = [max(p[a] for p in every) for a in range(3)]
    min_half = 0.4 * math.dist(all_lo, all_hi) / 2 / math.sqrt(3)
    box = []
    for a in range(3):
        centre, half = (lo[a] + hi[a]) / 2, max((hi[a] - lo[a]) / 2, min_half)
        box.append((centre - half, centre + half))
    return ",".join(f"{v:.9g}" for v in [b[0] for b in box] + [b[1] for b in box])


def main():
    parser = argparse.ArgumentParser()
    for name in ("--build-web", "--tangent-view", "--tangent", "--make-data", "--out"):
        parser.add_argument(name, required=True)
    parser.add_argument("--xvfb-run", default="xvfb-run")
    parser.add_argument("--break", dest="broken", action="store_true")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir(parents=True)
    failures = []

    def check(condition, message):
        print(("ok   " if condition else "FAIL ") + message)
        if not condition:
            failures.append(message)
        return condition

    def desktop(asset, options, name):
        return desktop_screenshot(args.tangent_view, args.xvfb_run, asset, options, out / f"{name}.desktop.png")[2]

    def agrees(web, other, name, what="tangent-view's"):
        same, differing, mean = matches(web, other)
        return check(same, f"{name}: the page's frame matches {what} ({differing * 100:.2f} % of pixels differ, mean {mean:.2f})")

    site = pathlib.Path(tempfile.mkdtemp(prefix="tangent-web-controls-"))
    for name in ("index.html", "tangent-view.js", "tangent-view.wasm"):
        shutil.copy(pathlib.Path(args.build_web) / name, site / name)
    corners, turned = grid_triangles()
    write_grid(site / "grid.gltf")
    write_grid(site / "grid-bad.gltf", turned=(turned,))
    write_grid(site / "grid-turned.gltf", turned="all")
    write_grid(site / "grid-short.gltf", rows=GRID - 1)
    subprocess.run([args.make_data, "--animated", str(site / "animated")], check=True, capture_output=True)

    # The hand-made grids as tangent check sees them: the reference the clicks below rely on.
    def check_json(path):
        return json.loads(subprocess.run([args.tangent, "check", "--format", "json", str(path)], capture_output=True, text=True).stdout)
    check(check_json(site / "grid.gltf")["files"][0]["status"] == "clean", "the clean grid passes tangent check")
    bad = check_json(site / "grid-bad.gltf")["files"][0]["primitives"][0]["findings"]
    check([(f["check"], f["failed"], f["unit"]) for f in bad] == [("reference", 3, "corners")],
          f"the turned triangle fails `reference` on its 3 corners only: {[(f['check'], f['failed']) for f in bad]}")

    query = lambda url, **extra: "index.html?" + urllib.parse.urlencode({"url": url, "size": f"{SIZE[0]}x{SIZE[1]}", "msaa": "0", **extra})
    with chromium.serve(site) as base, chromium.Browser(timeout=300) as chrome:
        # 1. A finding clicked.
        page = chrome.open(base + query("grid-bad.gltf", view="error"))
        check(page.wait_state() == "ready", "grid-bad.gltf reaches ready")
        width, height, before = page.read_pixels()
        share_before, centre_before = magenta(before, width, height)
        items = page.evaluate("[...document.querySelectorAll('#findings li.finding')].map(li => li.textContent)")
        check(len(items) == 1 and "reference" in items[0], f"the page lists the one finding: {items}")
        if not args.broken:
            page.evaluate("document.querySelector('#findings li.finding').click()")
        width, height, after = page.read_pixels()
        write_png(out / "finding.before.web.png", width, height, before)
        write_png(out / "finding.after.web.png", width, height, after)
        share_after, centre_after = magenta(after, width, height)
        controls = page.evaluate("[document.getElementById('view').value, document.getElementById('camera').value]")
        print(f"magenta before the click: {share_before * 100:.2f} % at {centre_before}; after: {share_after * 100:.2f} % at {centre_after}")
        check(controls == ["error", "front"], f"the click shows the error view from the front camera: {controls}")
        check(centre_before is not None and max(abs(centre_before[0] - 0.5), abs(centre_before[1] - 0.5)) > CENTRE_TOLERANCE,
              "before the click the turned triangle is off the frame's centre (the test can see the framing)")
        check(centre_after is not None and max(abs(centre_after[0] - 0.5), abs(centre_after[1] - 0.5)) <= CENTRE_TOLERANCE,
              f"after the click the turned triangle is at the frame's centre: {centre_after}")
        check(share_after >= MIN_SHARE_GAIN * share_before > 0,
              f"and fills at least {MIN_SHARE_GAIN}x its share before ({share_after / max(share_before, 1e-9):.1f}x)")
        agrees(after, desktop(site / "grid-bad.gltf", ["--view", "error", "--camera", "front", "--frame-box", frame_box(corners, turned)],
                              "finding"), "finding framed (--frame-box)")
        page.close()

        # 2. The animation picker, the timeline and the play button. The desktop frames its camera on
        # the pose it shows, so the page opens at the half time as well (?animation=0&time=H) and its
        # controls go to the rest pose, back to animation 0 at 0 s, then to H along the timeline.
        asset = json.loads((site / "animated" / "skinned.gltf").read_text())
        half = max(asset["accessors"][s["input"]]["max"][0] for s in asset["animations"][0]["samplers"]) / 2
        page = chrome.open(base + query("animated/skinned.gltf", view="tangent", animation="0", time=f"{half}"))
        check(page.wait_state() == "ready", "skinned.gltf reaches ready")
        width, height, opened = page.read_pixels()
        agrees(opened, desktop(site / "animated" / "skinned.gltf", ["--view", "tangent", "--animation", "0", "--time", f"{half}"],
                               "animated"), f"skinned at {half:.3f} s (?animation=0&time={half:g})")
        animations = page.evaluate("call.status().animations")
        check(len(animations) == 1 and animations[0]["duration"] == 2 * half, f"the page lists the file's animation: {animations}")
        picker = page.evaluate("[...document.getElementById('animation').options].map(o => o.value)")
        check(picker == ["-1", "0"], f"the picker offers the rest pose and animation 0: {picker}")
        choose = "(s => { s.value = '%s'; s.dispatchEvent(new Event('change')); })(document.getElementById('animation'))"
        page.evaluate(choose % "-1")
        check(page.evaluate("call.poseNow().animation") == -1, "the picker's rest pose")
        page.evaluate(choose % "0")
        frames = {}
        for seconds in (0.0, half):
            page.evaluate(f"(t => {{ t.value = '{seconds}'; t.dispatchEvent(new Event('input')); }})(document.getElementById('time'))")
            pose = page.evaluate("call.poseNow()")
            check(pose["animation"] == 0 and abs(pose["seconds"] - seconds) < 0.01 and not pose["playing"],
                  f"the picker and the timeline set animation 0 at {seconds:.3f} s: {pose}")
            width, height, frames[seconds] = page.read_pixels()
            write_png(out / f"animated.{seconds:.3f}.web.png", width, height, frames[seconds])
        agrees(frames[half], opened, f"the timeline back at {half:.3f} s", "the one opened at that time")
        differing = matches(frames[0.0], frames[half], (0.02, 1e9))[1]
        check(differing > 0.02, f"0 s and {half:.3f} s give different frames ({differing * 100:.1f} % of pixels differ)")
        page.evaluate("document.getElementById('play').click()")
        advanced = page.wait_for(f"(p => p.playing && Number(document.getElementById('time').value) > {half} + 0.05)(call.poseNow())", 60)
        check(bool(advanced), "the play button advances the timeline")
        page.close()

        # 3. A second file for the split compare, chosen through the page's file input.
        page = chrome.open(base + query("grid.gltf", view="tangent"))
        check(page.wait_state() == "ready", "grid.gltf reaches ready")
        page.evaluate("(c => { c.checked = true; c.dispatchEvent(new Event('change')); })(document.getElementById('split'))")
        width, height, fresh = page.read_pixels()
        page.set_input_files("#compareFile", [site / "grid-turned.gltf"])
        page.wait_for("document.getElementById('compareWith').options.length === 3", 30)
        width, height, split = page.read_pixels()
        write_png(out / "compare.fresh.web.png", width, height, fresh)
        write_png(out / "compare.file.web.png", width, height, split)
        agrees(split, desktop(site / "grid.gltf", ["--view", "tangent", "--compare", str(site / "grid-turned.gltf")], "compare"),
               "split against the second file (--compare FILE)")
        half_width = width // 2
        left = lambda px: b"".join(px[(y * width) * 4:(y * width + half_width - 4) * 4] for y in range(height))
        right = lambda px: b"".join(px[(y * width + half_width + 4) * 4:((y + 1) * width) * 4] for y in range(height))
        check(matches(left(split), left(fresh))[0], "the left half (the file's tangents) stays as it was")
        right_differing = matches(right(split), right(fresh), (0.05, 1e9))[1]
        check(right_differing > 0.05, f"the right half shows the second file's tangents ({right_differing * 100:.1f} % of its pixels changed)")
        page.set_input_files("#compareFile", [site / "grid-short.gltf"])
        message = page.wait_for("document.getElementById('message').textContent", 30)
        check("grid-short.gltf" in message and "triangle" in message, f"a second file with other triangles is refused by name: {message!r}")
        # The "options" field: any tangent-view option; a wrong one is answered by the viewer's parser.
        page.evaluate("(e => { e.value = '--no-such-option'; e.dispatchEvent(new Event('change')); })(document.getElementById('extra'))")
        message = page.evaluate("document.getElementById('message').textContent")
        check("unknown option '--no-such-option'" in message, f"the options field goes to tangent-view's parser: {message!r}")
        page.close()
    shutil.rmtree(site, ignore_errors=True)
    return report(failures, args.broken)


if __name__ == "__main__":
    sys.exit(main())
