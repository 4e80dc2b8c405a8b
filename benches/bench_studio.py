"""The studio's edit-to-redraw latency, in a real browser: a 360-step four-bar (the template: 361 positions, first
and second order at each) edited through the page's websocket, one dimension change at a time, each waited for
until the page has drawn the new design and the browser has painted the frame after it.

    .venv/bin/python benches/bench_studio.py [--edits 60]

prints, over the edits, the median and 90th percentile of: the whole latency (edit sent -> frame painted), the
page's part (JSON parsed, the edit's changes put in, mechanism and charts drawn, the task's end and the next frame),
the server's part (run + view + changes + JSON, wall and CPU time) and the core's run. Give the load average of the
machine with the numbers (`uptime`): the wall times grow with it, the CPU times much less.
The target is 50 ms for the whole. Needs Chromium (Debian's, /usr/bin/chromium) and mechfem[studio] + playwright.
"""

from __future__ import annotations

import argparse
import shutil
import statistics
import sys

from playwright.sync_api import sync_playwright

from mechfem.studio_app.server import serve_in_thread
from mechfem.studio_app.session import Session
from mechfem.studio_app.template import four_bar

FLAGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]


def quantiles(values: list[float]) -> str:
    q = statistics.quantiles(values, n=10)
    return f"median {statistics.median(values):6.1f} ms   p90 {q[8]:6.1f} ms"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--edits", type=int, default=60)
    args = parser.parse_args()
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if chromium is None:
        print("no chromium on the PATH (make browser installs it)", file=sys.stderr)
        return 1
    running = serve_in_thread(Session(four_bar()))
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=chromium, args=FLAGS)
            page = browser.new_page(viewport={"width": 1400, "height": 1000}, bypass_csp=True)
            page.goto(running.url)
            page.wait_for_function("window.mechfemStudio && window.mechfemStudio.revision >= 0")
            # Warm-up edits (the first view builds the drawing's caches), then the measured ones.
            samples = page.evaluate(
                """async (n) => {
                  const s = window.mechfemStudio;
                  const one = (value) => new Promise((done) => {
                    const before = s.latencies.length;
                    s.send({ op: "edit", changes: { "crank.length": value } });
                    const wait = () => (s.latencies.length > before ? done(s.latencies[before]) : setTimeout(wait, 1));
                    wait();
                  });
                  for (let k = 0; k < 5; k++) await one(1.0 + 0.001 * k);
                  const out = [];
                  for (let k = 0; k < n; k++) out.push(await one(1.0 + 0.2 * Math.sin(k)));
                  return out;
                }""",
                args.edits,
            )
            browser.close()
    finally:
        running.stop()
    painted = [s["painted"] for s in samples]
    server = [s["server"] for s in samples]
    run = [s["run"] for s in samples]
    page_part = [s["painted"] - s["server"] for s in samples]
    print(f"studio edit-to-redraw, 361-position four-bar with second order, {len(samples)} edits")
    print(f"  whole (edit -> painted)  {quantiles(painted)}")
    print(f"  page (transfer, parse, draw, paint)  {quantiles(page_part)}")
    print(f"  answer arrived           {quantiles([s['arrive'] for s in samples])}")
    print(f"  design drawn             {quantiles([s['shown'] for s in samples])}")
    for part in ("parse", "charts", "show"):
        print(f"    page's {part:6s}         {quantiles([s[part] for s in samples])}")
    print(f"  page's work done         {quantiles([s['committed'] for s in samples])}")
    print(f"  next frame begins        {quantiles([s['frame'] for s in samples])}")
    print(f"  server (run + view + JSON)  {quantiles(server)}")
    print(f"    its CPU time           {quantiles([s['server_cpu'] for s in samples])}")
    print(f"  core run                 {quantiles(run)}")
    print(f"  target 50 ms: {'met' if statistics.median(painted) <= 50 else 'NOT met'} (median)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
