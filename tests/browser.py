# SPDX-License-Identifier: BSD-2-Clause
"""A page opened in headless Chromium (Debian's `chromium`), driven over the Chrome DevTools protocol with
websocket-client: load a file offline, wait for its plots to draw, take a screenshot, and report the
console errors, the exceptions, any network request and what the plots drew."""

from __future__ import annotations

import base64
import itertools
import json
import os
import shutil
import subprocess
import tempfile
import time
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path
from typing import List, Optional

import pytest

# what the page's Plotly plots drew: per plot div, the points of its data and the drawn line paths
PLOTS_JS = """(() => Array.from(document.querySelectorAll('.js-plotly-plot')).map(g => ({
    points: (g._fullData || []).reduce((n, t) => n + (t._length || 0), 0),
    drawn: g.querySelectorAll('.scatterlayer .trace path.js-line').length
})))()"""


def chromium() -> Optional[str]:
    return shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")


def require_chromium() -> str:
    """The browser, or a skip with the reason; in CI (CI set) a missing browser fails: .ci/run installs it."""
    path = chromium()
    if path is None:
        if os.environ.get("CI"):
            pytest.fail("headless Chromium is missing in CI: .ci/run installs Debian's chromium")
        pytest.skip("headless Chromium is not installed (apt-get install chromium): the HTML pages are not opened")
    return path


@dataclass
class Page:
    errors: List[str] = field(default_factory=list)
    requests: List[str] = field(default_factory=list)
    plots: List[dict] = field(default_factory=list)
    text: str = ""


def open_page(path: Path, screenshot: Path, timeout: float = 60) -> Page:
    """Loads path in a fresh headless Chromium (no network needed), waits until every plot has drawn (or
    timeout), writes a PNG screenshot, and returns what the page said and drew."""
    import websocket

    profile = tempfile.mkdtemp(prefix="pmdfmu-chromium-")
    proc = subprocess.Popen(
        [
            require_chromium(),
            "--headless=new",
            "--no-sandbox",  # root in CI's container
            "--disable-gpu",
            "--no-first-run",
            "--disable-extensions",
            "--window-size=1400,1000",
            "--remote-debugging-port=0",
            f"--user-data-dir={profile}",
            "about:blank",
        ],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        # ./dev sanitize preloads ASan's runtimes for Python: not for the browser, which they keep from starting
        env={k: v for k, v in os.environ.items() if k != "LD_PRELOAD"},
    )
    try:
        port_file, end = Path(profile) / "DevToolsActivePort", time.monotonic() + timeout
        while not port_file.exists() or not port_file.read_text().strip():
            if time.monotonic() > end or proc.poll() is not None:
                raise RuntimeError(f"chromium did not start its DevTools endpoint (exit {proc.poll()})")
            time.sleep(0.1)
        port = int(port_file.read_text().split()[0])
        targets = json.load(urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=10))
        url = next(t["webSocketDebuggerUrl"] for t in targets if t["type"] == "page")
        ws = websocket.create_connection(url, timeout=timeout, suppress_origin=True)
        page, ids, events = Page(), itertools.count(1), []

        def call(method, **params):
            n = next(ids)
            ws.send(json.dumps({"id": n, "method": method, "params": params}))
            while True:
                message = json.loads(ws.recv())
                if message.get("id") == n:
                    if "error" in message:
                        raise RuntimeError(f"{method}: {message['error']}")
                    return message.get("result", {})
                events.append(message)

        def collect():
            for m in events:
                method, p = m.get("method"), m.get("params", {})
                if method == "Runtime.exceptionThrown":
                    page.errors.append(json.dumps(p["exceptionDetails"])[:500])
                elif method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
                    page.errors.append(" ".join(str(a.get("value", a.get("description"))) for a in p["args"]))
                elif method == "Log.entryAdded" and p["entry"]["level"] == "error":
                    page.errors.append(p["entry"]["text"])
                elif method == "Network.requestWillBeSent" and not p["request"]["url"].startswith(("file:", "data:")):
                    page.requests.append(p["request"]["url"])
            events.clear()

        for domain in ("Page", "Runtime", "Log", "Network"):
            call(f"{domain}.enable")
        call("Page.navigate", url=Path(path).resolve().as_uri())
        while not any(m.get("method") == "Page.loadEventFired" for m in events):
            if time.monotonic() > end:
                raise RuntimeError(f"{path}: the page did not load in {timeout} s")
            events.append(json.loads(ws.recv()))
        while True:  # Plotly draws after load: until every plot has drawn its lines
            plots = call("Runtime.evaluate", expression=PLOTS_JS, returnByValue=True)["result"]["value"]
            if (plots and all(p["drawn"] for p in plots)) or time.monotonic() > end:
                break
            time.sleep(0.2)
        page.plots = plots
        page.text = call("Runtime.evaluate", expression="document.body.innerText", returnByValue=True)["result"][
            "value"
        ]
        shot = call("Page.captureScreenshot", format="png", captureBeyondViewport=False)
        screenshot.write_bytes(base64.b64decode(shot["data"]))
        collect()
        ws.close()
        return page
    finally:
        proc.kill()
        proc.wait()
        shutil.rmtree(profile, ignore_errors=True)
