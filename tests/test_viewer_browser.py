"""The viewer page in a real headless browser (Debian's chromium, driven by selenium).

`make test` installs chromium and chromium-driver when it runs as root
(`make test-deps`); elsewhere this test is skipped with the reason.
"""

from __future__ import annotations

import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from nowplan.viz.viewer import write_viewer

CHROMIUM = Path("/usr/bin/chromium")
CHROMEDRIVER = Path("/usr/bin/chromedriver")
DATA = Path(__file__).parent / "data"

if not (CHROMIUM.exists() and CHROMEDRIVER.exists()):
    pytest.skip(
        f"{CHROMIUM} or {CHROMEDRIVER} missing: run 'make test-deps' as root "
        "(apt-get install chromium chromium-driver) to run the browser test",
        allow_module_level=True,
    )
webdriver = pytest.importorskip(
    "selenium.webdriver", reason="selenium is not installed: pip install -e '.[test]'"
)

# starting chromium and chromedriver has no time-out of its own
pytestmark = pytest.mark.timeout(120)

FLAGS = (
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--disable-dev-shm-usage", "--window-size=1400,1000",
)


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    from selenium.webdriver.chrome.service import Service

    profile = tempfile.TemporaryDirectory(prefix="nowplan-chromium-")
    opts = webdriver.ChromeOptions()
    opts.binary_location = str(CHROMIUM)
    for flag in (*FLAGS, f"--user-data-dir={profile.name}"):
        opts.add_argument(flag)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    # an explicit driver path: selenium-manager is never asked to download anything
    driver = webdriver.Chrome(service=Service(str(CHROMEDRIVER)), options=opts)
    try:
        yield driver
    finally:
        driver.quit()
        profile.cleanup()


def _open(browser: Any, page: Path) -> list[dict[str, Any]]:
    """Load a page, wait for the viewer to finish drawing, return the console messages."""
    from selenium.webdriver.support.ui import WebDriverWait

    browser.get_log("browser")  # drop messages from earlier pages
    browser.get(page.resolve().as_uri())
    WebDriverWait(browser, 10).until(lambda d: d.execute_script("return document.body.dataset.ready") == "true")
    return list(browser.get_log("browser"))


def _errors(logs: list[dict[str, Any]]) -> list[dict[str, Any]]:
    return [e for e in logs if e.get("level") in ("SEVERE", "ERROR")]


def _count(browser: Any, selector: str) -> int:
    return int(browser.execute_script("return document.querySelectorAll(arguments[0]).length", selector))


def test_logistics_trace_tree_and_timeline(browser: Any, tmp_path: Path) -> None:
    from selenium.webdriver.common.by import By

    page = write_viewer(DATA / "trace_logistics_small_failures.jsonl", tmp_path / "logistics.html")
    logs = _open(browser, page)
    assert _errors(logs) == [], logs
    assert browser.execute_script("return performance.getEntriesByType('resource').length") == 0
    # 23 plans, of which 3 -> 4 and 22 -> 23 are one-step plans refined for the same goal: shown once
    assert _count(browser, ".plan:not(.root):not(.failed-plan)") == 21
    assert _count(browser, "#plan-3, #plan-22") == 0
    assert browser.find_element(By.CSS_SELECTOR, "#plan-4 > .plan-head .plan-title").text == "Plan 3 → 4"
    root_head = browser.find_element(By.CSS_SELECTOR, "#plan-root > .plan-head").text
    assert "The run's goal" in root_head and "None" not in root_head
    assert _count(browser, "#plan-root > .children > .branch > .plan") == 4  # the first plan and 3 replans
    replans = browser.find_element(By.CSS_SELECTOR, "#plan-root > .plan-head .badge.replan").text
    assert replans == "replan ← failure: a plan was popped before finishing ×3"
    step = browser.find_element(By.ID, "p4-s1")
    assert "(drive_truck truck1 c1-l2 c1-l0 c1)" in step.text and "executed" in step.get_attribute("class")
    assert "primitive" in step.get_attribute("class")
    # plan 4 (shown for plan 3) hangs under step 1 of plan 2, which plan 3 refines
    assert browser.execute_script(
        "return document.getElementById('plan-4').parentElement.parentElement.parentElement.id"
    ) == "plan-2"
    assert "popped: not applicable" in browser.find_element(By.CSS_SELECTOR, "#plan-1 > .plan-head .badge.pop").text
    assert _count(browser, "#plan-1 > .steps .node.op.unselected") == 4  # steps 3-6 never reached
    assert _count(browser, "#tree .node.op.failed") == 3
    assert _count(browser, "#timeline li.ev-action") == 15
    assert _count(browser, "#timeline li.ev-failure") == 3
    assert _count(browser, "#timeline li.ev-push.hidden") == 24  # push/step hidden by default
    # collapsing a plan hides its sub-plans
    child = browser.find_element(By.ID, "plan-2")
    assert child.is_displayed()
    browser.find_element(By.CSS_SELECTOR, "#plan-1 > .plan-head > .toggle").click()
    assert not child.is_displayed()


def test_frames_and_hostile_strings(browser: Any, tmp_path: Path) -> None:
    from selenium.webdriver.common.by import By

    page = write_viewer(DATA / "trace_toy_frames.jsonl", tmp_path / "toy.html")
    logs = _open(browser, page)
    assert _errors(logs) == [], logs
    assert browser.execute_script("return window.__pwned === undefined")
    assert browser.execute_script("return performance.getEntriesByType('resource').length") == 0
    # trace strings are shown as text, not markup
    assert '<img src=x onerror="window.__pwned=1">' in browser.find_element(By.ID, "run").text
    assert _count(browser, "#tree img, #timeline img") == 0
    note = browser.find_element(By.CSS_SELECTOR, "#timeline li.ev-note").text
    assert "</script><script>window.__pwned=2</script>" in note
    # the tree: root -> plan 1 -> (plan 2, a failed planner call) under step 1
    assert _count(browser, ".plan:not(.root):not(.failed-plan)") == 2
    assert "node_limit" in browser.find_element(By.CSS_SELECTOR, "#plan-1 .failed-plan").text
    assert "replan ← failure" in browser.find_element(By.CSS_SELECTOR, "#plan-1 > .plan-head .badge.replan").text
    assert "slipped" in browser.find_element(By.ID, "p2-s2").text
    # frames: two embedded images that decode, one remote image refused; linked from the timeline
    sizes = browser.execute_script(
        "return [...document.querySelectorAll('#frames img')].map(i => [i.complete, i.naturalWidth])"
    )
    assert sizes == [[True, 48], [True, 48]]
    assert "image not embedded" in browser.find_element(By.ID, "frames").text
    link = browser.find_element(By.CSS_SELECTOR, "#ev-9 a.frame-link")
    assert link.get_attribute("href").endswith("#frame-11")
    link.click()
    assert browser.execute_script("return location.hash") == "#frame-11"


DEMOS = ("logistics", "namo", "pieces", "marsupial", "kitchen")


@pytest.fixture(scope="module")
def demo_pages(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """Each demo run once into a scratch folder; its viewer page by domain."""
    import contextlib
    import io as _io

    from nowplan.cli import main as cli_main

    root = tmp_path_factory.mktemp("demos")
    pages = {}
    for domain in DEMOS:
        with contextlib.redirect_stdout(_io.StringIO()):
            assert cli_main(["demo", domain, "--out", str(root / domain)]) == 0
        pages[domain] = root / domain / "trace.html"
    return pages


@pytest.mark.slow
@pytest.mark.timeout(600)
@pytest.mark.parametrize("domain", DEMOS)
def test_each_demo_page_shows_plans_timeline_and_frames(browser: Any, demo_pages: dict[str, Path],
                                                       domain: str, tmp_path: Path) -> None:
    logs = _open(browser, demo_pages[domain])
    assert _errors(logs) == [], logs
    assert _count(browser, "#tree .plan:not(.root)") >= 1  # the plans
    assert _count(browser, "#timeline li.ev-action") >= 1  # the timeline
    images = browser.execute_script(
        "return [...document.querySelectorAll('#frames img')].map(i => [i.complete, i.naturalWidth])")
    assert images and all(done and width > 0 for done, width in images)  # the frames decode
    # no plan box runs off the page: wide plans scroll inside their box
    overflow = browser.execute_script(
        "const w = document.getElementById('tree').getBoundingClientRect().right + 1;"
        "return [...document.querySelectorAll('#tree .plan')].filter(p => p.getBoundingClientRect().right > w)"
        ".length")
    assert overflow == 0
    shot = tmp_path / f"{domain}.png"
    assert browser.save_screenshot(str(shot)) and shot.stat().st_size > 10_000
