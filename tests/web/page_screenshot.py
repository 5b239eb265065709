# SPDX-License-Identifier: MIT
"""The web viewer's page as headless Chromium shows it (controls and canvas), for the README:
serves build-web/ with an asset folder beside it, opens index.html?url=..., waits for "ready"
and writes a PNG of the whole page. Used by scripts/web-image.sh.
Usage: page_screenshot.py BUILD_WEB ASSET_FOLDER FILE OUT.png [VIEW]"""
import base64
import pathlib
import shutil
import sys
import tempfile
import urllib.parse

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent / "browser"))
import chromium  # noqa: E402  (tests/browser/chromium.py)


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    build_web, assets, name, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3], pathlib.Path(sys.argv[4])
    view = sys.argv[5] if len(sys.argv) > 5 else "lit"
    site = pathlib.Path(tempfile.mkdtemp(prefix="tangent-web-shot-"))
    shutil.copytree(build_web, site / "web", ignore=shutil.ignore_patterns("cmake"))
    shutil.copytree(assets, site / "assets")
    try:
        with chromium.serve(site) as base, chromium.Browser(window=(720, 640), timeout=120) as chrome:
            query = urllib.parse.urlencode({"url": f"../assets/{name}", "view": view, "size": "704x440", "msaa": "4"})
            page = chrome.open(base + "web/index.html?" + query)
            page.call("Emulation.setDeviceMetricsOverride", width=720, height=640, deviceScaleFactor=1, mobile=False)
            state = page.wait_state()
            if state != "ready":
                sys.exit(f"{name}: page state {state!r}")
            shot = page.call("Page.captureScreenshot", format="png")
            out.write_bytes(base64.b64decode(shot["data"]))
            print(f"wrote {out}")
    finally:
        shutil.rmtree(site, ignore_errors=True)


if __name__ == "__main__":
    main()
