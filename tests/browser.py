"""Headless Chromium for the tests, driven over the DevTools protocol on a pipe.

No Python package is needed: ``chromium --remote-debugging-pipe`` reads protocol messages (JSON,
each ended by a NUL byte) on its file descriptor 3 and answers on 4. One browser serves many
pages; real input events (keys, the mouse) go through ``Input.dispatch*``, so what the tests see
is what a user's browser does with the page.
"""
from __future__ import annotations

import base64
import fcntl
import json
import os
import shutil
import subprocess
import tempfile
import time


def find_chromium() -> str | None:
    return shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")


class Browser:
    """One headless Chromium with one tab; ``open(url)`` waits for the page's ``data-rendered``."""

    def __init__(self, exe: str, size=(1280, 900)):
        self.size = size
        self.profile = tempfile.TemporaryDirectory()
        r_ours, w_theirs = os.pipe()     # the browser writes on its fd 4
        r_theirs, w_ours = os.pipe()     # and reads on its fd 3: bash puts the pipes there
        r_theirs, w_theirs = (self._high(fd) for fd in (r_theirs, w_theirs))
        args = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                "--hide-scrollbars", f"--user-data-dir={self.profile.name}", f"--window-size={size[0]},{size[1]}",
                "--remote-debugging-pipe", "about:blank"]
        self.proc = subprocess.Popen(["bash", "-c", f'exec "$0" "$@" 3<&{r_theirs} 4>&{w_theirs}', exe, *args],
                                     pass_fds=(r_theirs, w_theirs), stdin=subprocess.DEVNULL,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(r_theirs)
        os.close(w_theirs)
        self.rf, self.wf = os.fdopen(r_ours, "rb", buffering=0), os.fdopen(w_ours, "wb", buffering=0)
        self.buf, self.n, self.events = b"", 0, []
        try:
            target = self.call("Target.createTarget", url="about:blank")["targetId"]
            self.session = self.call("Target.attachToTarget", targetId=target, flatten=True)["sessionId"]
            self.send("Page.enable")
            self.send("Runtime.enable")
            self.send("Emulation.setDeviceMetricsOverride", width=size[0], height=size[1], deviceScaleFactor=1,
                      mobile=False)
        except Exception:
            self.close()
            raise

    @staticmethod
    def _high(fd: int) -> int:
        """``fd`` moved to 10 or above, clear of the 3 and 4 that the redirections write (bash reads
        fds of two digits; dash does not)."""
        high = fcntl.fcntl(fd, fcntl.F_DUPFD, 10)
        os.close(fd)
        return high

    # -- the protocol ------------------------------------------------------------------------------
    def _read(self) -> dict:
        while b"\0" not in self.buf:
            chunk = self.rf.read(1 << 16)
            if not chunk:
                raise RuntimeError("chromium closed the protocol pipe")
            self.buf += chunk
        msg, self.buf = self.buf.split(b"\0", 1)
        return json.loads(msg)

    def call(self, method: str, _session: str | None = None, **params) -> dict:
        self.n += 1
        msg = {"id": self.n, "method": method, "params": params}
        if _session:
            msg["sessionId"] = _session
        self.wf.write(json.dumps(msg).encode() + b"\0")
        while True:
            m = self._read()
            if m.get("id") == self.n:
                if "error" in m:
                    raise RuntimeError(f"{method}: {m['error']}")
                return m.get("result", {})
            self.events.append(m)

    def send(self, method: str, **params) -> dict:
        """A command to the tab."""
        return self.call(method, self.session, **params)

    def js(self, expr: str):
        r = self.send("Runtime.evaluate", expression=expr, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in r:
            raise RuntimeError(r["exceptionDetails"].get("text", "exception") + ": " + expr)
        return r["result"].get("value")

    def errors(self) -> list:
        """Uncaught exceptions and console errors or warnings of the pages opened so far."""
        out = []
        for m in self.events:
            if m.get("method") == "Runtime.exceptionThrown":
                out.append(m["params"]["exceptionDetails"])
            elif m.get("method") == "Runtime.consoleAPICalled" and \
                    m["params"]["type"] in ("error", "warning", "assert"):
                out.append(m["params"])
        return out

    # -- what the tests do ------------------------------------------------------------------------
    def open(self, url: str, timeout: float = 30.0) -> None:
        """Go to ``url`` (another page, or the same page at another fragment) and wait until its
        script has drawn (``document.body.dataset.rendered`` set anew)."""
        try:
            self.js("document.body && delete document.body.dataset.rendered")
        except RuntimeError:
            pass
        self.send("Page.navigate", url=url)
        self.wait("document.readyState === 'complete' && !!document.body && 'rendered' in document.body.dataset",
                  timeout)

    def wait(self, expr: str, timeout: float = 30.0):
        end = time.monotonic() + timeout
        while True:
            try:
                v = self.js(expr)
                if v:
                    return v
            except RuntimeError:
                pass
            if time.monotonic() > end:
                raise TimeoutError(expr)
            time.sleep(0.02)

    def dom(self) -> str:
        return self.js("document.documentElement.outerHTML")

    def screenshot(self) -> bytes:
        return base64.b64decode(self.send("Page.captureScreenshot", format="png")["data"])

    def key(self, key: str, code: int, shift: bool = False) -> None:
        mods = 8 if shift else 0
        for kind in ("keyDown", "keyUp"):
            self.send("Input.dispatchKeyEvent", type=kind, key=key, code=key, windowsVirtualKeyCode=code,
                      modifiers=mods)

    def mouse(self, kind: str, x: float, y: float) -> None:
        """kind: 'mouseMoved', or 'click' (pressed and released)."""
        if kind == "click":
            for t in ("mousePressed", "mouseReleased"):
                self.send("Input.dispatchMouseEvent", type=t, x=x, y=y, button="left", clickCount=1)
        else:
            self.send("Input.dispatchMouseEvent", type=kind, x=x, y=y)

    def close(self) -> None:
        try:
            self.call("Browser.close")
        except Exception:
            pass
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait(10)
        for f in (self.rf, self.wf):
            try:
                f.close()
            except OSError:
                pass
        self.profile.cleanup()
