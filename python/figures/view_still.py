"""Stills of the trajectory viewer (the page `touchdown view` writes): the page opened from disk
in Debian's headless Chromium, driven through Selenium, set to a time and a layout, saved as a
PNG. Used by python/tests/test_view.py and for the stills of docs/engines.md.

    .venv/bin/python python/figures/view_still.py OUT/fig-25-26.html --time 0.08 --out still.png \\
        [--mode side-by-side] [--width 1400] [--height 1000 | --part views]

Chromium and ChromeDriver come from Debian (/usr/bin/chromium, /usr/bin/chromedriver; see
scripts/setup-browser). The browser runs headless, sandbox-less (as root), with no GPU, no
network service of its own and a fresh profile, so a still depends on the page alone.
"""

import argparse
import contextlib
import shutil
import sys
import tempfile
import time
from pathlib import Path
from typing import Iterator, Optional

from selenium import webdriver
from selenium.webdriver.chrome.service import Service

CHROMIUM = Path("/usr/bin/chromium")
CHROMEDRIVER = Path("/usr/bin/chromedriver")
INSTALL = "scripts/setup-browser (as root: apt-get install -y chromium chromium-driver)"

# The page's parts a still can show: the whole page, or the 3D views alone.
PARTS = ("page", "views")


class BrowserMissing(RuntimeError):
    """Chromium or ChromeDriver is not installed."""


def check_browser() -> None:
    """Raises BrowserMissing, naming the set-up to run, unless both are installed."""
    missing = [str(p) for p in (CHROMIUM, CHROMEDRIVER) if not p.is_file()]
    if missing:
        raise BrowserMissing(f"{' and '.join(missing)} not found: install them with {INSTALL}")


@contextlib.contextmanager
def browser(width: int = 1400, height: int = 1000) -> Iterator[webdriver.Chrome]:
    """Headless Chromium whose viewport is width x height CSS pixels, with its console kept
    (driver.get_log("browser")); quit and its profile removed on leaving."""
    check_browser()
    profile = tempfile.mkdtemp(prefix="touchdown-chromium-")
    options = webdriver.ChromeOptions()
    options.binary_location = str(CHROMIUM)
    for flag in (
        "--headless=new",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--hide-scrollbars",
        f"--user-data-dir={profile}",
        f"--window-size={width},{height}",
    ):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(options=options, service=Service(str(CHROMEDRIVER)))
    try:
        set_viewport(driver, width, height)
        yield driver
    finally:
        driver.quit()
        shutil.rmtree(profile, ignore_errors=True)


def set_viewport(driver: webdriver.Chrome, width: int, height: int) -> None:
    """Sizes the window so that the page itself gets width x height CSS pixels."""
    driver.set_window_size(width, height)
    inner = driver.execute_script("return [window.innerWidth, window.innerHeight]")
    driver.set_window_size(2 * width - inner[0], 2 * height - inner[1])


def open_page(driver: webdriver.Chrome, page: Path, timeout_s: float = 30.0) -> None:
    """Opens `page` (an HTML file) from disk and waits until the viewer has drawn it."""
    driver.get(Path(page).resolve().as_uri())
    wait_ready(driver, timeout_s)


def wait_ready(driver: webdriver.Chrome, timeout_s: float = 30.0) -> None:
    """Waits until window.touchdownView reports its trajectory drawn."""
    deadline = time.monotonic() + timeout_s
    while not driver.execute_script("return Boolean(window.touchdownView && window.touchdownView.ready)"):
        if time.monotonic() > deadline:
            raise TimeoutError(f"the viewer did not draw within {timeout_s} s: {driver.get_log('browser')}")
        time.sleep(0.05)


def show(driver: webdriver.Chrome, t_s: float, mode: str = "overlay") -> None:
    """Sets the viewer's layout and time (it draws at once)."""
    driver.execute_script("touchdownView.mode(arguments[0]); touchdownView.setTime(arguments[1]);", mode, t_s)


def still(
    page: Path,
    t_s: float,
    png: Path,
    mode: str = "overlay",
    width: int = 1400,
    height: Optional[int] = None,
    part: str = "page",
) -> Path:
    """Saves a PNG of `page` at time `t_s` (s) in layout `mode` ("overlay" or
    "side-by-side") in a viewport `width` CSS pixels wide and `height` high: of the whole page
    (part="page"; `height` None: as tall as the page) or of its 3D views alone (part="views";
    `height` None: 900)."""
    if part not in PARTS:
        raise ValueError(f"part: one of {PARTS}, got {part!r}")
    with browser(width, height or 900) as driver:
        open_page(driver, page)
        if height is None and part == "page":
            # As tall as the page (which may grow with the viewport: the 3D views do, up to a
            # limit).
            for _ in range(5):
                full = driver.execute_script("return document.documentElement.scrollHeight")
                if full <= driver.execute_script("return window.innerHeight"):
                    break
                set_viewport(driver, width, full)
        show(driver, t_s, mode)
        png = Path(png)
        png.parent.mkdir(parents=True, exist_ok=True)
        if part == "views":
            saved = driver.find_element("id", "views").screenshot(str(png))
        else:
            saved = driver.save_screenshot(str(png))
        if not saved:
            raise RuntimeError(f"Chromium could not save {png}")
    return png


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("page", type=Path, help="the page (an HTML file written by `touchdown view`)")
    parser.add_argument("--time", type=float, required=True, help="the landing time to show, s")
    parser.add_argument("--out", type=Path, required=True, help="the PNG to write")
    parser.add_argument("--mode", choices=("overlay", "side-by-side"), default="overlay")
    parser.add_argument("--width", type=int, default=1400, help="CSS pixels (default 1400)")
    parser.add_argument("--height", type=int, help="CSS pixels (default: the whole page, or 900 with --part views)")
    parser.add_argument("--part", choices=PARTS, default="page", help="the whole page or the 3D views alone")
    a = parser.parse_args()
    try:
        png = still(a.page, a.time, a.out, a.mode, a.width, a.height, a.part)
    except BrowserMissing as e:
        print(f"view_still: {e}", file=sys.stderr)
        return 1
    print(f"wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
