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

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import browser  # noqa: E402


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    build_web, assets, name, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3], pathlib.Path(sys.argv[4])
    view = sys.argv[5] if len(sys.argv) > 5 else "lit"
    site = pathlib.Path(tempfile.mkdtemp(prefix="tangent-web-shot-"))
    shutil.copytree(build_web, site / "web", ignore=shutil.ignore_patterns("cmake"))
    shutil.copytree(assets, site / "assets")
    server, chrome = browser.Server(site), browser.Browser(width=720, height=640)
    try:
        query = urllib.parse.urlencode({"url": f"../assets/{name}", "view": view, "size": "704x440", "msaa": "4"})
        session = chrome.open(server.url + "web/index.html?" + query)
        chrome.send("Emulation.setDeviceMetricsOverride", {"width": 720, "height": 640, "deviceScaleFactor": 1, "mobile": False},
                    session=session)
        state = chrome.wait_state(session)
        if state != "ready":
            sys.exit(f"{name}: page state {state!r}")
        shot = chrome.send("Page.captureScreenshot", {"format": "png"}, session=session)
        out.write_bytes(base64.b64decode(shot["data"]))
        print(f"wrote {out}")
    finally:
        chrome.close()
        server.close()
        shutil.rmtree(site, ignore_errors=True)


if __name__ == "__main__":
    main()
