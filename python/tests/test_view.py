"""The trajectory viewer (`touchdown view`, crates/view/assets) in a real browser: the page
written by the command line, opened from disk in Debian's headless Chromium through Selenium
(python/figures/view_still.py), played, turned, read back pixel by pixel. Run by scripts/test, after
scripts/setup-browser has installed Chromium and ChromeDriver."""

import base64
import io
import json
import subprocess
import sys
import time
from pathlib import Path

import pytest
from PIL import Image
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select

ROOT = Path(__file__).resolve().parents[2]
TOUCHDOWN = ROOT / "target" / "debug" / "touchdown"
sys.path.insert(0, str(ROOT / "python" / "figures"))
import view_still  # noqa: E402  (python/figures/)

# The landing the tests watch (two engines, a slope, holes, touchdowns and lift-offs), and a
# second one the file picker opens.
SCENARIO = "fig-25-26"
ENGINES = "core,rapier"
OTHER = "level-sliding"
WIDTH, HEIGHT = 1400, 1000


def view(stem: str, engines: str, out: Path) -> tuple:
    """`touchdown view scenarios/<stem>.toml --engines ENGINES --out OUT`: the page and the
    trajectory document it embeds."""
    run = subprocess.run(
        [TOUCHDOWN, "view", f"scenarios/{stem}.toml", "--engines", engines, "--out", str(out)],
        capture_output=True, check=False, cwd=ROOT,
    )
    assert run.returncode == 0, run.stderr.decode()
    page, data = out / f"{stem}.html", out / f"{stem}.trajectory.json"
    assert page.is_file() and data.is_file(), run.stdout.decode()
    return page, json.loads(data.read_text(encoding="utf-8")), data


@pytest.fixture(scope="module")
def landing(tmp_path_factory):
    out = tmp_path_factory.mktemp("view")
    page, doc, _ = view(SCENARIO, ENGINES, out)
    _, other, other_path = view(OTHER, "core", out)
    return {"page": page, "doc": doc, "other": other, "other_path": other_path}


@pytest.fixture(scope="module")
def browser():
    try:
        view_still.check_browser()
    except view_still.BrowserMissing as missing:
        pytest.fail(f"{missing}. The viewer's tests need a real browser.", pytrace=False)
    with view_still.browser(WIDTH, HEIGHT) as driver:
        yield driver


@pytest.fixture
def page(browser, landing):
    """The landing's page freshly opened; after the test, nothing went wrong in its console."""
    view_still.open_page(browser, landing["page"])
    yield browser
    assert console_problems(browser, landing["page"]) == []


def console_problems(driver, page: Path) -> list:
    """The console's errors, and the warnings of the page's own scripts, since last asked."""
    url = page.resolve().as_uri()
    return [
        e for e in driver.get_log("browser")
        if e["level"] == "SEVERE" or (e["level"] == "WARNING" and (url in e["message"] or e["source"] == "console-api"))
    ]


def canvas_png(driver, canvas_id: str) -> bytes:
    """The canvas's pixels (its backing store), as PNG."""
    url = driver.execute_script("return document.getElementById(arguments[0]).toDataURL('image/png')", canvas_id)
    return base64.b64decode(url.split(",", 1)[1])


def rgb(hex_colour: str) -> tuple:
    return tuple(int(hex_colour[i:i + 2], 16) for i in (1, 3, 5))


def drawn_at(driver, engine: int, point: list) -> tuple:
    """Where the page's camera puts surface-frame `point` of `engine`: (canvas id, backing-store
    pixel x, y), computed here from the transform the page reports."""
    cam = driver.execute_script("return touchdownView.camera(arguments[0])", engine)
    m = cam["matrix"]
    x, y, z = point
    xc, yc, _, wc = (m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3] for r in range(4))
    assert wc > 0, "the point is behind the camera"
    css = ((xc / wc + 1) / 2 * cam["width"], (1 - yc / wc) / 2 * cam["height"])
    assert 0 <= css[0] < cam["width"] and 0 <= css[1] < cam["height"], f"{point} is off the canvas: {css}"
    return cam["canvasId"], int(css[0] * cam["devicePixelRatio"]), int(css[1] * cam["devicePixelRatio"])


def mid_run(contact: list, state: int) -> int:
    """The frame in the middle of the longest run of `state` in a footpad's contact states, or -1."""
    best, start = (0, -1), None
    for i, c in enumerate(contact + [None]):
        if c == state and start is None:
            start = i
        elif c != state and start is not None:
            best = max(best, (i - start, (start + i - 1) // 2))
            start = None
    return best[1]


def test_the_page_opens_from_disk_with_everything_inside(page, landing):
    doc = landing["doc"]
    assert page.execute_script("return touchdownView.ready") is True
    assert page.find_element(By.ID, "scenario-name").text == doc["scenario_name"]
    assert page.execute_script("return touchdownView.timeRange()") == [
        min(e["frames"]["t_s"][0] for e in doc["engines"]),
        max(e["frames"]["t_s"][-1] for e in doc["engines"]),
    ]
    # One row per engine, its outcome; nothing loaded from anywhere but the page.
    rows = page.find_elements(By.CSS_SELECTOR, "#engines-now tbody tr")
    assert [r.text.split()[0] for r in rows] == [e["name"] for e in doc["engines"]]
    for row, engine in zip(rows, doc["engines"]):
        assert engine["outcome"] in row.text
        assert ("past capacity" in row.text) == bool(engine["past_capacity"]), row.text
    resources = page.execute_script("return performance.getEntriesByType('resource').map(r => r.name)")
    assert [r for r in resources if not r.startswith(("data:", "file:"))] == []
    assert len(page.find_elements(By.CSS_SELECTOR, "#plots .uplot")) == 3


def test_a_strut_past_its_capacity_is_named_beside_the_outcome(browser, tmp_path):
    # The stroke-out drop bottoms its four primaries: the outcome never reads simply stable.
    page_path, doc, _ = view("stroke-out", "core", tmp_path)
    past = doc["engines"][0]["past_capacity"]
    assert sorted(p["strut"] for p in past) == [f"leg{i}.primary" for i in range(1, 5)]
    view_still.open_page(browser, page_path)
    row = browser.find_element(By.CSS_SELECTOR, "#engines-now tbody tr")
    assert "4 struts past capacity" in row.text, row.text
    note = row.find_element(By.CSS_SELECTOR, ".past-capacity").get_attribute("title")
    assert note.count("\n") == 3 and "leg1.primary" in note and "kN" in note, note
    assert console_problems(browser, page_path) == []


def test_a_scenario_named_like_markup_is_shown_as_text(browser, tmp_path):
    # A name that opens a comment and a script inside the embedded JSON (`<!--<script>`) would
    # swallow the rest of the page if the JSON held a `<`: it renders, named as written.
    name = "<!--<script></script>"
    scenario = tmp_path / "markup.toml"
    scenario.write_text(f'extends = "{ROOT / "scenarios" / "flat-drop.toml"}"\nname = {json.dumps(name)}\n')
    run = subprocess.run([TOUCHDOWN, "view", scenario, "--engines", "core", "--out", tmp_path],
                         capture_output=True, cwd=ROOT)
    assert run.returncode == 0, run.stderr.decode()
    page_path = tmp_path / "markup.html"
    view_still.open_page(browser, page_path)
    assert browser.execute_script("return touchdownView.ready") is True
    assert browser.find_element(By.ID, "scenario-name").text == name
    assert console_problems(browser, page_path) == []


def test_the_slider_moves_time_and_the_picture(page, landing):
    t0, t1 = page.execute_script("return touchdownView.timeRange()")
    before, clock = canvas_png(page, "view-0"), page.find_element(By.ID, "clock").text
    target = t0 + 0.6 * (t1 - t0)
    # As a user moving it: the slider's value, then its input event.
    page.execute_script(
        "const s = document.getElementById('slider'); s.value = arguments[0];"
        "s.dispatchEvent(new Event('input', {bubbles: true}));",
        str(target),
    )
    assert page.execute_script("return touchdownView.time()") == pytest.approx(target, abs=1e-9)
    assert page.find_element(By.ID, "clock").text != clock
    assert f"{target:.4f}" in page.find_element(By.ID, "clock").text
    assert canvas_png(page, "view-0") != before


def test_play_pause_and_a_click_on_a_plot(page):
    t0, t1 = page.execute_script("return touchdownView.timeRange()")
    # The slowest speed, so that the playback (a 0.09 s landing: 1.8 s at 0.05×) is still
    # running when the second click comes, however slow the machine is to deliver it.
    Select(page.find_element(By.ID, "speed")).select_by_value("0.05")
    page.find_element(By.ID, "play").click()
    assert page.execute_script("return touchdownView.playing()") is True
    time.sleep(0.5)
    page.find_element(By.ID, "play").click()
    assert page.execute_script("return touchdownView.playing()") is False
    assert page.execute_script("return touchdownView.time()") > t0
    # A click in the middle of the pitch-rate plot goes to the middle of the landing.
    over = page.find_element(By.CSS_SELECTOR, "#plot-pitch .u-over")
    ActionChains(page).move_to_element(over).click().perform()
    assert page.execute_script("return touchdownView.time()") == pytest.approx((t0 + t1) / 2, abs=0.01 * (t1 - t0))


@pytest.mark.parametrize("mode", ["overlay", "side-by-side"])
def test_each_footpad_is_drawn_where_the_camera_puts_it_in_its_contact_colour(page, landing, mode):
    """For every contact state a footpad of the engine goes through (never touched before
    touchdown, in contact, left the surface): at a frame in that state, the pixel where the
    page's camera puts the footpad's centre has that state's colour. Overlaid, the first engine
    is drawn on top; side by side, each engine in its own canvas."""
    doc = landing["doc"]
    page.execute_script("touchdownView.mode(arguments[0])", mode)
    colours = page.execute_script("return touchdownView.contactColours")
    assert len(set(colours)) == 3
    engines = [0] if mode == "overlay" else range(len(doc["engines"]))
    checked = set()
    for e in engines:
        legs = doc["engines"][e]["frames"]["legs"]
        t_s = doc["engines"][e]["frames"]["t_s"]
        for state in (0, 1, 2):
            found = [(leg, mid_run(legs[leg]["contact"], state)) for leg in range(len(legs))]
            found = [(leg, i) for leg, i in found if i >= 0]
            if not found:
                continue
            leg, i = found[0]
            page.execute_script("touchdownView.setTime(arguments[0])", t_s[i])
            canvas, x, y = drawn_at(page, e, legs[leg]["pad_m"][i])
            pixel = Image.open(io.BytesIO(canvas_png(page, canvas))).convert("RGB").getpixel((x, y))
            want = rgb(colours[state])
            assert all(abs(a - b) <= 2 for a, b in zip(pixel, want)), (
                f"engine {e}, leg {leg + 1}, t = {t_s[i]} s, state {state}: pixel ({x}, {y}) of {canvas} "
                f"is {pixel}, not {want}"
            )
            checked.add(state)
    # The landing has touchdowns: its footpads are seen before and in contact at least.
    assert {0, 1} <= checked


def test_a_contact_change_between_frames_is_shown_at_its_time(page, landing):
    """The frames keep a state a millisecond; the events every change of contact. At the time of
    a change that falls between two frames the footpad has its new state's colour, and a tenth
    of a microsecond before it the state it left."""
    doc = landing["doc"]
    page.execute_script("touchdownView.mode('side-by-side')")
    colours = page.execute_script("return touchdownView.contactColours")
    core = doc["engines"][0]
    frames = set(core["frames"]["t_s"])
    between = [ev for ev in core["events"] if ev["t_s"] not in frames]
    assert between, "no contact change between frames to check"
    for state in sorted({ev["contact"] for ev in between}):
        ev = next(ev for ev in between if ev["contact"] == state)
        earlier = [e for e in core["events"] if e["leg"] == ev["leg"] and e["t_s"] < ev["t_s"]]
        left = earlier[-1]["contact"] if earlier else core["frames"]["legs"][ev["leg"] - 1]["contact"][0]
        for t, want in ((ev["t_s"], state), (ev["t_s"] - 1e-7, left)):
            page.execute_script("touchdownView.setTime(arguments[0])", t)
            canvas, x, y = drawn_at(page, 0, ev["pad_m"])
            pixel = Image.open(io.BytesIO(canvas_png(page, canvas))).convert("RGB").getpixel((x, y))
            assert all(abs(a - b) <= 2 for a, b in zip(pixel, rgb(colours[want]))), (
                f"leg {ev['leg']} at {t} s: pixel {pixel}, not the colour of state {want}"
            )


def test_open_trajectory_replaces_the_landing(page, landing):
    other = landing["other"]
    assert other["scenario_name"] != landing["doc"]["scenario_name"]
    page.find_element(By.ID, "open-file").send_keys(str(landing["other_path"]))
    deadline = time.monotonic() + 30
    while page.find_element(By.ID, "scenario-name").text != other["scenario_name"]:
        assert time.monotonic() < deadline, page.find_element(By.ID, "status").text
        time.sleep(0.05)
    view_still.wait_ready(page)
    assert other["scenario_name"] in page.title
    assert page.find_element(By.ID, "status").text == ""
    assert len(page.find_elements(By.CSS_SELECTOR, "#engines-now tbody tr")) == len(other["engines"])
    assert page.execute_script("return touchdownView.timeRange()")[1] == other["engines"][0]["frames"]["t_s"][-1]


def test_a_file_that_is_not_a_trajectory_is_refused_and_the_landing_kept(page, landing, tmp_path):
    shown = page.find_element(By.ID, "scenario-name").text
    wrong = tmp_path / "summary.json"
    wrong.write_text(json.dumps({"schema": "touchdown.run/1", "engine": "core"}))
    page.find_element(By.ID, "open-file").send_keys(str(wrong))
    deadline = time.monotonic() + 30
    while "Could not open" not in page.find_element(By.ID, "status").text:
        assert time.monotonic() < deadline, "no message about the refused file"
        time.sleep(0.05)
    status = page.find_element(By.ID, "status").text
    assert "summary.json" in status and "touchdown.run/1" in status and "touchdown.trajectory/1" in status, status
    assert page.find_element(By.ID, "scenario-name").text == shown
    assert page.execute_script("return touchdownView.ready") is True


def test_side_by_side_shows_one_view_per_engine_and_the_camera_turns(page, landing):
    names = [e["name"] for e in landing["doc"]["engines"]]
    page.find_element(By.CSS_SELECTOR, "input[name=layout][value=side-by-side]").click()
    assert page.execute_script("return touchdownView.mode()") == "side-by-side"
    canvases = page.find_elements(By.CSS_SELECTOR, "#views canvas")
    assert len(canvases) == len(names)
    assert [v.text for v in page.find_elements(By.CSS_SELECTOR, "#views .view-label")] == names
    assert len({page.execute_script("return touchdownView.camera(arguments[0]).canvasId", e) for e in range(len(names))}) == len(names)
    # Dragging one view turns every view's camera; the reset button brings it back.
    first = canvas_png(page, "view-0")
    ActionChains(page).drag_and_drop_by_offset(canvases[0], 120, 40).perform()
    turned = canvas_png(page, "view-0")
    assert turned != first
    page.find_element(By.ID, "reset-camera").click()
    assert canvas_png(page, "view-0") == first
    page.find_element(By.CSS_SELECTOR, "input[name=layout][value=overlay]").click()
    assert len(page.find_elements(By.CSS_SELECTOR, "#views canvas")) == 1


def test_a_still_of_the_page(landing, tmp_path):
    """python/figures/view_still.py (the stills of docs/engines.md) saves the page as a PNG."""
    doc = landing["doc"]
    t = doc["engines"][0]["frames"]["t_s"][-1] / 2
    png = view_still.still(landing["page"], t, tmp_path / "still.png", mode="side-by-side", width=1200, height=800)
    image = Image.open(png)
    assert image.format == "PNG" and image.size == (1200, 800)
    # A picture, not a blank page: many colours.
    assert len(image.convert("RGB").getcolors(maxcolors=1 << 20)) > 200
