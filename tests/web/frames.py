# SPDX-License-Identifier: MIT
"""What the web viewer's tests compare: PNGs (read and written with the standard library), the
desktop viewer's screenshot of the same file and options, and the per-pixel tolerance between
the two software rasterisers (tests/web/web_viewer_test.py says how it was chosen)."""
import struct
import subprocess
import zlib

SIZE = (320, 240)
CHANNEL_TOLERANCE = 12      # of 255: a pixel differs when any channel is off by more
MAX_DIFFERING = 0.01        # fraction of pixels that may differ
MAX_MEAN = 1.5              # mean absolute channel difference, of 255


def compare(a, b):
    """(fraction of pixels differing by more than CHANNEL_TOLERANCE, mean channel difference)."""
    differing, total = 0, 0
    pixels = len(a) // 4
    for p in range(pixels):
        d = max(abs(a[4 * p + c] - b[4 * p + c]) for c in range(3))
        total += abs(a[4 * p] - b[4 * p]) + abs(a[4 * p + 1] - b[4 * p + 1]) + abs(a[4 * p + 2] - b[4 * p + 2])
        differing += d > CHANNEL_TOLERANCE
    return differing / pixels, total / (3 * pixels)


def matches(a, b, limits=(MAX_DIFFERING, MAX_MEAN)):
    """Whether two frames agree within the tolerance; also (differing, mean) for the message."""
    differing, mean = compare(a, b)
    return differing <= limits[0] and mean <= limits[1], differing, mean


def desktop_screenshot(tangent_view, xvfb_run, asset, options, out):
    """tangent-view ASSET --screenshot OUT at SIZE without MSAA, under Xvfb: width, height, RGBA."""
    command = [xvfb_run, "-a", "-s", "-screen 0 1280x1024x24", tangent_view, str(asset), "--screenshot", str(out),
               "--size", f"{SIZE[0]}x{SIZE[1]}", *options, "--msaa", "0"]
    result = subprocess.run(command, capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: {result.stderr}")
    return read_png(out)


def read_png(path):
    """8-bit RGB or RGBA, not interlaced (what tangent-view writes): width, height, RGBA rows top first."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, chunks, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            chunks += body
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        raise ValueError(f"{path}: only 8-bit RGB/RGBA PNGs without interlacing are read here")
    channels = 4 if colour == 6 else 3
    raw, stride = zlib.decompress(chunks), width * channels
    out, previous = bytearray(), bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up, upleft = previous[i], previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - upleft
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - upleft)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else upleft)) & 255
        previous = line
        if channels == 4:
            out += line
        else:
            for x in range(width):
                out += line[x * 3:x * 3 + 3] + b"\xff"
    return width, height, bytes(out)


def png_bytes(width, height, rgba):
    """RGBA rows top first as a PNG file's bytes (filter 0)."""
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    rows = b"".join(b"\0" + rgba[y * width * 4:(y + 1) * width * 4] for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def write_png(path, width, height, rgba):
    """RGBA rows top first into a PNG file."""
    with open(path, "wb") as out:
        out.write(png_bytes(width, height, rgba))


def report(failures, broken):
    """Prints each failure; the exit code of a browser test (--break: failures are expected)."""
    for failure in failures:
        print("FAIL:", failure)
    if broken:
        print("(--break: failures expected)")
    return 1 if failures else 0
