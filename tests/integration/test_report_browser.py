"""The report page in a real browser: Debian's chromium, headless, driven by Playwright (no browser
download), with every request that is not the page's own file blocked and counted.

For the marm (good and broken), the panda (the Setup Assistant's MoveIt 1 package), the PR2 (a
package `init` generates) and a vendor package (Kinova Gen3 + Robotiq, MoveIt 2): the page loads
with no console error and fetches nothing; every state draws the robot (pixels differ from the
empty scene); picking a pose that moves the robot changes the picture; links in contact are red
exactly where a state has contacts; a group lights up; a trajectory moves. Skips only where
chromium or playwright is missing (`.ci/run` installs chromium). Sizes and build times are
printed (`pytest -s`).
"""

from __future__ import annotations

import re
import shutil
import time
from dataclasses import dataclass
from pathlib import Path

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.conftest import realworld, realworld2
from tests.report_helpers import broken_marm, marm_package

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--enable-unsafe-swiftshader",  # WebGL on the CPU (no GPU here)
]
# Pictures are grabbed from the viewer's canvas and compared inside the page: `shoot(name, action)`
# does the action, renders and keeps the pixels under `name`; `changed(a, b)` counts pixels whose
# colour differs (any channel by more than 24); `count(name, kind)` counts red or orange pixels.
PICTURES = """() => {
  const v = report.viewer;
  const shots = {};
  const grab = () => new Promise((done) => {
    const img = new Image();
    img.onload = () => {
      const c = document.createElement("canvas");
      c.width = img.width; c.height = img.height;
      const g = c.getContext("2d");
      g.drawImage(img, 0, 0);
      done(g.getImageData(0, 0, c.width, c.height).data);
    };
    img.src = v.capture_image();
  });
  const kinds = {
    red: (r, g, b) => r > 140 && g < 80 && b < 80,
    orange: (r, g, b) => r > 170 && g > 90 && g < 190 && b < 80 && r - g > 50,
  };
  window.pictures = {
    async shoot(name, action) {
      if (action.kind === "empty") v.set_property(["robot"], "visible", false);
      if (action.kind === "state") report.showState(action.key);
      if (action.kind === "group") report.highlightGroup(action.key);
      if (action.kind === "motion") { report.playMotion(action.index); report.stopMotion(); report.showMotionAt(action.t); }
      shots[name] = await grab();
      v.set_property(["robot"], "visible", true);
    },
    changed(a, b) {
      const x = shots[a], y = shots[b];
      let n = 0;
      for (let k = 0; k < x.length; k += 4) {
        if (Math.max(Math.abs(x[k] - y[k]), Math.abs(x[k + 1] - y[k + 1]), Math.abs(x[k + 2] - y[k + 2])) > 24) n++;
      }
      return n;
    },
    count(name, kind) {
      const x = shots[name];
      let n = 0;
      for (let k = 0; k < x.length; k += 4) if (kinds[kind](x[k], x[k + 1], x[k + 2])) n++;
      return n;
    },
  };
}"""


@dataclass(frozen=True)
class Page:
    name: str
    path: Path
    megabytes: float
    seconds: float


def _chromium_and_playwright():
    if not Path(CHROMIUM).exists():
        pytest.skip("chromium is not installed (apt-get install chromium)")
    return pytest.importorskip("playwright.sync_api")


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    api = _chromium_and_playwright()
    with api.sync_playwright() as p:
        profile = tmp_path_factory.mktemp("chromium-profile")  # a fresh user data dir
        context = p.chromium.launch_persistent_context(
            str(profile), executable_path=CHROMIUM, args=FLAGS, viewport={"width": 1200, "height": 760}
        )
        yield context
        context.close()


@pytest.fixture(scope="module")
def root(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("pages")


def _build(root: Path, name: str, package: Path, *options: str | Path) -> Page:
    page = root / f"{name}.html"
    started = time.perf_counter()
    result = CliRunner().invoke(app, ["report", str(package), "-o", str(page), *map(str, options)])
    seconds = time.perf_counter() - started
    assert result.exit_code in (0, 1), result.output
    built = Page(name, page, page.stat().st_size / 1e6, seconds)
    print(f"\nreport {name}: {built.megabytes:.2f} MB in {seconds:.1f} s ({result.stdout.strip()})")
    return built


def _pr2_package(root: Path) -> Path:
    urdf = realworld("ros1", "pr2_description", "urdf", "robot.xml")
    out = root / "pr2_moveit_config"
    result = CliRunner().invoke(app, ["init", str(urdf), "--out", str(out), "--trials", "1000"])
    assert result.exit_code == 0, result.output
    return out


_BUILT: dict[tuple[Path, str], Page] = {}
# One worker runs the module (`--dist loadgroup`): one browser, and each page (the PR2's: an init
# and a report, half a minute) built once, not once per worker.
pytestmark = pytest.mark.xdist_group("report_browser")


def _page(root: Path, name: str) -> Page:
    """The page of robot `name`, built once per test module."""
    if (root, name) not in _BUILT:
        _BUILT[root, name] = _build_page(root, name)
    return _BUILT[root, name]


def _build_page(root: Path, name: str) -> Page:
    if name == "marm":
        return _build(root, name, marm_package(root))
    if name == "marm_broken":
        return _build(root, name, broken_marm(root))
    if name == "panda":
        return _build(
            root, name, realworld("ros1", "panda_moveit_config"), "--package-path", realworld("ros1")
        )
    if name == "pr2":  # the matrix at the package's own 1000 trials: 10,000 cost 10 s more a page
        return _build(root, name, _pr2_package(root), "--trials", "1000")
    kortex = realworld2("ros2_kortex")
    package = kortex / "kortex_moveit_config" / "kinova_gen3_6dof_robotiq_2f_85_moveit_config"
    return _build(
        root, name, package, "--package-path", kortex, "--package-path", realworld2("ros2_robotiq_gripper")
    )


class Opened:
    """A page open in the browser, with what it logged and tried to fetch."""

    def __init__(self, context, path: Path):
        self.errors: list[str] = []
        self.fetched: list[str] = []
        self.page = context.new_page()
        self.page.on("console", lambda m: self.errors.append(m.text) if m.type == "error" else None)
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))
        self.page.route("**/*", self._only_the_file)
        self.page.goto(path.resolve().as_uri())
        self.page.wait_for_selector("body[data-ready=true]", state="attached", timeout=60_000)
        self.page.evaluate("report.showMarkers(false)")  # frames and labels aside: the robot alone
        self.page.evaluate(PICTURES)

    def _only_the_file(self, route) -> None:
        url = route.request.url
        if url.startswith("file:"):
            route.continue_()
        else:
            self.fetched.append(url)
            route.abort()

    def shoot(self, name: str, kind: str, **action) -> None:
        self.page.evaluate(
            "([name, action]) => pictures.shoot(name, action)", [name, {"kind": kind, **action}]
        )

    def changed(self, a: str, b: str) -> int:
        return self.page.evaluate("([a, b]) => pictures.changed(a, b)", [a, b])

    def count(self, name: str, kind: str) -> int:
        return self.page.evaluate("([name, kind]) => pictures.count(name, kind)", [name, kind])


ROBOTS = ("marm", "marm_broken", "panda", "pr2", "kinova_gen3")
VISIBLE = 0.01  # [m] a link whose every shape is smaller is a few pixels at the robot's scale


def visible(data: dict, link: str) -> bool:
    """Whether the page draws `link` big enough to see: a mesh, or a shape of 1 cm or more."""
    shapes = next((lk["shapes"] for lk in data["geometry"]["links"] if lk["name"] == link), [])
    return any(s["kind"] == "mesh" or max(s.get("size") or [0.0]) >= VISIBLE for s in shapes)


@pytest.mark.parametrize("name", ROBOTS)
def test_the_page_draws_the_robot_at_every_pose(browser, root, name):
    built = _page(root, name)
    opened = Opened(browser, built.path)
    data = opened.page.evaluate("JSON.parse(document.getElementById('report-data').textContent)")
    opened.shoot("empty", "empty")
    opened.shoot("start", "state", key="start")
    start_joints = next(s["joints"] for s in data["states"] if s["key"] == "start")
    for state in data["states"]:
        key = state["key"]
        opened.shoot(key, "state", key=key)
        assert opened.changed(key, "empty") > 300, f"{key} draws nothing"
        red = opened.count(key, "red")
        if any(visible(data, link) for pair in state["contacts"] for link in pair):
            assert red > 20, f"{key}: links in contact {state['contacts']} are not red"
        elif state["contacts"]:  # e.g. the PR2's 1 mm accelerometer boxes: nothing to see
            pass
        else:
            assert red < 5, f"{key}: red without a contact"
        moved = any(abs(v - start_joints[j]) > 0.05 for j, v in state["joints"].items())
        if key.startswith("pose:") and moved:
            assert opened.changed(key, "start") > 50, f"picking {key} does not change the picture"
    opened.shoot("start", "state", key="start")
    group = next(g for g in data["groups"] if g["links"])
    opened.shoot("lit", "group", key=group["name"])
    assert opened.count("lit", "orange") > 50, f"group {group['name']} does not light up"
    opened.shoot("unlit", "group", key=group["name"])  # a second pick turns it off
    for index, motion in enumerate(data["motions"][:2]):
        opened.shoot("begin", "motion", index=index, t=0.0)
        opened.shoot("end", "motion", index=index, t=motion["duration"])
        assert opened.changed("begin", "end") > 50, (
            f"trajectory {motion['start']} -> {motion['goal']} does not move"
        )
    opened.page.screenshot(path=str(root / f"{name}.png"))
    assert opened.errors == [] and opened.fetched == []
    opened.page.close()


def test_the_broken_marm_shows_its_errors(browser, root):
    opened = Opened(browser, _page(root, "marm_broken").path)
    rules = opened.page.evaluate(
        "[...document.querySelectorAll('#findings td.sev')].map(td => td.textContent)"
    )
    assert "error" in rules and "warning" in rules
    titles = opened.page.evaluate("[...document.querySelectorAll('#states button')].map(b => b.textContent)")
    assert any(t.startswith("matrix.stale:") for t in titles) and any(
        t.startswith("pose.collision:") for t in titles
    )
    assert opened.errors == [] and opened.fetched == []


# Readability at a laptop's 1280x800 and on a wide screen (issue 33): per visible text, its font
# size on screen (an SVG text's scaled by the SVG's own scale); per table, how far it reaches past
# the box it sits in, and whether that box scrolls; the side column's own horizontal overflow;
# every text and tooltip of the page.
READABILITY = """() => {
  const fonts = [];
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  for (let n = walker.nextNode(); n; n = walker.nextNode()) {
    const e = n.parentElement;
    if (!n.textContent.trim() || !e || e.closest("script, style, option, title")) continue;
    if (!e.getClientRects().length) continue;
    let px = parseFloat(getComputedStyle(e).fontSize);
    if (e instanceof SVGElement) { const m = e.getScreenCTM(); px *= Math.hypot(m.a, m.b); }
    fonts.push([px, n.textContent.trim().slice(0, 40)]);
  }
  const tables = [...document.querySelectorAll("table")].map((t) => {
    const box = t.parentElement;
    return { box: box.className || box.id, past: t.getBoundingClientRect().width - box.clientWidth,
             scrolls: ["auto", "scroll"].includes(getComputedStyle(box).overflowX) };
  });
  const side = document.getElementById("side");
  const texts = [];
  const all = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  for (let n = all.nextNode(); n; n = all.nextNode()) if (!n.parentElement.closest("script, style")) texts.push(n.textContent);
  for (const e of document.querySelectorAll("[title]")) texts.push(e.title);
  return { fonts, tables, sideOverflow: side.scrollWidth - side.clientWidth, text: texts.join("\\n") };
}"""
# After following a section link: every sticky or fixed element of the side column overlapping
# the section's heading (none may), whether the heading is in view, and whether it is what is
# drawn at its own middle.
COVERED = """(id) => {
  const heading = document.getElementById(id).querySelector("h2");
  const h = heading.getBoundingClientRect();
  const over = [];
  for (const e of document.querySelectorAll("#side *")) {
    const position = getComputedStyle(e).position;
    if (position !== "sticky" && position !== "fixed") continue;
    const r = e.getBoundingClientRect();
    if (r.width && r.height && r.bottom > h.top + 0.5 && r.top < h.bottom - 0.5 && r.right > h.left && r.left < h.right)
      over.push(e.id || e.tagName);
  }
  const side = document.getElementById("side").getBoundingClientRect();
  const atMiddle = document.elementFromPoint(h.left + 5, (h.top + h.bottom) / 2);
  return { over, shown: h.top >= side.top && h.bottom <= side.bottom, top: atMiddle === heading || heading.contains(atMiddle) };
}"""
SIZES = ((1280, 800), (1920, 1080))
MACHINE_PATH = re.compile(r"(?<![\w./~+@-])/(?:[\w.+@~-]+/)+[\w.+@~-]+")


@pytest.mark.parametrize("size", SIZES, ids=lambda s: f"{s[0]}x{s[1]}")
@pytest.mark.parametrize("name", ("marm_broken", "pr2"))
def test_the_page_is_readable_at_each_size(browser, root, name, size):
    """Text >= 11 px (the matrix's labels included), no table wider than its box, no path of
    this machine, and a section link never leaves its heading under a sticky element; a
    screenshot per size (and of the matrix) in the pages folder, to look at."""
    opened = Opened(browser, _page(root, name).path)
    page = opened.page
    page.set_viewport_size({"width": size[0], "height": size[1]})
    page.screenshot(path=str(root / f"{name}-{size[0]}x{size[1]}.png"))
    seen = page.evaluate(READABILITY)
    smallest = min(seen["fonts"])
    assert round(smallest[0], 1) >= 11, f"text '{smallest[1]}' is {smallest[0]:.1f} px"
    for table in seen["tables"]:  # no column cut: every table fits its box (1 px of rounding)
        assert table["past"] <= 1, f"a table in {table['box']} is {table['past']:.0f} px too wide"
    assert seen["sideOverflow"] <= 0, "the side column scrolls sideways"
    machine = [p for p in MACHINE_PATH.findall(seen["text"]) if Path("/", p.split("/")[1]).is_dir()]
    assert machine == [] and str(root) not in seen["text"], f"absolute paths on the page: {machine[:3]}"
    links = page.query_selector_all("#toc a")
    assert len(links) == 5
    for link in links:
        section = link.get_attribute("href").lstrip("#")
        link.click()
        covered = page.evaluate(COVERED, section)
        assert covered == {"over": [], "shown": True, "top": True}, f"{section}: {covered}"
        if section == "matrix-section":
            page.screenshot(path=str(root / f"{name}-{size[0]}x{size[1]}-matrix.png"))
    print(f"\n{name} at {size[0]}x{size[1]}: screenshots in {root}")
    assert opened.errors == [] and opened.fetched == []
    page.close()
