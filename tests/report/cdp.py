"""A tiny Chrome DevTools Protocol client (tornado's websocket client, installed with distributed)
to check a page in headless chromium: load it, then report every image's naturalWidth, every audio
element's readyState/error, and the console errors, exceptions and failed loads the browser logs.
Used by tests/report/test_html.py; ``find_chromium()`` is None when chromium is not installed."""
from __future__ import annotations

import asyncio
import json
import shutil
import socket
import subprocess
import tempfile
import time
import urllib.request
from pathlib import Path

CHECK_JS = """
(async () => {
  const audios = Array.from(document.querySelectorAll('audio'));
  await Promise.all(audios.map(a => new Promise(res => {
    if (a.readyState >= 1 || a.error) return res();
    a.addEventListener('loadedmetadata', res, {once: true});
    a.addEventListener('error', res, {once: true});
    a.load();
    setTimeout(res, 8000);
  })));
  await Promise.all(Array.from(document.images).map(i => i.decode().catch(() => null)));
  return JSON.stringify({
    title: document.title,
    first: document.body.firstElementChild ? document.body.firstElementChild.tagName : null,
    blockquote_index: Array.from(document.body.children).findIndex(e => e.tagName === 'BLOCKQUOTE'),
    images: Array.from(document.images).map(i => ({src: i.src.slice(0, 40), complete: i.complete,
                                                   naturalWidth: i.naturalWidth})),
    audio: audios.map(a => ({readyState: a.readyState, error: a.error ? a.error.code : null,
                             duration: a.duration})),
  });
})()
"""


def find_chromium() -> str | None:
    for name in ("chromium", "chromium-browser", "google-chrome"):
        if shutil.which(name):
            return shutil.which(name)
    return None


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _page_ws(port: int, proc, timeout: float) -> str:
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        if proc.poll() is not None:
            raise RuntimeError(f"chromium exited with {proc.returncode}")
        try:
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=2) as r:
                pages = [t for t in json.load(r) if t.get("type") == "page" and t.get("webSocketDebuggerUrl")]
            if pages:
                return pages[0]["webSocketDebuggerUrl"]
        except OSError:
            pass
        time.sleep(0.2)
    raise TimeoutError("chromium's DevTools endpoint did not come up")


async def _inspect(ws_url: str, url: str, timeout: float) -> dict:
    from tornado.websocket import websocket_connect

    conn = await websocket_connect(ws_url, max_message_size=64 * 1024 * 1024)
    events, counter = [], [0]

    async def call(method, **params):
        counter[0] += 1
        mid = counter[0]
        conn.write_message(json.dumps({"id": mid, "method": method, "params": params}))
        while True:
            msg = await asyncio.wait_for(conn.read_message(), timeout)
            if msg is None:
                raise RuntimeError("DevTools connection closed")
            data = json.loads(msg)
            if data.get("id") == mid:
                if "error" in data:
                    raise RuntimeError(f"{method}: {data['error']}")
                return data.get("result", {})
            events.append(data)

    async def until(name):
        while not any(e.get("method") == name for e in events):
            msg = await asyncio.wait_for(conn.read_message(), timeout)
            if msg is None:
                raise RuntimeError("DevTools connection closed")
            events.append(json.loads(msg))

    for domain in ("Runtime", "Log", "Page"):
        await call(f"{domain}.enable")
    await call("Page.navigate", url=url)
    await until("Page.loadEventFired")
    res = await call("Runtime.evaluate", expression=CHECK_JS, awaitPromise=True, returnByValue=True)
    page = json.loads(res["result"]["value"])
    try:                                     # late log entries
        while True:
            msg = await asyncio.wait_for(conn.read_message(), 0.5)
            if msg is None:
                break
            events.append(json.loads(msg))
    except asyncio.TimeoutError:
        pass
    conn.close()
    errors = []
    for e in events:
        m, p = e.get("method"), e.get("params", {})
        if m == "Runtime.exceptionThrown":
            errors.append("exception: " + p["exceptionDetails"].get("text", ""))
        elif m == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            errors.append("console." + p["type"] + ": " + " ".join(str(a.get("value", "")) for a in p.get("args", [])))
        elif m == "Log.entryAdded" and p["entry"].get("level") == "error":
            errors.append("log: " + p["entry"].get("text", ""))
    page["errors"] = errors
    return page


def inspect_page(path: Path, timeout: float = 60.0) -> dict:
    """Load ``path`` (an HTML file) in headless chromium; {'title', 'first', 'blockquote_index', 'images':
    [{src, complete, naturalWidth}], 'audio': [{readyState, error, duration}], 'errors': [...]}."""
    exe = find_chromium()
    if exe is None:
        raise FileNotFoundError("chromium is not installed")
    port = _free_port()
    with tempfile.TemporaryDirectory(ignore_cleanup_errors=True) as profile:  # chromium's helpers may still write
        proc = subprocess.Popen([exe, "--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
                                 "--mute-audio", "--autoplay-policy=no-user-gesture-required",
                                 f"--remote-debugging-port={port}", f"--user-data-dir={profile}", "about:blank"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            ws = _page_ws(port, proc, timeout)
            return asyncio.run(_inspect(ws, Path(path).resolve().as_uri(), timeout))
        finally:
            proc.terminate()
            try:
                proc.wait(10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
