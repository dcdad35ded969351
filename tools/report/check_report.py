#!/usr/bin/env python3
"""Opens an lc2wf-eval report.html in headless Chromium and prints what a test needs to know, as JSON:
console errors and uncaught exceptions, the time until the first building was rendered, pixel statistics of a
screenshot of the 3D view, and the table order before and after clicking column headers.

Talks to Chromium over the DevTools protocol through its pipe transport (--remote-debugging-pipe: commands on
fd 3, replies on fd 4, NUL-separated JSON), so it needs only the Python standard library.

  tools/report/check_report.py OUT/report.html [--chromium /usr/bin/chromium] [--timeout 60]
Exit codes: 0 the checks ran (read the JSON), 1 the browser failed, 2 bad command line.
"""
import argparse
import base64
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import zlib

FLAGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    # WebGL without a GPU: the software rasteriser, which recent Chromium enables only on request.
    "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
    "--window-size=1400,900", "--remote-debugging-pipe",
]


class Browser:
    """One headless Chromium with a fresh profile, driven over the DevTools pipe."""

    def __init__(self, chromium, timeout):
        self.timeout = timeout
        self.profile = tempfile.mkdtemp(prefix="lc2wf_chromium_")
        to_child_r, self.to_child = os.pipe()
        self.from_child, from_child_w = os.pipe()

        def wire_pipes():  # runs in the child: the protocol's fd 3 (commands) and fd 4 (replies)
            a, b = os.dup(to_child_r), os.dup(from_child_w)
            os.dup2(a, 3)
            os.dup2(b, 4)
            os.set_inheritable(3, True)
            os.set_inheritable(4, True)

        self.proc = subprocess.Popen([chromium, *FLAGS, "--user-data-dir=" + self.profile, "about:blank"],
                                     stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                     close_fds=False, preexec_fn=wire_pipes)
        os.close(to_child_r)
        os.close(from_child_w)
        self.buffer = b""
        self.next_id = 0
        self.events = []
        self.session = None

    def _read_message(self, deadline):
        while b"\0" not in self.buffer:
            if time.monotonic() > deadline:
                raise TimeoutError("no reply from Chromium")
            chunk = os.read(self.from_child, 1 << 16)
            if not chunk:
                raise RuntimeError("Chromium closed the DevTools pipe (exit code %s)" % self.proc.poll())
            self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def send(self, method, params=None, session=True):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            message["sessionId"] = self.session
        os.write(self.to_child, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + self.timeout
        while True:
            reply = self._read_message(deadline)
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise RuntimeError("%s: %s" % (method, reply["error"]))
                return reply.get("result", {})
            if "method" in reply:
                self.events.append(reply)

    def evaluate(self, expression):
        result = self.send("Runtime.evaluate", {"expression": expression, "returnByValue": True, "awaitPromise": True})
        if "exceptionDetails" in result:
            raise RuntimeError("page script failed: %s" % json.dumps(result["exceptionDetails"])[:500])
        return result["result"].get("value")

    def wait_for(self, expression, what):
        deadline = time.monotonic() + self.timeout
        while time.monotonic() < deadline:
            value = self.evaluate(expression)
            if value:
                return value
            time.sleep(0.05)
        raise TimeoutError("timed out waiting for " + what)

    def click(self, selector):
        box = self.evaluate("(() => { const r = document.querySelector(%s).getBoundingClientRect();"
                            " return [r.x + r.width / 2, r.y + r.height / 2]; })()" % json.dumps(selector))
        for kind in ("mousePressed", "mouseReleased"):
            self.send("Input.dispatchMouseEvent", {"type": kind, "x": box[0], "y": box[1], "button": "left", "clickCount": 1})

    def close(self):
        try:
            self.send("Browser.close", session=False)
        except Exception:
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        shutil.rmtree(self.profile, ignore_errors=True)


def png_pixels(data):
    """Decodes an 8-bit RGB/RGBA non-interlaced PNG (what Chromium writes) into (width, height, channels, rows)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        length = int.from_bytes(data[pos:pos + 4], "big")
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height = int.from_bytes(body[0:4], "big"), int.from_bytes(body[4:8], "big")
            depth, colour, interlace = body[8], body[9], body[12]
            assert depth == 8 and colour in (2, 6) and interlace == 0, "unsupported PNG layout"
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, prev = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):  # undo the row filter (PNG spec §9)
            a = line[x - channels] if x >= channels else 0
            b = prev[x]
            c = prev[x - channels] if x >= channels else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return width, height, channels, rows


def pixel_stats(png):
    """Share of non-background pixels, and of clearly red / green / grey / blue ones, in a screenshot (blue: the
    translucent wall faces)."""
    width, height, channels, rows = png_pixels(png)
    total = width * height
    ink = red = green = grey = blue = 0
    colours = set()
    for line in rows:
        for x in range(0, len(line), channels):
            r, g, b = line[x], line[x + 1], line[x + 2]
            colours.add((r >> 4, g >> 4, b >> 4))
            if r > 245 and g > 245 and b > 245:
                continue
            ink += 1
            if r > g + 60 and r > b + 60:
                red += 1
            elif g > r + 40 and g > b + 20:
                green += 1
            elif max(r, g, b) - min(r, g, b) < 24:
                grey += 1
            elif b > r + 30 and b > g + 15:
                blue += 1
    return {"width": width, "height": height, "ink": ink / total, "red": red / total, "green": green / total,
            "grey": grey / total, "blue": blue / total,
            "colours": len(colours)}


def canvas_stats(browser, save_as):
    """Screenshot of the 3D view (half resolution keeps the pure-Python PNG decoding quick) and its statistics."""
    # Clip coordinates are the document's: scroll the view in, then add the scroll offsets.
    rect = browser.evaluate("(() => { const c = document.querySelector('#view3d canvas'); c.scrollIntoView({block: 'center'});"
                            " const r = c.getBoundingClientRect();"
                            " return {x: r.x + scrollX, y: r.y + scrollY, width: r.width, height: r.height}; })()")
    png = base64.b64decode(browser.send("Page.captureScreenshot", {"format": "png", "clip": dict(rect, scale=0.5)})["data"])
    if save_as:
        with open(save_as, "wb") as f:
            f.write(png)
    return pixel_stats(png)


def check(report, chromium, timeout, shots=None):
    browser = Browser(chromium, timeout)
    out = {}
    try:
        target = browser.send("Target.createTarget", {"url": "about:blank"}, session=False)
        attached = browser.send("Target.attachToTarget", {"targetId": target["targetId"], "flatten": True}, session=False)
        browser.session = attached["sessionId"]
        for domain in ("Runtime.enable", "Log.enable", "Page.enable"):
            browser.send(domain)
        browser.send("Emulation.setDeviceMetricsOverride", {"width": 1400, "height": 900, "deviceScaleFactor": 1, "mobile": False})
        started = time.monotonic()
        browser.send("Page.navigate", {"url": "file://" + os.path.abspath(report)})
        out["rendered"] = browser.wait_for("document.body && document.body.dataset.rendered", "the first building")
        out["open_seconds"] = time.monotonic() - started
        out["first_render_ms"] = browser.evaluate("window.lc2wfReport.firstRenderMs")
        out["buildings"] = browser.evaluate("window.lc2wfReport.order().length")
        out["summary_rows"] = browser.evaluate("document.querySelectorAll('#summary table')[0].tBodies[0].rows.length")
        out["canvas"] = canvas_stats(browser, shots and os.path.join(shots, "first.png"))
        out["faces_first"] = int(browser.evaluate("document.body.dataset.faces || '0'"))
        out["face_summary_rows"] = browser.evaluate(
            "(() => { const h = [...document.querySelectorAll('#summary h2')].findIndex(e => e.textContent.startsWith('(d)'));"
            " return h < 0 ? 0 : document.querySelectorAll('#summary h2')[h].nextElementSibling.tBodies[0].rows.length; })()")
        # Sorting by clicking headers: name ascending, then descending; an edge-recall sort, worst first.
        out["order_initial"] = browser.evaluate("window.lc2wfReport.order()")
        browser.click("#buildings th[data-key=n]")
        out["order_name_1"] = browser.evaluate("window.lc2wfReport.order()")
        browser.click("#buildings th[data-key=n]")
        out["order_name_2"] = browser.evaluate("window.lc2wfReport.order()")
        browser.click("#buildings th[data-key=sR]")
        out["sort_sR"] = browser.evaluate("window.lc2wfReport.sortKey()")
        out["column_sR"] = browser.evaluate(
            "[...document.querySelectorAll('#buildings tbody tr')].map(tr => parseFloat(tr.children[7].textContent))")
        # Opening another building from the table: the first row not shown already.
        browser.click("#buildings tbody tr:not(.sel)")
        out["rendered_after_click"] = browser.wait_for(
            "document.body.dataset.rendered !== %s && document.body.dataset.rendered" % json.dumps(out["rendered"]),
            "the clicked building")
        out["canvas_after_click"] = canvas_stats(browser, shots and os.path.join(shots, "clicked.png"))
        out["faces_after_click"] = int(browser.evaluate("document.body.dataset.faces || '0'"))
        # The faces toggled off: their translucent colours go (they stay off, so the colours below are the lines').
        browser.click("#show-faces")
        out["canvas_faces_off"] = canvas_stats(browser, shots and os.path.join(shots, "faces_off.png"))
        # Colour by score and another threshold: the prediction is no longer drawn in plain red.
        browser.click("#by-score")
        browser.evaluate("(() => { const s = document.getElementById('eta'); s.value = '2';"
                         " s.dispatchEvent(new Event('change')); })()")
        out["canvas_by_score"] = canvas_stats(browser, shots and os.path.join(shots, "by_score.png"))
        browser.send("Runtime.evaluate", {"expression": "0"})  # flush pending events
    finally:
        browser.close()
    errors = []
    for e in browser.events:
        p = e.get("params", {})
        if e["method"] == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            errors.append("console.%s: %s" % (p["type"], " ".join(str(a.get("value", a.get("description"))) for a in p.get("args", []))))
        elif e["method"] == "Runtime.exceptionThrown":
            d = p.get("exceptionDetails", {})
            errors.append("exception: %s %s" % (d.get("text", ""), d.get("exception", {}).get("description", "")))
        elif e["method"] == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
            errors.append("log: %s" % p["entry"].get("text"))
    out["console_errors"] = errors
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("report", help="path of report.html")
    parser.add_argument("--chromium", default=shutil.which("chromium") or "/usr/bin/chromium")
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per browser step")
    parser.add_argument("--screenshots", help="folder to keep the 3D-view screenshots in (first.png, clicked.png)")
    args = parser.parse_args()
    if not os.path.isfile(args.report):
        parser.error("--report: %s does not exist" % args.report)
    if not os.access(args.chromium, os.X_OK):
        parser.error("--chromium: %s is not an executable (apt-get install chromium)" % args.chromium)
    try:
        if args.screenshots:
            os.makedirs(args.screenshots, exist_ok=True)
        result = check(args.report, args.chromium, args.timeout, args.screenshots)
    except (RuntimeError, TimeoutError, OSError) as e:
        print("check_report: %s" % e, file=sys.stderr)
        return 1
    json.dump(result, sys.stdout, indent=1)
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main())
