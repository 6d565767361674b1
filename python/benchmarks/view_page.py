"""The trajectory viewer on a long landing: a 2-second landing of the robotic lander on its 5°
slope, run to its end time on the three engines (about 12,000 core steps and 76,000 steps of
each multibody engine), written by `touchdown view` and opened in headless Chromium
(docs/performance.md, "The trajectory viewer").

    .venv/bin/python python/benchmarks/view_page.py [--touchdown target/release/touchdown] [--draws 400]

Prints what the file holds (frames, events, bytes), the time `touchdown view` takes, the time
from opening the page to its first drawing, and the time of one redraw at a new time (what the
slider, a plot click and playback do at every step), in overlay and side by side.
"""

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "python" / "figures"))
import view_still  # noqa: E402

SCENARIO = "scenarios/robotic-lander-slope.toml"
LONG = ["--set", "integrator.t_end=2.0", "--set", "stability.terminate_on_decision=false"]

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--touchdown", type=Path, default=ROOT / "target" / "release" / "touchdown")
parser.add_argument("--draws", type=int, default=400, help="redraws timed per layout")
args = parser.parse_args()

with tempfile.TemporaryDirectory() as out:
    start = time.perf_counter()
    run = subprocess.run([args.touchdown, "view", SCENARIO, *LONG, "--out", out], cwd=ROOT,
                         capture_output=True, text=True, check=True)
    written = time.perf_counter() - start
    print(run.stdout.strip())
    data = Path(out) / "robotic-lander-slope.trajectory.json"
    page = Path(out) / "robotic-lander-slope.html"
    doc = json.loads(data.read_text())
    for e in doc["engines"]:
        print(f"{e['name']}: {e['steps']} steps, {len(e['frames']['t_s'])} frames, {len(e['events'])} contact events")
    print(f"trajectory file {data.stat().st_size / 1e6:.2f} MB, page {page.stat().st_size / 1e6:.2f} MB; "
          f"touchdown view took {written:.1f} s")
    with view_still.browser(1400, 1000) as driver:
        opened = time.perf_counter()
        view_still.open_page(driver, page)
        ready = time.perf_counter() - opened
        print(f"page opened and drawn in {ready * 1000:.0f} ms (file:// load, JSON parse, first drawing)")
        for mode in ("overlay", "side-by-side"):
            switched = driver.execute_script(
                "const s = performance.now(); touchdownView.mode(arguments[0]); flush();"
                "return performance.now() - s;"
                "function flush() { for (const c of document.querySelectorAll('#views canvas'))"
                " c.getContext('2d').getImageData(0, 0, 1, 1); }",
                mode,
            )
            # Each redraw timed to its pixels: a one-pixel read of every view forces the
            # canvas to rasterise what the redraw recorded.
            ms = driver.execute_script(
                """const [t0, t1] = touchdownView.timeRange(), n = arguments[0], out = [];
                const canvases = [...document.querySelectorAll('#views canvas')].map((c) => c.getContext('2d'));
                for (let i = 0; i < n; i++) {
                  const s = performance.now();
                  touchdownView.setTime(t0 + (t1 - t0) * ((i * 0.618034) % 1));
                  for (const c of canvases) c.getImageData(0, 0, 1, 1);
                  out.push(performance.now() - s);
                }
                return out;""",
                args.draws,
            )
            ms.sort()
            print(f"{mode}: switching to it {switched:.0f} ms; one redraw at a new time (3D views, panel, "
                  f"plot cursors, rasterised): median {statistics.median(ms):.2f} ms, 95th percentile "
                  f"{ms[int(0.95 * len(ms))]:.2f} ms, most {ms[-1]:.2f} ms over {len(ms)} draws")
        # Playback as a user sees it: frames drawn in 3 s of playing at 1x.
        frames = driver.execute_async_script(
            """const done = arguments[arguments.length - 1], stamps = [];
            touchdownView.mode('overlay'); touchdownView.setTime(touchdownView.timeRange()[0]);
            document.getElementById('speed').value = '1'; document.getElementById('speed').dispatchEvent(new Event('change'));
            touchdownView.play();
            function count(t) { stamps.push(t); if (t - stamps[0] < 3000) requestAnimationFrame(count);
              else { touchdownView.pause(); done(stamps); } }
            requestAnimationFrame(count);""")
        gaps = sorted(b - a for a, b in zip(frames, frames[1:]))
        print(f"playback at 1x, overlay: {len(frames) / ((frames[-1] - frames[0]) / 1000):.0f} frames/s, "
              f"longest gap between frames {gaps[-1]:.1f} ms")
        # The benchmark's own pixel reads draw Chromium's advice on getImageData: not the page's.
        problems = [e for e in driver.get_log("browser")
                    if e["level"] in ("SEVERE", "WARNING") and "willReadFrequently" not in e["message"]]
        print(f"console errors and warnings of the page: {len(problems)}")
        for p in problems:
            print("  ", p["level"], p["message"][:200])
