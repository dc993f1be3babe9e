"""The reports in a real browser: Debian's headless Chromium driven by Playwright.

Each page is opened from a file:// URL while every console message, page error and
network request is recorded: a report must render with no errors and fetch nothing but
itself. The viewer is then driven like a person would (scrubber, play button, filters,
sorting) and checked against the episode it shows.

Never Playwright's own browser download: /usr/bin/chromium (the ``chromium`` package).
Set EMBOTEAM_DOCS_SCREENSHOT=1 to also refresh docs/img/report.png.
"""

from __future__ import annotations

import bisect
import os
import re
import shutil
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest

from emboteam.exec.episode import Episode
from emboteam.report import save_episode_report, write_bench_index
from test_report_fixtures import (
    executed_fridge_episode,
    fridge_plan,
    scripted_fridge_episode,
    scripted_shuttle_episode,
)

CHROMIUM = Path("/usr/bin/chromium")
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]
VIEWPORT = {"width": 1400, "height": 900}
DOCS_IMG = Path(__file__).resolve().parents[1] / "docs" / "img" / "report.png"

pytestmark = pytest.mark.timeout(300)


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        pytest.skip("playwright is not installed (the report tests drive Chromium through it)")
    if not CHROMIUM.exists():
        pytest.skip(f"{CHROMIUM} is missing: install Debian's chromium package to run the browser tests")
    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=str(CHROMIUM), args=ARGS)
        try:
            yield b
        finally:
            b.close()


@dataclass
class Watched:
    page: Any
    url: str
    errors: list[str] = field(default_factory=list)
    requests: list[str] = field(default_factory=list)

    def assert_clean(self) -> None:
        assert self.errors == [], f"console errors: {self.errors}"
        others = [u for u in self.requests if u.split("#")[0] != self.url]
        assert others == [], f"the page fetched: {others}"


def open_page(browser: Any, path: Path) -> Watched:
    page = browser.new_page(viewport=VIEWPORT)
    w = Watched(page=page, url=path.resolve().as_uri())
    page.on("console", lambda m: w.errors.append(m.text) if m.type in ("error", "warning") else None)
    page.on("pageerror", lambda e: w.errors.append(f"uncaught: {e}"))
    page.on("requestfailed", lambda r: w.errors.append(f"request failed: {r.url}"))
    page.on("request", lambda r: w.requests.append(r.url))
    page.goto(w.url)
    page.wait_for_load_state("load")
    return w


def report_for(episode: Episode, directory: Path) -> Path:
    episode.save(directory)
    return save_episode_report(episode, directory)


def robot_positions(page: Any) -> dict[str, tuple[float, float]]:
    out: dict[str, tuple[float, float]] = {}
    for name, transform in page.eval_on_selector_all(
            "#map g.robot", "gs => gs.map(g => [g.dataset.robot, g.getAttribute('transform')])"):
        m = re.fullmatch(r"translate\(([-\d.]+),([-\d.]+)\)", transform or "")
        assert m, f"robot {name} has no position: {transform!r}"
        out[name] = (float(m.group(1)), float(m.group(2)))
    return out


def expected_positions(data: dict[str, Any], t: float) -> dict[str, tuple[float, float]]:
    """Where the trace puts each robot at ``t`` (linear between pose samples), in map units."""
    fmap = data["map"]
    out = {}
    for robot, tr in data["timeline"]["poses"].items():
        i = bisect.bisect_right(tr["t"], t) - 1
        if i < 0:
            x, z = tr["x"][0], tr["z"][0]
        elif i >= len(tr["t"]) - 1:
            x, z = tr["x"][-1], tr["z"][-1]
        else:
            t0, t1 = tr["t"][i], tr["t"][i + 1]
            f = (t - t0) / (t1 - t0) if t1 > t0 else 1.0
            x = tr["x"][i] + f * (tr["x"][i + 1] - tr["x"][i])
            z = tr["z"][i] + f * (tr["z"][i + 1] - tr["z"][i])
        out[robot] = ((x - fmap["min_x"]) * 100, (fmap["max_z"] - z) * 100)
    return out


def click_scrubber(page: Any, fraction: float) -> float:
    box = page.locator("#scrubber").bounding_box()
    page.mouse.click(box["x"] + 8 + (box["width"] - 16) * fraction, box["y"] + box["height"] / 2)
    t: float = page.evaluate("window.emboteamReport.time()")
    return t


def page_data(page: Any) -> dict[str, Any]:
    data: dict[str, Any] = page.evaluate("JSON.parse(document.getElementById('episode-data').textContent)")
    return data


def check_viewer(w: Watched, episode: Episode, tmp_path: Path, shot: str) -> None:
    """What every episode viewer must do, checked against the episode it shows."""
    page = w.page
    data = page_data(page)
    robots = list(episode.robots)
    assert page.locator("#map g.robot").count() == len(robots)
    assert page.locator("#gantt .gantt-row").count() == len(robots)
    assert page.locator("#gantt rect.bar").count() == episode.actions
    assert page.locator("#verdict").inner_text() == ("SUCCESS" if episode.success else "FAILED")

    # the scrubber moves the robots to where the trace says they are
    seen = []
    for fraction in (0.1, 0.45, 0.8):
        t = click_scrubber(page, fraction)
        assert t == pytest.approx(fraction * data["timeline"]["end"], abs=0.03 * data["timeline"]["end"])
        got, want = robot_positions(page), expected_positions(data, t)
        for r in robots:
            assert got[r] == pytest.approx(want[r], abs=1.0), f"{r} at t={t}"
        assert page.locator("#clock").inner_text().startswith(f"t = {t:.2f}")
        seen.append(got)
    assert any(seen[0][r] != seen[-1][r] for r in robots), "no robot moved"

    # the Gantt cursor follows the scrubber
    x1 = float(page.get_attribute("#gantt line.cursor", "x1") or 0)
    click_scrubber(page, 0.2)
    assert float(page.get_attribute("#gantt line.cursor", "x1") or 0) < x1

    # statuses at the scrubber's time: at the end, steps have finished
    click_scrubber(page, 1.0)
    done = page.locator("#tree .node[data-status=success]").count()
    assert done >= 1
    click_scrubber(page, 0.0)
    assert page.locator("#tree .node[data-status=success]").count() < done

    # play advances simulated time, pause stops it
    page.click("#play")
    page.wait_for_timeout(600)
    page.click("#play")
    t_paused = page.evaluate("window.emboteamReport.time()")
    assert t_paused > 0
    page.wait_for_timeout(200)
    assert page.evaluate("window.emboteamReport.time()") == t_paused

    page.evaluate("window.emboteamReport.setTime(window.emboteamReport.end * 0.45)")
    path = tmp_path / shot
    page.screenshot(path=str(path))
    assert path.stat().st_size > 20_000
    w.assert_clean()


def test_scripted_episode_report_renders_offline_and_follows_the_scrubber(browser: Any, tmp_path: Path) -> None:
    episode = scripted_fridge_episode()
    w = open_page(browser, report_for(episode, tmp_path / "run"))
    check_viewer(w, episode, tmp_path, "scripted.png")
    page = w.page
    # three sync points, drawn as arrows
    assert page.locator("#gantt path.sync").count() == 3
    # keyboard: arrows step 1 % of the episode, space plays and pauses
    end = page.evaluate("window.emboteamReport.end")
    page.evaluate("window.emboteamReport.setTime(1.0); document.activeElement.blur()")
    page.keyboard.press("ArrowRight")
    assert page.evaluate("window.emboteamReport.time()") == pytest.approx(1.0 + end / 100)
    page.keyboard.press(" ")
    page.wait_for_timeout(400)
    page.keyboard.press(" ")
    t = page.evaluate("window.emboteamReport.time()")
    assert t > 1.0 + end / 100
    page.wait_for_timeout(150)
    assert page.evaluate("window.emboteamReport.time()") == t
    # clicking the Gantt chart jumps there
    box = page.locator("#gantt svg").bounding_box()
    page.mouse.click(box["x"] + box["width"] - 20, box["y"] + box["height"] / 2)
    assert page.evaluate("window.emboteamReport.time()") > 0.9 * end
    # the event filters: hide the locks, then search for the sync flags
    visible_keys = "() => [...document.querySelectorAll('#event-list .ev-window .ev-row')].filter(r => !r.hidden).map(r => r.children[3].textContent)"
    page.click("#event-filters .chip[data-category=lock]")
    keys = page.evaluate(visible_keys)
    assert keys and not any(k.startswith("lock") for k in keys)
    page.fill("#event-filters input[type=search]", "done/robot1")
    keys = page.evaluate(visible_keys)
    assert keys and all(k.startswith("done/robot1") for k in keys)
    w.assert_clean()
    page.close()


def test_real_executor_episode_report(browser: Any, tmp_path: Path) -> None:
    pytest.importorskip("emboteam.exec.executor", reason="the executor has not landed yet")
    episode = executed_fridge_episode()
    w = open_page(browser, report_for(episode, tmp_path / "run"))
    check_viewer(w, episode, tmp_path, "executed.png")
    data = page_data(w.page)
    assert data["tree"]["source"] == "trace" and len(data["tree"]["nodes"]) > 100
    if os.environ.get("EMBOTEAM_DOCS_SCREENSHOT"):
        DOCS_IMG.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(tmp_path / "executed.png", DOCS_IMG)
    w.page.close()


def test_no_btc_episode_shows_the_plan_tree_with_derived_statuses(browser: Any, tmp_path: Path) -> None:
    pytest.importorskip("emboteam.exec.linear", reason="the linear executor has not landed yet")
    episode = executed_fridge_episode(linear=True)
    assert not any(e.kind == "node" for e in episode.trace)
    w = open_page(browser, report_for(episode, tmp_path / "run"))
    page = w.page
    assert "shape from the plan" in page.locator("#tree-caption").inner_text()
    assert page.locator("#tree .node").count() == 1 + 3 + 6 * len(fridge_plan().steps)
    page.evaluate("window.emboteamReport.setTime(0.01)")
    assert page.locator("#tree .node[data-status=running]").count() >= 3  # a step per robot
    assert page.locator("#gantt .gantt-row").count() == 3
    w.assert_clean()
    page.close()


def test_a_robot_that_breaks_down_is_greyed_out_from_then_on(browser: Any, tmp_path: Path) -> None:
    pytest.importorskip("emboteam.exec.executor", reason="the executor has not landed yet")
    from emboteam.sim.faults import Breakdown, FaultConfig

    faults = FaultConfig(breakdowns=(Breakdown(robot="robot2", at=6.0),))
    episode = executed_fridge_episode(seed=1, faults=faults)
    assert not episode.success
    w = open_page(browser, report_for(episode, tmp_path / "run"))
    page = w.page
    down = "#map g.robot[data-robot=robot2].down"
    page.evaluate("window.emboteamReport.setTime(5.9)")
    assert page.locator(down).count() == 0
    page.evaluate("window.emboteamReport.setTime(6.1)")
    assert page.locator(down).count() == 1
    # its last action failed with robot_down, drawn in that reason's colour with a legend entry
    assert "failed: robot down" in page.locator("#gantt-legend").inner_text()
    assert page.locator("#verdict").inner_text() == "FAILED"
    w.assert_clean()
    page.close()


def test_large_trace_stays_responsive(browser: Any, tmp_path: Path) -> None:
    episode = scripted_shuttle_episode(rounds=60)
    assert len(episode.trace) > 10_000
    path = report_for(episode, tmp_path / "run")
    started = time.perf_counter()
    w = open_page(browser, path)
    load = time.perf_counter() - started
    per_scrub_ms = w.page.evaluate("""() => {
        const R = window.emboteamReport, n = 100; let seed = 1;
        const rnd = () => (seed = (seed * 16807) % 2147483647) / 2147483647;
        const t0 = performance.now();
        for (let i = 0; i < n; i++) { R.setTime(R.end * rnd()); document.body.getBoundingClientRect(); }
        return (performance.now() - t0) / n; }""")
    rows_in_dom = w.page.locator("#event-list .ev-row").count()
    print(f"\nlarge trace: {len(episode.trace)} events, {episode.actions} actions, "
          f"{path.stat().st_size / 1e6:.1f} MB page, load {load:.2f} s, {per_scrub_ms:.1f} ms per scrub")
    assert load < 15, f"loading took {load:.1f} s"
    assert per_scrub_ms < 60, f"a scrub takes {per_scrub_ms:.1f} ms"
    assert rows_in_dom < 100, "the event list must render only the rows in view"
    w.assert_clean()
    w.page.close()


def test_bench_index_sorts_filters_and_links_to_episode_reports(browser: Any, tmp_path: Path) -> None:
    ok, failed = scripted_fridge_episode(), scripted_fridge_episode(seed=0)
    pairs = [("full__seed=7", ok), ("no-btc__seed=0", failed.model_copy(update={"mode": "no-btc"})),
             ("full__seed=0", failed)]
    for key, ep in pairs:
        ep.save(tmp_path / "episodes" / key)
    summary = {"suite": "mace-thor", "n": 3, "sr": 1 / 3, "gcr": 0.6}
    index = write_bench_index(tmp_path, pairs, summary, "| mode | SR |\n|---|---|\n| full | 0.5 |\n", [])
    w = open_page(browser, index)
    page = w.page
    rows = "#episodes tbody tr:not([hidden])"
    assert page.locator(rows).count() == 3
    page.click("#episodes th[data-key=gcr]")
    page.click("#episodes th[data-key=gcr]")  # descending: the successful episode first
    assert page.locator(f"{rows} td.yes").count() == 1
    assert page.locator(rows).first.locator("td.yes").count() == 1
    page.select_option("select[data-filter=mode]", "no-btc")
    assert page.locator(rows).count() == 1
    assert page.locator("#episodes-count").inner_text() == "1 of 3 shown"
    href = page.locator(f"{rows} a").first.get_attribute("href")
    assert href == "episodes/no-btc__seed%3D0/report.html"
    w.assert_clean()
    # the link opens that episode's viewer, which is itself offline and clean
    page.locator(f"{rows} a").first.click()
    page.wait_for_load_state("load")
    assert page.url == (tmp_path / "episodes" / "no-btc__seed=0" / "report.html").as_uri()
    data = page_data(page)
    assert data["meta"]["mode"] == "no-btc"
    assert [u for u in w.requests if not u.startswith("file://")] == []
    assert w.errors == []
    page.close()


def test_docs_screenshot_exists() -> None:
    """docs/report.md shows docs/img/report.png; it must be a real PNG of a report."""
    assert DOCS_IMG.is_file(), "run EMBOTEAM_DOCS_SCREENSHOT=1 pytest tests/test_report_browser.py"
    head = DOCS_IMG.read_bytes()[:24]
    assert head[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")
    assert (width, height) == (VIEWPORT["width"], VIEWPORT["height"])


def test_the_readings_considered_and_unexplained_mentions_are_listed(browser: Any, tmp_path: Path) -> None:
    """Issue 25: the report lists the offline reader's candidates (best first, with their
    scores and the doubts they settle) and the mentions nothing explained."""
    candidates = (
        {"sentence": "The potato is hot.", "goals": ["hot(Potato)"], "score": -0.44, "as_read": True,
         "resolves": []},
        {"sentence": "The potato is hot and the potato is in the microwave.",
         "goals": ["hot(Potato)", "inside(Potato, Microwave)"], "score": -1.51, "as_read": False,
         "resolves": [{"kind": "means", "span": "microwave", "choice": "left_in_device",
                       "how": "the potato is in the microwave"}]},
    )
    episode = scripted_fridge_episode().model_copy(update={"candidates": candidates, "unexplained": ("tomato",)})
    w = open_page(browser, report_for(episode, tmp_path / "run"))
    items = w.page.eval_on_selector_all("#reading-candidates li", "ls => ls.map(l => l.textContent)")
    assert items == ["-0.44  The potato is hot.",
                     "-1.51  The potato is hot and the potato is in the microwave.  "
                     "[the potato is in the microwave]"]
    notes = w.page.eval_on_selector_all("#reading-notes li", "ls => ls.map(l => l.textContent)")
    assert "unexplained: tomato (named, but in no goal)" in notes
    w.assert_clean()
    w.page.close()
