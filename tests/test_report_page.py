"""report.html and index.html in a real browser: headless Chromium opens them from disk (no network)."""

import base64
import json
import os
import platform
import re
import shlex
from datetime import datetime, timedelta, timezone
from pathlib import Path

import imageio.v3 as iio
import mujoco
import numpy as np
import pytest
from chromium import INSTALL, Chromium, executable  # tests/chromium.py (pytest puts tests/ on sys.path)
from scipy.spatial.transform import Rotation

from sim_origami import scenes
from sim_origami.cli import main
from sim_origami.presets import FAST
from sim_origami.report import VIEW_FRAMES, VIEW_INT, as_dict, motion_view, provenance
from sim_origami.report_page import write_index, write_page, write_thumbnail
from sim_origami.validation import validate

# every test here starts a browser, most after a MuJoCo run: all slow
pytestmark = [pytest.mark.skipif(executable() is None, reason=INSTALL), pytest.mark.slow]

# Evaluated in the page: the verdict text, the images and whether each decoded, and every resource reference.
PROBE = """({
  verdict: document.getElementById('verdict').textContent,
  checks: document.querySelectorAll('#checks tr').length - 1,
  images: Array.from(document.images).map(i => [i.getAttribute('src').slice(0, 15), i.complete && i.naturalWidth > 0]),
  external: Array.from(document.querySelectorAll('[src], link[href]')).map(e => e.src || e.href)
             .filter(u => !u.startsWith('data:')),
  model: document.querySelector('a[href="model.xml"]') !== null,
  links: Array.from(document.querySelectorAll('#scenes a')).map(a => a.getAttribute('href')),
})"""

# Evaluated in a report: the 3-D canvas's pixels, then again after the slider moves to the last frame.
VIEW = """(() => {
  const canvas = document.getElementById('view');
  const pixels = () => { const copy = document.createElement('canvas'); copy.width = canvas.width;
    copy.height = canvas.height; const g = copy.getContext('2d'); g.drawImage(canvas, 0, 0);
    return g.getImageData(0, 0, canvas.width, canvas.height).data; };
  const before = pixels();
  const slider = document.getElementById('view-frame');
  slider.value = slider.max;
  slider.dispatchEvent(new Event('input'));
  const after = pixels();
  let drawn = 0, changed = 0;
  for (let i = 0; i < before.length; i += 4) {
    if (before[i] < 250 || before[i + 1] < 250 || before[i + 2] < 250) drawn++;  // not the white background
    if (before[i] !== after[i] || before[i + 1] !== after[i + 1] || before[i + 2] !== after[i + 2]) changed++;
  }
  return {drawn: drawn / (before.length / 4), changed: changed / (before.length / 4), frames: +slider.max + 1,
          branches: Array.from(document.getElementById('view-branch').options).map(o => o.textContent),
          label: document.getElementById('view-input').textContent};
})()"""

INDEX = """({
  verdict: document.getElementById('verdict').textContent,
  links: Array.from(document.querySelectorAll('#scenes td.scene a')).map(a => a.getAttribute('href')),
  columns: Array.from(document.querySelectorAll('#scenes th')).map(th => th.textContent),
  thumbs: Array.from(document.querySelectorAll('#scenes img')).map(i => [i.getAttribute('src'),
          i.complete && i.naturalWidth > 0, i.width]),
  summaries: Array.from(document.querySelectorAll('#scenes td.scene small')).map(s => s.textContent),
  totals: document.getElementById('totals').textContent,
  versions: document.getElementById('versions').textContent,
})"""
PARAMS = """({
  params: Array.from(document.querySelectorAll('#params tr')).slice(1).map(r => Array.from(r.cells).map(
          c => c.textContent)),
  cpu: Array.from(document.querySelectorAll('th')).find(th => th.textContent === 'MuJoCo step CPU')
       .nextElementSibling.textContent,
  back: document.getElementById('index'),
})"""


@pytest.fixture(scope="module")
def browser():
    chromium = Chromium()
    yield chromium
    chromium.close()


COMMAND = ["validate", "bennett", "--render", "--size", "320x240", "-p", "alpha=30", "--out"]


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("runs")
    status = main([*COMMAND, str(out / "bennett")])
    return status, out


@pytest.fixture(scope="module")
def fold_run(tmp_path_factory):
    """A FOLD file's degree-4 vertex: a crease pattern, driven at e0, locking where e0 folds flat."""
    out = tmp_path_factory.mktemp("fold") / "vertex4"
    main(["validate", "--fold", str(Path(__file__).parents[1] / "docs/examples/reference/vertex4.fold"), "--out",
          str(out)])
    return out


# Evaluated in an origami report: the crease pattern's lines and marks, and the events table.
PATTERN = """(() => {
  const svg = document.getElementById('crease-pattern');
  return {
    creases: Array.from(svg.querySelectorAll('line.crease')).map(l => [l.parentNode.textContent.split(':')[0],
      l.classList[1], l.getAttribute('stroke'), +l.getAttribute('stroke-width')]),
    border: svg.querySelectorAll('line:not(.crease)').length,
    rings: Array.from(svg.querySelectorAll('circle.event')).map(c => c.textContent),
    events: Array.from(document.querySelectorAll('#events tr')).slice(1).map(r => r.cells[0].textContent),
    size: [svg.getBoundingClientRect().width, svg.getBoundingClientRect().height],
  };
})()"""


def not_blank(png: bytes) -> float:
    """Pixel standard deviation of a screenshot (a blank page gives 0)."""
    return float(np.asarray(iio.imread(png), dtype=float)[..., :3].std())


def test_report_page_renders_with_its_verdict_plot_and_animation(run, browser):
    status, out = run
    doc = json.loads((out / "bennett" / "report.json").read_text())
    page = browser.load(out / "bennett" / "report.html", PROBE)
    assert page.errors == []
    assert not_blank(page.screenshot) > 20.0  # measured about 70 (text, tables and the plot on white)
    seen = page.value
    assert seen["verdict"].startswith("PASS" if doc["passed"] else "FAIL") and status == (0 if doc["passed"] else 1)
    verdicts = len(doc["verdicts"]) + sum(len(b["verdicts"]) for b in doc["branches"])
    assert seen["checks"] == verdicts and f"{verdicts} of {verdicts}" in seen["verdict"]
    # the curves inside the page, the motion from fold.gif beside it (embedded, it was there twice)
    assert [s for s, _ in seen["images"]] == ["data:image/png;", "fold.gif"]
    assert all(decoded for _, decoded in seen["images"])
    assert seen["external"] == [(out / "bennett" / "fold.gif").as_uri()] and seen["model"]  # nothing off the disk
    assert (out / "bennett" / "model.xml").is_file()
    html = (out / "bennett" / "report.html").read_text()
    assert "data:image/gif" not in html and 'href="fold.mp4"' in html and 'href="frames/">frames/</a> (3 PNG' in html
    # measured: 64 kB (the curves 39 kB as base64, the view 10 kB), the GIF not in it
    assert len(html.encode()) < 120_000


def test_index_links_each_scene_page_with_its_verdict(run, browser):
    _, out = run
    doc = json.loads((out / "bennett" / "report.json").read_text())
    doc["thumbnail"] = write_thumbnail(out / "bennett").name  # as validate --all makes it
    failed = dict(doc, scene="bennett-copy", passed=False, thumbnail=None)
    write_index([doc, failed], out)
    page = browser.load(out / "index.html", INDEX)
    assert page.errors == []
    assert not_blank(page.screenshot) > 5.0
    seen = page.value
    assert seen["verdict"] == "1 of 2 scenes pass"
    assert seen["links"] == ["bennett/report.html", "bennett-copy/report.html"]
    assert seen["columns"] == ["", "scene", "result", "checks passed", "preset", "max path error (rad)",
                               "max closure residual (m)", "MuJoCo CPU per step (ms)"]
    # the rendered run's thumbnail (its middle frame, 200 px wide at most), decoded; none for the copy
    assert seen["thumbs"] == [["bennett/thumb.png", True, 160]]
    assert 0 < iio.imread(out / "bennett" / "thumb.png").shape[1] <= 200
    assert seen["summaries"] == [doc["summary"]] * 2 and doc["summary"].startswith("Bennett 4R")
    checks = len(doc["verdicts"]) + sum(len(b["verdicts"]) for b in doc["branches"])
    assert seen["totals"].startswith(f"1 of 2 scenes pass; {2 * checks} of {2 * checks} checks")
    made = doc["provenance"]
    assert f"sim_origami {made['sim_origami']}" in seen["versions"] and f"MuJoCo {made['mujoco']}" in seen["versions"]
    # a scene's page in validate --all links back to the index
    (out / "bennett-copy").mkdir(exist_ok=True)
    write_page(failed, out / "bennett-copy", in_index=True)
    back = browser.load(out / "bennett-copy" / "report.html", "document.getElementById('index').href")
    assert back.errors == [] and back.value == (out / "index.html").as_uri()


def test_parameters_are_shown_in_the_units_typed(run, browser):
    _, out = run
    page = browser.load(out / "bennett" / "report.html", PARAMS)
    assert page.errors == []
    rows = {r[0]: r[1:] for r in page.value["params"]}
    assert rows["alpha"][:2] == ["30", "deg"] and float(rows["alpha"][2]) == pytest.approx(np.pi / 6, rel=1e-3)
    assert rows["a"][:2] == ["1", "m"] and rows["b"][:2] == ["1.5", "m"]
    assert "ms per step" in page.value["cpu"] and "s in total" in page.value["cpu"]
    assert page.value["back"] is None  # a single run has no index to go back to


def test_the_browser_check_sees_errors_and_blank_pages(tmp_path, browser):
    # the checks above can fail: a script error, a console error and a missing file are all reported
    bad = tmp_path / "bad.html"
    bad.write_text('<!DOCTYPE html><p id="verdict">PASS</p><img src="missing.png">'
                   '<script>console.error("broken"); undefinedFunction();</script>')
    page = browser.load(bad, "document.getElementById('verdict').textContent")
    assert page.value == "PASS"
    assert len(page.errors) == 3 and "broken" in page.errors
    blank = tmp_path / "blank.html"
    blank.write_text("<!DOCTYPE html><title>blank</title>")
    assert not_blank(browser.load(blank, "1").screenshot) == 0.0


def test_report_says_what_made_the_run(run, browser):
    _, out = run
    doc = json.loads((out / "bennett" / "report.json").read_text())
    made = doc["provenance"]
    assert made["command"] == shlex.join(["sim-origami", *COMMAND, str(out / "bennett")])
    assert (made["mujoco"], made["numpy"], made["python"]) == (mujoco.__version__, np.__version__,
                                                               platform.python_version())
    assert made["sim_origami"] == doc["sim_origami"] and made["preset"] == doc["preset"]
    assert re.fullmatch(r"[0-9a-f]{4,40}(\+dirty)?", made["git_commit"])  # the tests run from the checkout
    assert timedelta(0) <= datetime.now(timezone.utc) - datetime.fromisoformat(made["date_utc"]) < timedelta(hours=1)
    assert made["machine"]["cores"] == os.cpu_count() and made["machine"]["arch"] == platform.machine()
    assert provenance(FAST)["command"] is None  # the Python API passes none
    # the parameters as typed: degrees and metres, beside the radians
    assert doc["params_user"]["alpha"] == {"value": 30.0, "unit": "deg"}
    assert doc["params_user"]["a"] == {"value": 1.0, "unit": "m"} and doc["params"]["alpha"] == pytest.approx(np.pi / 6)
    assert doc["summary"].startswith("Bennett")
    shown = browser.load(out / "bennett" / "report.html", "document.getElementById('provenance').innerText").value
    assert made["command"] in shown and f"MuJoCo, Python, numpy\t{mujoco.__version__}" in shown


def test_the_3d_view_draws_the_motion_and_follows_the_slider(run, browser):
    _, out = run
    doc = json.loads((out / "bennett" / "report.json").read_text())
    page = browser.load(out / "bennett" / "report.html", VIEW)
    assert page.errors == []
    seen = page.value
    # measured: the four links cover 2-3 % of the canvas and the last frame moves about as many pixels
    assert seen["drawn"] > 0.005 and seen["changed"] > 0.005
    assert seen["frames"] == 100 and seen["branches"] == [b["branch_requested"] for b in doc["branches"]]
    assert seen["label"].startswith("theta1 = ") and seen["label"].endswith("(frame 100 of 100)")


def test_an_origami_page_draws_its_crease_pattern_and_folds_it_in_3d(fold_run, browser):
    doc = json.loads((fold_run / "report.json").read_text())
    page = browser.load(fold_run / "report.html", PATTERN)
    assert page.errors == []
    seen = page.value
    # four creases by the side MuJoCo folded them to, the driven one thick; the border's four edges
    assert sorted(c[0] for c in seen["creases"]) == ["e0", "e1", "e2", "e3"] and seen["border"] == 4
    colours = {"M": "#d91a1a", "V": "#1a4de6"}
    assert all(colours[side] == stroke for _, side, stroke, _ in seen["creases"])
    assert sorted(side for _, side, _, _ in seen["creases"]) == ["M", "V", "V", "V"]  # degree 4: one against three
    assert {name: width for name, _, _, width in seen["creases"]}["e0"] == 4  # the driven crease (--input default)
    assert doc["input"]["drive_joint"] == "e0"
    # the lock where e0 folds flat: ringed on e0 and listed
    assert len(seen["rings"]) == 1 and seen["rings"][0].startswith("lock: crease e0 folds flat")
    assert seen["events"] == [e["kind"] for e in doc["events"]] == ["lock"]
    assert 300 < max(seen["size"]) < 600
    # the lines are the numeric trace of the file's pattern, and the error is to it: no closed form here
    curves = (fold_run / "curves.svg").read_text()
    assert "lines: numeric trace; markers: MuJoCo" in curves and "closed form" not in curves
    assert 'href="curves.svg"' in (fold_run / "report.html").read_text()
    view = browser.load(fold_run / "report.html", VIEW)
    assert view.errors == [] and view.value["drawn"] > 0.02 and view.value["changed"] > 0.005


# Evaluated in a report with several branches: the picture after each control is used.
CONTROLS = """(() => {
  const canvas = document.getElementById('view');
  const pixels = () => { const copy = document.createElement('canvas'); copy.width = canvas.width;
    copy.height = canvas.height; const g = copy.getContext('2d'); g.drawImage(canvas, 0, 0);
    return Array.from(g.getImageData(0, 0, canvas.width, canvas.height).data); };
  const differs = (a, b) => a.some((v, i) => v !== b[i]);
  const select = document.getElementById('view-branch');
  const first = pixels();
  select.value = '1';
  select.dispatchEvent(new Event('change'));
  const branch = pixels();
  const at = {clientX: 400, clientY: 250, pointerId: 1, bubbles: true};
  canvas.dispatchEvent(new PointerEvent('pointerdown', at));
  canvas.dispatchEvent(new PointerEvent('pointermove', {...at, clientX: 480, clientY: 220}));
  canvas.dispatchEvent(new PointerEvent('pointerup', at));
  const turned = pixels();
  canvas.dispatchEvent(new WheelEvent('wheel', {deltaY: -400, bubbles: true, cancelable: true}));
  const zoomed = pixels();
  return {options: Array.from(select.options).map(o => o.value), label: document.getElementById('view-input')
          .textContent, branch: differs(first, branch), turned: differs(branch, turned),
          zoomed: differs(turned, zoomed)};
})()"""


@pytest.fixture(scope="module")
def vertex4():
    return validate(scenes.get("vertex4").build())


def test_the_view_poses_are_packed_within_their_rounding(vertex4):
    view = motion_view(vertex4)
    mech, centre = vertex4.scene.mechanism, np.array(view["centre"])
    bodies = [b for b in mech.bodies if not b.spacer]
    for run, branch in zip(vertex4.runs, view["branches"], strict=True):
        ints = np.frombuffer(base64.b64decode(branch["poses"]), "<i2").astype(float).reshape(-1, len(bodies), 7)
        assert len(ints) == len(branch["input"]) == VIEW_FRAMES and np.abs(ints).max() <= VIEW_INT
        q = run.dynamic.q
        rows = np.unique(np.linspace(0, len(q) - 1, VIEW_FRAMES).round().astype(int))
        poses = mech.body_poses(q[rows])
        T = np.stack([poses[b.name] for b in bodies], 1)
        position = centre + ints[..., :3] * branch["scale"]
        assert np.abs(position - T[..., :3, 3]).max() <= 0.5 * branch["scale"] * (1 + 1e-6)
        assert np.abs(ints[..., :3]).max() > 0.99 * VIEW_INT  # the largest offset spans the int16 range
        quat = ints[..., 3:] / VIEW_INT
        R = Rotation.from_quat(quat.reshape(-1, 4)).as_matrix().reshape(T[..., :3, :3].shape)
        assert np.abs(R - T[..., :3, :3]).max() < 1e-4  # a turn under 1e-4 rad
    # the poses as 5-digit numbers were 3.3x the bytes (waterbomb-twist: 1.84 MB, 0.6 MB packed)
    assert sum(len(b["poses"]) for b in view["branches"]) <= len(view["branches"]) * VIEW_FRAMES * len(bodies) * 19


def test_the_3d_view_switches_branch_turns_and_zooms(tmp_path, browser, vertex4):
    report = vertex4
    assert len(report.runs) >= 2
    write_page(as_dict(report), tmp_path, motion_view(report))
    page = browser.load(tmp_path / "report.html", CONTROLS)
    assert page.errors == []
    seen = page.value
    assert seen["options"] == [str(k) for k in range(len(report.runs))]
    assert seen["branch"] and seen["turned"] and seen["zoomed"]
    assert seen["label"].startswith(f"{report.scene.kinematics.input_name} = ")
