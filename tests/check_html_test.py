#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""CTest `check.html`: `tangent check --format html` on files with failures.

Usage: check_html_test.py TANGENT SOURCE_DIR WORK_DIR WITH_VIEWER(0|1)

The demo sphere is baked, then 20 of its stored tangents are turned 90 degrees about z (they
leave the tangent plane and the reference), and copied under a name that is not UTF-8 and holds
markup characters; the demo quad baked clean; a .glb that is not glTF. The report must be:
- HTML whose tags balance (html.parser, void elements aside) with only known character
  references, one html/head/body, no script;
- free of external URLs: no http:, https:, ftp: or // anywhere, no url( in its style, every
  src a data:image/png, every href the relative web-viewer link;
- complete: each file's section names it as the JSON report does and holds every finding's
  check, count, message and worst samples (from `--format json` on the same files);
- with a thumbnail per failing primitive (when the viewer is built) that decodes as a PNG
  (chunk CRCs, zlib stream, scanline filters) of the width and height the img states, framed on
  the failing triangles (their magenta covers several times the share it has unframed);
- a link per failing primitive to build-web/index.html?url=ASSET&view=error that, resolved
  beside the report, reaches the file;
- written, without thumbnails and saying why, when tangent-view is off, missing or has no display.
"""
import base64
import html
import html.parser
import json
import os
import pathlib
import re
import shutil
import struct
import subprocess
import sys
import urllib.parse
import zlib

tangent, source, work, with_viewer = os.path.abspath(sys.argv[1]), pathlib.Path(sys.argv[2]).resolve(), pathlib.Path(sys.argv[3]).resolve(), sys.argv[4] == "1"
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL " + message)
    return condition


# The 20 turned tangents' magenta covers 3.1 % of the framed thumbnail, 0.9 % of the whole sphere
# seen from the same side (0.2 % from the default iso camera).
MIN_MAGENTA_SHARE = 0.02
VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "track", "wbr"}


class StrictParser(html.parser.HTMLParser):
    """Tag balance, known references, and what the other checks need (text per section, img, a)."""

    def __init__(self):
        super().__init__(convert_charrefs=False)
        self.stack, self.errors, self.counts = [], [], {}
        self.images, self.links, self.sections, self.section = [], [], {}, None
        self.doctype = False

    def handle_decl(self, decl):
        self.doctype = self.doctype or decl.lower() == "doctype html"

    def handle_starttag(self, tag, attrs):
        self.counts[tag] = self.counts.get(tag, 0) + 1
        attributes = dict(attrs)
        if tag == "img":
            self.images.append(attributes)
        if tag == "a":
            self.links.append(attributes.get("href"))
        if tag == "section":
            self.section = attributes.get("id")
            self.sections[self.section] = ""
        if tag not in VOID:
            self.stack.append(tag)

    def handle_startendtag(self, tag, attrs):
        if tag not in VOID:
            self.errors.append(f"<{tag}/> is not a void element")
        self.handle_starttag(tag, attrs)

    def handle_endtag(self, tag):
        if tag in VOID:
            self.errors.append(f"</{tag}> closes a void element")
        elif not self.stack or self.stack[-1] != tag:
            self.errors.append(f"</{tag}> closes {self.stack[-1] if self.stack else 'nothing'}")
        else:
            self.stack.pop()
            if tag == "section":
                self.section = None

    def handle_data(self, data):
        if self.section is not None:
            self.sections[self.section] += data

    def handle_entityref(self, name):
        if name not in ("amp", "lt", "gt", "quot"):
            self.errors.append(f"unknown reference &{name};")
        self.handle_data(html.unescape(f"&{name};"))

    def handle_charref(self, name):
        self.handle_data(html.unescape(f"&#{name};"))


def parse(page):
    parser = StrictParser()
    parser.feed(page)
    parser.close()
    check(parser.doctype, "no <!DOCTYPE html>")
    check(not parser.stack, f"elements left open: {parser.stack}")
    check(not parser.errors, f"markup errors: {parser.errors[:5]}")
    for tag in ("html", "head", "body", "title"):
        check(parser.counts.get(tag) == 1, f"{parser.counts.get(tag, 0)} <{tag}> elements")
    check("script" not in parser.counts, "the report has a script")
    check(not re.search(r"&(?!(amp|lt|gt|quot|#\d+);)", page), "a bare & in the page")
    return parser


def decode_png(data):
    """Decodes a non-interlaced 8-bit PNG by the spec (PNG 1.2): returns (width, height, channels, pixels)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "no PNG signature"
    at, chunks = 8, []
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        crc, = struct.unpack(">I", data[at + 8 + length:at + 12 + length])
        assert zlib.crc32(kind + body) == crc, f"bad CRC in {kind}"
        chunks.append((kind, body))
        at += 12 + length
    assert chunks[0][0] == b"IHDR" and chunks[-1][0] == b"IEND", "IHDR first, IEND last"
    width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", chunks[0][1])
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
    assert depth == 8 and interlace == 0, f"depth {depth}, interlace {interlace}"
    raw = zlib.decompress(b"".join(body for kind, body in chunks if kind == b"IDAT"))
    stride = width * channels
    assert len(raw) == height * (stride + 1), f"{len(raw)} bytes of scanlines for {width}x{height}"
    pixels, previous = bytearray(), bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        assert kind <= 4, f"unknown scanline filter {kind}"
        for x in range(stride):  # PNG 1.2 section 6: None, Sub, Up, Average, Paeth
            a = line[x - channels] if x >= channels else 0
            b, c = previous[x], previous[x - channels] if x >= channels else 0
            if kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                predictor = a if pa <= pb and pa <= pc else b if pb <= pc else c
            else:
                predictor = (0, a, b, (a + b) // 2, 0)[kind]
            line[x] = (line[x] + predictor) & 255
        pixels += line
        previous = line
    return width, height, channels, bytes(pixels)


def magenta_share(channels, pixels):
    """The share of pixels in the error view's colour for corners that fail the checks."""
    count = len(pixels) // channels
    return sum(pixels[i] > 200 and pixels[i + 1] < 60 and pixels[i + 2] > 200 for i in range(0, len(pixels), channels)) / count


def run(args, env=None, expect=1):
    result = subprocess.run([tangent, "check", *args], cwd=work, env=env, capture_output=True)
    check(result.returncode == expect, f"check {' '.join(map(str, args))}: exit {result.returncode}, expected {expect}: "
          f"{result.stderr.decode(errors='replace')[-400:]}")
    return result


# The inputs.
shutil.rmtree(work, ignore_errors=True)
assets = work / "assets"
assets.mkdir(parents=True)
subprocess.run([tangent, "bake", str(source / "data/demo/sphere.gltf"), "-o", str(assets / "sphere.gltf"), "--quiet"], check=True)
subprocess.run([tangent, "bake", str(source / "data/demo/quad.gltf"), "-o", str(assets / "quad.gltf"), "--quiet"], check=True)
gltf = json.loads((assets / "sphere.gltf").read_text())
accessor = gltf["accessors"][gltf["meshes"][0]["primitives"][0]["attributes"]["TANGENT"]]
view = gltf["bufferViews"][accessor["bufferView"]]
binary = assets / gltf["buffers"][view["buffer"]]["uri"]
data = bytearray(binary.read_bytes())
stride, start = view.get("byteStride", 16), view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
for v in range(40, 60):
    x, y, z, w = struct.unpack_from("<4f", data, start + v * stride)
    struct.pack_into("<4f", data, start + v * stride, -y, x, z, w)
binary.write_bytes(bytes(data))
odd = os.fsencode(assets) + b"/odd <b>&amp; \"name\" \xff.gltf"
shutil.copyfile(assets / "sphere.gltf", odd)
(assets / "not-gltf.glb").write_bytes(b"glTF\x02\x00\x00\x00 not a binary glTF")
inputs = [pathlib.Path("assets/sphere.gltf"), pathlib.Path(os.fsdecode(odd)).relative_to(work), pathlib.Path("assets/quad.gltf")]

# The report and its JSON twin.
reports = work / "reports"
reports.mkdir()
run([*inputs, "--format", "html", "-o", "reports/report.html"])
expected = json.loads(run([*inputs, "--format", "json"]).stdout)
page = (reports / "report.html").read_text(encoding="utf-8")
parser = parse(page)

# No external URL.
check(not re.search(r"(?i)\b(https?|ftp):|url\(", page), "an external URL or url( in the report")
for attribute in re.findall(r"""(?:src|href)\s*=\s*["']([^"']*)""", page):
    check(attribute.startswith("data:image/png;base64,") or attribute.startswith("build-web/index.html?url="),
          f"an attribute leaves the page: {attribute[:80]}")
check("//" not in re.sub(r"data:image/png;base64,[A-Za-z0-9+/=]*", "", page), "// in the report")

# Every file, primitive and finding.
failing = 0
for i, file in enumerate(expected["files"]):
    text = parser.sections.get(f"file-{i}", "")
    check(file["file"] in text, f"section {i} does not name {file['file']}")
    for primitive in file["primitives"]:
        failing += bool(primitive["findings"])
        for finding in primitive["findings"]:
            for piece in (finding["check"], f"{finding['failed']} of {finding['total']} {finding['unit']}", finding["message"],
                          *(sample["detail"] for sample in finding["worst"])):
                check(piece in text, f"{file['file']}: the report lacks {piece!r}")
check(failing == 2, f"{failing} failing primitives, expected 2 (the sphere and its copy)")
check("\\xFF" in page or "\\xff" in page, "the file name that is not UTF-8 is not shown escaped")
check("<b>" not in page, "markup from a file name reached the page")

# Thumbnails.
if with_viewer:
    check(len(parser.images) == failing, f"{len(parser.images)} thumbnails for {failing} failing primitives")
    for image in parser.images:
        try:
            width, height, channels, pixels = decode_png(base64.b64decode(image["src"].split(",", 1)[1], validate=True))
            check((width, height) == (int(image["width"]), int(image["height"])),
                  f"thumbnail is {width}x{height}, the img says {image['width']}x{image['height']}")
            share = magenta_share(channels, pixels)
            print(f"thumbnail {width}x{height}: {100 * share:.1f} % of it the failing corners' magenta")
            check(share > MIN_MAGENTA_SHARE, f"the thumbnail is not framed on the failing triangles ({100 * share:.1f} % magenta)")
        except Exception as e:  # noqa: BLE001: any decoding failure is the finding
            check(False, f"a thumbnail does not decode: {e}")
else:
    check(not parser.images and "No thumbnails: tangent-view was found neither" in page, "without the viewer: no thumbnails, and why")

# The web viewer links: beside the report, build-web/index.html with the file's path from there.
links = [link for link in parser.links if link]
check(len(links) == failing, f"{len(links)} web-viewer links for {failing} failing primitives")
for link in links:
    path, _, query = link.partition("?")
    params = dict(pair.split("=", 1) for pair in query.split("&"))  # raw: the file name is bytes, not UTF-8
    check(path == "build-web/index.html" and params.get("view") == "error", f"link {link}")
    target = (reports / "build-web" / os.fsdecode(urllib.parse.unquote_to_bytes(params["url"]))).resolve()
    check(target in [(work / p).resolve() for p in inputs], f"link {link} reaches {target}, no input")

# Without thumbnails: the report is still written, and says why.
for label, change, reason in (("turned off", {"TANGENT_VIEW": ""}, "thumbnails are turned off"),
                              ("missing", {"TANGENT_VIEW": str(work / "no-such-viewer")}, "is not an executable file"),
                              ("no display", {"DISPLAY": "", "PATH": str(work / "empty")}, "no display")):
    if label == "no display" and not with_viewer:
        continue
    env = {**os.environ, **change}
    (reports / "plain.html").unlink(missing_ok=True)
    run([*inputs, "--format", "html", "-o", "reports/plain.html"], env=env)
    plain = (reports / "plain.html").read_text(encoding="utf-8")
    parse(plain)
    check("<img" not in plain and f"No thumbnails: " in plain and reason in plain, f"{label}: the report does not say {reason!r}")

# An unreadable file: exit 2, the report written with its error; standard output by default.
result = run(["assets/not-gltf.glb", "assets/quad.gltf", "--format", "html"], expect=2)
out = result.stdout.decode()
parse(out)
check("unreadable" in out and "not-gltf.glb" in out, "the unreadable file is not reported")

print("all passed" if not failures else f"{len(failures)} failed")
sys.exit(1 if failures else 0)
