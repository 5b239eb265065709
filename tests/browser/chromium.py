# SPDX-License-Identifier: MIT
"""Headless Chromium for the browser tests (tests/browser: the npm package and its example page;
tests/web: the web viewer; scripts/web-image.sh), from the standard library only.

serve(root) serves a folder on 127.0.0.1 (an ephemeral port) with the MIME types browsers insist
on for modules and WebAssembly; Browser() starts Debian's chromium headless (WebGL2 through
SwiftShader) and talks to it over the DevTools protocol on a pipe (--remote-debugging-pipe:
JSON messages, each ended by a NUL byte, commands on fd 3, replies and events on fd 4).
Pages report through the DOM (document.body.dataset); Page.wait_for polls an expression,
Page.wait_state waits for the web viewer's "ready" or "error: ...", Page.read_pixels reads its frame.
"""
import base64
import contextlib
import functools
import http.server
import json
import os
import queue
import shutil
import subprocess
import tempfile
import threading
import time

CHROMIUM_FLAGS = ["--headless=new", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                  "--disable-gpu-sandbox", "--no-first-run", "--no-default-browser-check", "--disable-extensions", "--mute-audio"]


def find_chromium():
    for name in ("chromium", "chromium-browser"):
        path = shutil.which(name)
        if path:
            return path
    return None


class _Handler(http.server.SimpleHTTPRequestHandler):
    # What a static host sends: .mjs/.js as JavaScript, .wasm as application/wasm (the one
    # type WebAssembly.instantiateStreaming accepts). .cjs keeps Python's default on purpose.
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map,
                      ".js": "text/javascript", ".mjs": "text/javascript", ".wasm": "application/wasm",
                      ".json": "application/json", ".glb": "model/gltf-binary", ".gltf": "model/gltf+json"}

    def log_message(self, format, *args):  # quiet: failures show in the page's own report
        pass


class _IsolatedHandler(_Handler):
    # Cross-origin isolation (COOP/COEP), without which a page has no SharedArrayBuffer and so
    # no WebAssembly threads.
    def end_headers(self):
        self.send_header("Cross-Origin-Opener-Policy", "same-origin")
        self.send_header("Cross-Origin-Embedder-Policy", "require-corp")
        super().end_headers()


@contextlib.contextmanager
def serve(root, isolated=False):
    """Serves `root` on 127.0.0.1 (cross-origin isolated where asked); yields the base URL (ending in '/')."""
    handler = _IsolatedHandler if isolated else _Handler
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(handler, directory=str(root)))
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()


class ProtocolError(RuntimeError):
    pass


class Page:
    """One tab, attached in flat mode: its commands carry the session id."""

    def __init__(self, browser, session, target=None):
        self.browser, self.session, self.target = browser, session, target
        self.console = []  # console messages and uncaught exceptions, for failure messages

    def call(self, method, **params):
        return self.browser.call(method, params, self.session)

    def evaluate(self, expression):
        """The expression's value (awaited when it is a promise), as JSON-able data."""
        reply = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in reply:
            details = reply["exceptionDetails"]
            raise ProtocolError(f"{expression}: {details.get('exception', {}).get('description') or details.get('text')}")
        return reply["result"].get("value")

    def wait_for(self, expression, timeout, interval=0.1):
        """Polls until `expression` is truthy; returns its value, or raises with the page's console."""
        deadline = time.monotonic() + timeout
        while True:
            value = self.evaluate(expression)
            if value:
                return value
            if time.monotonic() > deadline:
                raise TimeoutError(f"after {timeout} s still falsy: {expression}\npage console:\n  " + "\n  ".join(self.console))
            time.sleep(interval)

    def wait_state(self, timeout=120):
        """The web viewer's page (viewer/web/index.html): waits until document.body.dataset.state is
        "ready" or begins with "error"; returns it."""
        return self.wait_for("(s => s === 'ready' || s.startsWith('error') ? s : null)"
                             "(document.body ? document.body.dataset.state || '' : '')", timeout, interval=0.05)

    def read_pixels(self):
        """The web viewer's frame drawn now (tangent_web_read_pixels): width, height, RGBA rows top first."""
        answer = self.evaluate("""(() => {
            const p = Module._tangent_web_read_pixels(), w = Module.canvas.width, h = Module.canvas.height;
            const bytes = Module.HEAPU8.subarray(p, p + w * h * 4);
            let s = ""; for (let i = 0; i < bytes.length; i += 32768) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 32768));
            return {w, h, data: btoa(s)}; })()""")
        width, height, raw = answer["w"], answer["h"], base64.b64decode(answer["data"])
        row = width * 4
        return width, height, b"".join(raw[(height - 1 - y) * row:(height - y) * row] for y in range(height))

    def close(self):
        """Closes the tab (a test that opens many pages frees each one's WebAssembly memory)."""
        self.browser.call("Target.closeTarget", {"targetId": self.target})
        self.browser._pages.pop(self.session, None)

    def set_input_files(self, selector, paths):
        """What choosing files in an <input type=file> does (DOM.setFileInputFiles fires change)."""
        root = self.call("DOM.getDocument")["root"]["nodeId"]
        node = self.call("DOM.querySelector", nodeId=root, selector=selector)["nodeId"]
        if not node:
            raise ProtocolError(f"no element matches {selector}")
        self.call("DOM.setFileInputFiles", nodeId=node, files=[str(p) for p in paths])


class Browser:
    """Headless chromium driven over --remote-debugging-pipe. Use as a context manager."""

    def __init__(self, executable=None, timeout=60, window=(1280, 800)):
        self.executable = executable or find_chromium()
        self.window = window
        self.timeout = timeout
        self._next_id = 0
        self._replies = {}
        self._events = queue.Queue()
        self._lock = threading.Condition()
        self._pages = {}

    def __enter__(self):
        self._profile = tempfile.TemporaryDirectory(prefix="tangent-chromium-")
        to_browser_read, self._to_browser = os.pipe()
        self._from_browser, from_browser_write = os.pipe()

        def plumb():  # in the child: the pipe ends as fd 3 (commands in) and fd 4 (replies out)
            os.dup2(to_browser_read, 3)
            os.dup2(from_browser_write, 4)

        self._process = subprocess.Popen(
            [self.executable, *CHROMIUM_FLAGS, "--remote-debugging-pipe", f"--user-data-dir={self._profile.name}",
             f"--window-size={self.window[0]},{self.window[1]}", "about:blank"],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, preexec_fn=plumb, pass_fds=(3, 4))
        os.close(to_browser_read)
        os.close(from_browser_write)
        self._stderr = []
        threading.Thread(target=self._read_stderr, daemon=True).start()
        threading.Thread(target=self._read, daemon=True).start()
        return self

    def __exit__(self, *exc):
        try:
            self.call("Browser.close", {})
        except Exception:
            pass
        try:
            self._process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self._process.kill()
            self._process.wait()
        os.close(self._to_browser)
        self._profile.cleanup()

    def _read_stderr(self):
        for line in self._process.stderr:
            self._stderr.append(line.decode(errors="replace").rstrip())

    def _read(self):
        buffer = b""
        with os.fdopen(self._from_browser, "rb", buffering=0) as pipe:
            while True:
                chunk = pipe.read(1 << 16)
                if not chunk:
                    break
                buffer += chunk
                while b"\0" in buffer:
                    raw, buffer = buffer.split(b"\0", 1)
                    message = json.loads(raw)
                    if "id" in message:
                        with self._lock:
                            self._replies[message["id"]] = message
                            self._lock.notify_all()
                    else:
                        self._on_event(message)
        with self._lock:
            self._closed = True
            self._lock.notify_all()

    def _on_event(self, message):
        page = self._pages.get(message.get("sessionId"))
        params = message.get("params", {})
        if page is None:
            return
        if message["method"] == "Runtime.consoleAPICalled":
            text = " ".join(str(a.get("value", a.get("description", ""))) for a in params.get("args", []))
            page.console.append(f"console.{params.get('type')}: {text}")
        elif message["method"] == "Log.entryAdded":  # what the browser itself says: refused scripts, failed loads
            entry = params.get("entry", {})
            page.console.append(f"{entry.get('source')} {entry.get('level')}: {entry.get('text')} {entry.get('url', '')}".rstrip())
        elif message["method"] == "Runtime.exceptionThrown":
            details = params.get("exceptionDetails", {})
            page.console.append(f"uncaught: {details.get('exception', {}).get('description') or details.get('text')}")

    def call(self, method, params, session=None):
        with self._lock:
            self._next_id += 1
            command_id = self._next_id
        message = {"id": command_id, "method": method, "params": params}
        if session:
            message["sessionId"] = session
        os.write(self._to_browser, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + self.timeout
        with self._lock:
            while command_id not in self._replies:
                if getattr(self, "_closed", False) or time.monotonic() > deadline:
                    raise ProtocolError(f"{method}: no reply from chromium (stderr: {' | '.join(self._stderr[-5:])})")
                self._lock.wait(0.5)
            reply = self._replies.pop(command_id)
        if "error" in reply:
            raise ProtocolError(f"{method}: {reply['error'].get('message')}")
        return reply.get("result", {})

    def open(self, url):
        """A new tab on `url`, with its console collected, once loaded; returns a Page."""
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        page = Page(self, session, target)
        self._pages[session] = page
        page.call("Runtime.enable")
        page.call("Log.enable")
        page.call("Page.enable")
        page.call("Page.navigate", url=url)
        # Page.navigate answers before the new document replaces about:blank.
        page.wait_for("location.href !== 'about:blank' && document.readyState === 'complete'", self.timeout)
        return page
