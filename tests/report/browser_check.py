#!/usr/bin/env python3
"""The HTML report in a real browser: headless Chromium (Debian's `chromium`, installed by
scripts/setup.sh) loads a report's index.html over HTTP, and in the page itself every
<img> must have loaded (naturalWidth > 0) and every link must answer 200 (a HEAD by the
page's fetch); a screenshot at each of two widths (1280 and 420 px) must not be blank, and
the page must fit the narrow width (wide tables scroll inside their box).

Usage:
  browser_check.py REPORT_DIR [--screenshots DIR]
      exit 0: all good; 1: the problems, one a line; 2: cannot run (no Chromium, ...)
  browser_check.py --self-test --ldmbench PATH [--screenshots DIR]
      makes a small run and its report, checks it passes, then breaks a copy (one figure
      removed, one linked file removed) and checks that both are reported: the check can fail.

Chromium is driven through its DevTools protocol on a pipe (--remote-debugging-pipe: JSON
messages ending in NUL on file descriptors 3 and 4), so that nothing but the standard
library and matplotlib (to read the screenshots) is needed."""
import argparse
import base64
import functools
import http.server
import io
import json
import os
import select
import shutil
import subprocess
import sys
import tempfile
import threading
import time

WIDTHS = (1280, 420)
HEIGHT = 900
TIMEOUT_S = 60
CHROMIUM_CANDIDATES = ("chromium", "chromium-browser", "google-chrome")

PAGE_CHECK = """(async () => {
  const out = {images: [], links: [], scrollWidth: document.documentElement.scrollWidth,
               title: document.title, text: document.body ? document.body.innerText.length : 0};
  for (const img of Array.from(document.images)) {
    if (!img.complete) await new Promise(r => { img.onload = img.onerror = r; });
    out.images.push({src: img.getAttribute('src'), ok: img.naturalWidth > 0});
  }
  for (const a of Array.from(document.querySelectorAll('a[href]'))) {
    let status = -1;
    try { status = (await fetch(a.href, {method: 'HEAD', cache: 'no-store'})).status; } catch (e) {}
    out.links.push({href: a.getAttribute('href'), status: status});
  }
  return out;
})()"""


class CannotRun(Exception):
    """No browser, or it did not answer: not a finding about the report."""


def find_chromium():
    for name in CHROMIUM_CANDIDATES:
        path = shutil.which(name)
        if path:
            return path
    raise CannotRun("no chromium on PATH (scripts/setup.sh installs Debian's chromium)")


class Browser:
    """Headless Chromium and one page, spoken to over the DevTools pipe."""

    def __init__(self):
        self.profile = tempfile.mkdtemp(prefix="ldm-browser-")
        to_browser_r, self.to_browser = os.pipe()
        self.from_browser, from_browser_w = os.pipe()
        chromium = find_chromium()
        args = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                "--disable-extensions", "--hide-scrollbars", "--disable-dev-shm-usage", "--remote-debugging-pipe",
                f"--user-data-dir={self.profile}", "about:blank"]
        # the pipe ends as the protocol wants them: 3 read by the browser, 4 written by it
        self.process = subprocess.Popen(
            ["/bin/sh", "-c", f'exec "$0" "$@" 3<&{to_browser_r} 4>&{from_browser_w}', chromium] + args,
            pass_fds=(to_browser_r, from_browser_w), stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL)
        os.close(to_browser_r)
        os.close(from_browser_w)
        self.buffer, self.next_id, self.events = b"", 0, []
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        self.session = self.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        self.call("Page.enable", session=True)

    def send(self, method, params, session):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = self.session
        os.write(self.to_browser, json.dumps(message).encode() + b"\0")
        return self.next_id

    def receive(self, deadline):
        while b"\0" not in self.buffer:
            left = deadline - time.monotonic()
            if left <= 0 or not select.select([self.from_browser], [], [], left)[0]:
                raise CannotRun("chromium did not answer within "
                                f"{TIMEOUT_S} s (DevTools pipe)")
            chunk = os.read(self.from_browser, 1 << 20)
            if not chunk:
                raise CannotRun("chromium closed the DevTools pipe (did it start?)")
            self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)

    def call(self, method, params=None, session=False):
        wanted = self.send(method, params, session)
        deadline = time.monotonic() + TIMEOUT_S
        while True:
            message = self.receive(deadline)
            if message.get("id") == wanted:
                if "error" in message:
                    raise CannotRun(f"{method}: {message['error']}")
                return message.get("result", {})
            if "method" in message:
                self.events.append(message)

    def wait_for(self, event):
        deadline = time.monotonic() + TIMEOUT_S
        while True:
            for k, message in enumerate(self.events):
                if message.get("method") == event:
                    del self.events[:k + 1]
                    return message
            self.events.append(self.receive(deadline))

    def open(self, url, width):
        self.call("Emulation.setDeviceMetricsOverride",
                  {"width": width, "height": HEIGHT, "deviceScaleFactor": 1, "mobile": width < 600},
                  session=True)
        self.events.clear()
        self.call("Page.navigate", {"url": url}, session=True)
        self.wait_for("Page.loadEventFired")

    def evaluate(self, expression):
        result = self.call("Runtime.evaluate", {"expression": expression, "awaitPromise": True,
                                                "returnByValue": True}, session=True)
        if "exceptionDetails" in result:
            raise CannotRun(f"the page check threw: {result['exceptionDetails']}")
        return result["result"]["value"]

    def screenshot(self):
        return base64.b64decode(self.call("Page.captureScreenshot", {"format": "png"}, session=True)["data"])

    def close(self):
        try:
            self.send("Browser.close", {}, session=False)
            self.process.wait(timeout=10)
        except Exception:
            self.process.kill()
        for fd in (self.to_browser, self.from_browser):
            os.close(fd)
        shutil.rmtree(self.profile, ignore_errors=True)


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def serve(folder):
    """The report over HTTP on a free local port (as a web server or a CI artefact viewer
    would serve it; links then fail with 404 rather than a browser's file:// rules)."""
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0),
                                             functools.partial(QuietHandler, directory=folder))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server


def blank(png_bytes):
    """Whether a screenshot shows (almost) nothing: fewer than 2 % of its pixels differ
    from its most common colour."""
    import matplotlib.image as mpimg
    import numpy as np
    pixels = (mpimg.imread(io.BytesIO(png_bytes), format="png")[..., :3] * 255).astype(np.uint8)
    flat = pixels.reshape(-1, 3)
    colours, counts = np.unique(flat, axis=0, return_counts=True)
    return 1 - counts.max() / len(flat) < 0.02


def check_report(folder, screenshots=None):
    """The problems of the report in `folder`, one line each (empty: all good)."""
    if not os.path.isfile(os.path.join(folder, "index.html")):
        return [f"{folder}: no index.html"]
    problems = []
    server = serve(folder)
    browser = Browser()
    try:
        url = f"http://127.0.0.1:{server.server_address[1]}/index.html"
        for width in WIDTHS:
            browser.open(url, width)
            page = browser.evaluate(PAGE_CHECK)
            if width == WIDTHS[0]:
                if not page["images"]:
                    problems.append("index.html shows no image")
                problems += [f"image not loaded: {i['src']}" for i in page["images"] if not i["ok"]]
                problems += [f"broken link: {l['href']} (HTTP {l['status']})"
                             for l in page["links"] if l["status"] != 200]
            elif page["scrollWidth"] > width + 1:
                problems.append(f"at {width} px the page is {page['scrollWidth']} px wide "
                                "(something does not shrink or scroll in its box)")
            shot = browser.screenshot()
            if screenshots:
                os.makedirs(screenshots, exist_ok=True)
                with open(os.path.join(screenshots, f"report-{width}px.png"), "wb") as f:
                    f.write(shot)
            if blank(shot):
                problems.append(f"the screenshot at {width} px is blank")
        print(f"browser: {len(page['images'])} images, {len(page['links'])} links checked at "
              f"widths {', '.join(map(str, WIDTHS))} px")
    finally:
        browser.close()
        server.shutdown()
    return problems


def self_test(ldmbench, screenshots):
    """A real report must pass, and the same report with one figure and one linked file
    removed must fail naming both."""
    work = tempfile.mkdtemp(prefix="ldm-browser-report-")
    run, report = os.path.join(work, "run"), os.path.join(work, "report")
    for args in (["run", "--scene", "cornell", "--structure", "psppsll", "--pass", "ao,hbao",
                  "-N", "4,8", "-R", "32", "--width", "32", "--height", "32", "--frames", "2",
                  "--warmup", "1", "--reference-spp", "16", "--cache-dir",
                  os.path.join(work, "cache"), "--out", run],
                 ["report", run, "--out", report, "--format", "png,svg,pdf"]):
        done = subprocess.run([ldmbench] + args, capture_output=True, text=True)
        if done.returncode != 0:
            raise CannotRun(f"ldmbench {args[0]} failed: {done.stdout}{done.stderr}")
    problems = check_report(report, screenshots)
    if problems:
        return ["the real report: " + p for p in problems]
    broken = os.path.join(work, "broken")
    shutil.copytree(report, broken)
    with open(os.path.join(broken, "manifest.json")) as f:
        shown = [p for fig in json.load(f)["figures"] for p in fig["files"] if p.endswith(".svg")]
    os.remove(os.path.join(broken, shown[0]))
    os.remove(os.path.join(broken, "tidy.csv"))
    found = check_report(broken)
    expected = [f"image not loaded: {shown[0]}", "broken link: tidy.csv (HTTP 404)"]
    missed = [e for e in expected if e not in found]
    shutil.rmtree(work, ignore_errors=True)
    if missed:
        return [f"the broken report passed where it should not: {m} not reported (got: {found})"
                for m in missed]
    print(f"browser: a broken copy is caught: {'; '.join(found)}")
    return []


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("report", nargs="?", help="a report folder (index.html inside)")
    parser.add_argument("--self-test", action="store_true")
    parser.add_argument("--ldmbench", help="the ldmbench binary (with --self-test)")
    parser.add_argument("--screenshots", help="where to keep the screenshots")
    args = parser.parse_args(argv)
    try:
        if args.self_test:
            if not args.ldmbench:
                parser.error("--self-test needs --ldmbench PATH")
            problems = self_test(args.ldmbench, args.screenshots)
        elif args.report:
            problems = check_report(args.report, args.screenshots)
        else:
            parser.error("give a report folder or --self-test")
    except CannotRun as e:
        print(f"browser_check: cannot run: {e}", file=sys.stderr)
        return 2
    for p in problems:
        print(f"browser_check: {p}", file=sys.stderr)
    if not problems:
        print("browser_check: OK")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
