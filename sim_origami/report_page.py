"""report.html per run and index.html for `validate --all`: pages that open from disk, with no network.

What a page shows is inside it (the curves plot as a base64 data URI, styles, the 3-D view's script and data
inline) except, with --render, the animation: the page shows fold.gif beside it, as its downloads link model.xml,
curves.csv and the rest (embedded, each GIF was in its run's folder twice).
"""

import base64
import html
import json
import math
import re
from pathlib import Path

import imageio.v3 as iio
import numpy as np

from .files import atomic_path, write_text

STYLE = """
body { font-family: system-ui, sans-serif; margin: 2em auto; max-width: 64em; color: #222; padding: 0 1em; }
h1 { font-size: 1.5em; } h2 { font-size: 1.15em; margin-top: 1.6em; }
table { border-collapse: collapse; margin: 0.5em 0; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; vertical-align: top; }
th { background: #f2f2f2; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
.pass { color: #11702d; font-weight: 600; } .fail { color: #b3131b; font-weight: 600; }
.verdict { font-size: 1.3em; padding: 0.3em 0.8em; border-radius: 4px; display: inline-block; }
.verdict.pass { background: #e3f4e8; } .verdict.fail { background: #fbe4e5; }
img { max-width: 100%; border: 1px solid #ddd; }
#view { width: 100%; max-width: 800px; aspect-ratio: 8 / 5; border: 1px solid #ddd; touch-action: none; cursor: grab; }
.controls { display: flex; gap: 0.8em; align-items: center; flex-wrap: wrap; max-width: 800px; }
.controls input[type=range] { flex: 1; min-width: 12em; }
"""
# index.html's thumbnails: width in pixels.
THUMB_WIDTH = 200
# The 3-D view's renderer (package data), inlined into each page.
VIEWER = Path(__file__).with_name("assets") / "viewer.js"


def _e(value) -> str:
    return html.escape(str(value))


def _num(value) -> str:
    """A number as text: 3 significant digits, '-' for none or NaN."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    if isinstance(value, bool | str):
        return _e(value)
    return f"{value:.3g}"


def _deg(radians: float | None) -> str:
    """An angle in radians as degrees (as typed on the command line), 4 significant digits."""
    return "-" if radians is None else f"{math.degrees(radians):.4g}"


def _status(passed: bool) -> str:
    return f'<span class="{"pass" if passed else "fail"}">{"PASS" if passed else "FAIL"}</span>'


def _data_uri(path: Path, mime: str) -> str | None:
    """The file as a base64 data URI, or None if it does not exist."""
    if not path.is_file():
        return None
    return f"data:{mime};base64,{base64.b64encode(path.read_bytes()).decode('ascii')}"


def _verdict_rows(verdicts: list[dict]) -> str:
    rows = []
    for v in verdicts:
        rows.append(f"<tr data-id=\"{_e(v.get('id', ''))}\"><td>{_status(v['passed'])}</td><td>{_e(v['name'])}</td>"
                    f"<td class=num>{_num(v['measured'])}</td><td class=num>{_num(v['tolerance'])}</td>"
                    f"<td>{_e(v.get('detail', ''))}</td></tr>")
    return "\n".join(rows)


def _provenance(doc: dict) -> str:
    """What made the run (report.json's `provenance`): versions, commit, command, date, machine."""
    p = doc.get("provenance")
    if p is None:  # a report.json written before provenance was recorded
        return f'<p id="provenance">sim_origami {_e(doc.get("sim_origami", "?"))}</p>'
    machine = p["machine"]
    rows = [
        ("command", f"<code>{_e(p['command'])}</code>" if p["command"] else "the Python API"),
        ("date (UTC)", _e(p["date_utc"])),
        ("sim_origami", _e(p["sim_origami"]) + (f" (commit {_e(p['git_commit'])})" if p["git_commit"] else "")),
        ("MuJoCo, Python, numpy", f"{_e(p['mujoco'])}, {_e(p['python'])}, {_e(p['numpy'])}"),
        ("preset", _e(p["preset"])),
        ("machine", f"{_e(machine['os'])}, {_e(machine['arch'])}, {_e(machine['cores'])} cores"),
    ]
    return '<table id="provenance">' + "".join(f"<tr><th>{k}</th><td>{v}</td></tr>" for k, v in rows) + "</table>"


# Crease colours on the pattern drawing, as in the 3-D view: mountain red, valley blue, flat grey.
SIDE_COLOURS = {"M": "#d91a1a", "V": "#1a4de6", "F": "#888888"}
PATTERN_PX = 520  # the drawing's larger side


def _pattern_svg(pattern: dict, events: list[dict]) -> str:
    """
    The crease pattern as inline SVG: border black, creases by the side they folded to in the first run (dashed
    where that is against their letter), driven creases thick, creases an event names ringed.
    """
    xy = [(pattern["vertices"][2 * i], pattern["vertices"][2 * i + 1]) for i in range(len(pattern["vertices"]) // 2)]
    xs, ys = [p[0] for p in xy], [p[1] for p in xy]
    span = max(max(xs) - min(xs), max(ys) - min(ys)) or 1.0
    pad = 14
    scale = (PATTERN_PX - 2 * pad) / span
    width, height = (max(xs) - min(xs)) * scale + 2 * pad, (max(ys) - min(ys)) * scale + 2 * pad

    def at(i: int) -> tuple[float, float]:  # y up on paper, down in SVG
        return (xy[i][0] - min(xs)) * scale + pad, (max(ys) - xy[i][1]) * scale + pad

    def line(a: int, b: int, attrs: str) -> str:
        (x1, y1), (x2, y2) = at(a), at(b)
        return f'<line x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}" {attrs}/>'

    parts = [line(a, b, 'stroke="#222" stroke-width="1.5"') for a, b in pattern["border"]]
    named = {}
    for e in events:
        for c in pattern["creases"]:
            if re.search(rf"\b{re.escape(c['name'])}\b", e.get("detail", "")):
                named.setdefault(c["name"], []).append(e)
    for c in pattern["creases"]:
        a, b = c["ends"]
        against = c["assignment"] in "MV" and c["side"] in "MV" and c["assignment"] != c["side"]
        driven = c["name"] in pattern["driven"]
        title = f"{c['name']}: assigned {c['assignment']}, folded {c['side']}" + (" (driven)" if driven else "")
        attrs = (f'stroke="{SIDE_COLOURS[c["side"]]}" stroke-width="{4 if driven else 1.6}"'
                 + (' stroke-dasharray="6 4"' if against else "") + f' class="crease {c["side"]}"')
        parts.append(f"<g><title>{_e(title)}</title>{line(a, b, attrs)}</g>")
        (x1, y1), (x2, y2) = at(a), at(b)
        if driven:
            parts.append(f'<text x="{(x1 + x2) / 2 + 4:.1f}" y="{(y1 + y2) / 2 - 4:.1f}" font-size="11">'
                         f"{_e(c['name'])} (driven)</text>")
        for e in named.get(c["name"], []):
            parts.append(f'<circle class="event" cx="{(x1 + x2) / 2:.1f}" cy="{(y1 + y2) / 2:.1f}" r="7" '
                         f'fill="none" stroke="#e08000" stroke-width="2.5"><title>{_e(e["kind"])}: '
                         f"{_e(e['detail'])}</title></circle>")
    svg = (f'<svg id="crease-pattern" xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" '
           f'height="{height:.0f}" viewBox="0 0 {width:.1f} {height:.1f}" role="img" aria-label="crease pattern">'
           f'{"".join(parts)}</svg>')
    return f"""<h2>Crease pattern</h2>
<p><small>As cut, flat; each crease coloured by the side it folded to in MuJoCo's run of the first branch:
mountain <span style="color:{SIDE_COLOURS["M"]}">red</span>, valley <span style="color:{SIDE_COLOURS["V"]}">blue</span>,
flat grey; dashed against its letter; the driven crease thick; a ring marks a crease an event names (hover for
details).</small></p>
{svg}"""


def _events(events: list[dict]) -> str:
    """The events on the path (bifurcation, lock, blockage, contact...) with their inputs, as a table."""
    rows = "".join(
        f"<tr><td>{_e(e['kind'])}</td><td class=num>{_num(math.degrees(e['input_rad']))}</td>"
        f"<td>{_e(', '.join(e.get('branches', [])))}</td><td>{_e(e.get('detail', ''))}</td></tr>"
        for e in events
        if e.get("input_rad") is not None
    )
    if not rows:
        return "<h2>Events on the path</h2>\n<p>None.</p>"
    return ("<h2>Events on the path</h2>\n<table id=\"events\"><tr><th>event</th><th>input (deg)</th>"
            f"<th>branches</th><th>what</th></tr>{rows}</table>")


def _view(view: dict | None) -> str:
    """The interactive 3-D view of the motion (`report.motion_view`'s data, inline), or nothing without data."""
    if not view or not view["branches"]:
        return ""
    data = json.dumps(view, separators=(",", ":")).replace("</", "<\\/")  # no '</script>' inside the data
    return f"""<h2>Motion in 3-D</h2>
<p id="view-note"><small>MuJoCo's run, every body as simulated: drag to turn, wheel to zoom; paper front
<span style="background:#f5dba3">&nbsp;&nbsp;</span> and back <span style="background:#9ebde0">&nbsp;&nbsp;</span>,
creases mountain <span style="color:{SIDE_COLOURS["M"]}">red</span>,
valley <span style="color:{SIDE_COLOURS["V"]}">blue</span>.</small></p>
<canvas id="view" width="800" height="500"></canvas>
<div class="controls"><button id="view-play" type="button">play</button>
<input id="view-frame" type="range" min="0" max="0" value="0" aria-label="frame">
<select id="view-branch" aria-label="branch"></select> <span id="view-input"></span></div>
<script type="application/json" id="motion-data">{data}</script>
<script>{VIEWER.read_text()}</script>"""


def _step_cpu(timings: dict) -> str:
    """MuJoCo's stepping CPU per step (ms) and in total (s): the total alone hid a scene's step cost."""
    total, steps = timings.get("mujoco_step_cpu_s"), timings.get("mujoco_steps")
    if total is None:
        return "-"
    if not steps:
        return f"{_num(total)} s in total"
    return f"{_num(total / steps * 1e3)} ms per step ({int(steps)} steps, {_num(total)} s in total)"


def _params(doc: dict) -> str:
    """The parameters in the units typed (`params_user`: deg, m) beside the API's radians and metres."""
    api = doc["params"]
    if not api:
        return "<p>None.</p>"
    typed = doc.get("params_user") or {}
    rows = "".join(
        f"<tr><td>{_e(name)}</td><td class=num>{_e(_typed(typed[name]['value']))}</td><td>{_e(typed[name]['unit'])}"
        f"</td><td class=num>{_num(value)}</td></tr>"
        if name in typed
        else f"<tr><td>{_e(name)}</td><td class=num>-</td><td></td><td class=num>{_num(value)}</td></tr>"
        for name, value in api.items()
    )
    return ('<table id="params"><tr><th>parameter</th><th>value</th><th>unit</th><th>API value (rad, m)</th></tr>'
            f"{rows}</table>")


def _typed(value) -> str:
    """A parameter as people type it: up to 10 significant digits (30 deg, not 29.999999999999996)."""
    return "-" if value is None else f"{value:.10g}"


def page(doc: dict, out: Path, view: dict | None = None, in_index: bool = False) -> str:
    """
    The HTML of one run's report (`doc` as in report.json), embedding out/curves.png if present, showing
    out/fold.gif from beside it, and the 3-D view of `view` (`report.motion_view`); `in_index`: the run is one of
    `validate --all`'s, whose index.html is one folder up.
    """
    scene, passed = doc["scene"], doc["passed"]
    verdicts = doc["verdicts"] + [v for b in doc["branches"] for v in b["verdicts"]]
    key = [
        ("preset", doc["preset"]),
        ("seed", doc["seed"]),
        ("input", f"{doc['input']['name']} (drives {doc['input']['drive_joint']})"),
        ("max path error (rad)", _num(doc["angle_error_max_rad"])),
        ("max closure residual (m)", _num(doc["closure_residual_max_m"])),
        ("MuJoCo step CPU", _step_cpu(doc["timings_s"])),
    ]
    if "render" in doc:
        render = doc["render"]
        key.append(("seconds per frame", f"{_num(render['seconds_per_frame'])} ({render['gl_renderer']})"))
    branches = "\n".join(
        f"<tr><td>{_e(b['branch_requested'])}</td><td>{_e(b['branch_followed'] or '-')}</td>"
        f"<td class=num>{_deg(b['input_range_rad'][0])} .. {_deg(b['input_range_rad'][1])}</td>"
        f"<td class=num>{_num(b['angle_error_max_rad'])}</td><td class=num>{_num(b['closure_residual_max_m'])}</td>"
        f"<td class=num>{b['steps']}</td></tr>"
        for b in doc["branches"]
    )
    params = _params(doc)
    adjusted = "".join(
        f"<tr><td>{_e(a['name'])}</td><td class=num>{_num(a['given'])}</td><td class=num>{_num(a['value'])}</td>"
        f"<td class=num>{_num(a['moved'])}</td><td class=num>{_num(a['precision'])}</td>"
        f"<td class=num>{_num(a['ratio'])}</td><td>{_e(a['unit'])}</td></tr>"
        for a in doc.get("adjustments", [])
    )
    if adjusted:
        adjusted = (
            "<h2>Adjusted to the nearest exact model</h2>\n<p>The values as given meet an exact condition only "
            "within their precision (half a unit in the last digit given); the model validated is the nearest one "
            "that meets it exactly.</p>\n<table id=\"adjustments\"><tr><th>value</th><th>given</th>"
            "<th>validated</th><th>moved</th><th>precision</th><th>moved / precision</th><th>unit</th></tr>"
            f"{adjusted}</table>"
        )
    figures = []
    curves = _data_uri(out / "curves.png", "image/png")
    if curves:
        vector = ""
        if (out / "curves.svg").is_file():
            vector = ' (<a href="curves.svg">curves.svg</a>: the same as a vector drawing)'
        figures.append(f'<h2>Curves: the reference against MuJoCo</h2>\n<p><small>Joint angles, then each joint\'s '
                       "error with the check's tolerance (dashed) and the events on the branch marked"
                       f"{vector}.</small></p>\n"
                       f'<img alt="curves of {_e(scene)}" src="{curves}">')
    if (out / "fold.gif").is_file():  # beside the page: as base64, GIFs were about 21 of the main job's 37 MB of pages
        video = ' (<a href="fold.mp4">fold.mp4</a>: full size)' if (out / "fold.mp4").is_file() else ""
        figures.append(f"<h2>Motion</h2>\n<p><small>MuJoCo's frames, from fold.gif beside this page{video}."
                       f'</small></p>\n<img id="motion" alt="{_e(scene)} folding" src="fold.gif">')
    curves_file = "curves.csv.gz" if (out / "curves.csv.gz").is_file() else "curves.csv"
    downloads = ['<a href="model.xml" download>model.xml</a> (the MJCF that was stepped)',
                 '<a href="report.json">report.json</a>', f'<a href="{curves_file}">{curves_file}</a>']
    if (out / "curves.svg").is_file():
        downloads.append('<a href="curves.svg">curves.svg</a>')
    stills = len(list((out / "frames").glob("frame_*.png")))
    if stills:
        downloads.append(f'<a href="frames/">frames/</a> ({stills} PNG frame{"s" if stills > 1 else ""})')
    if (out / "motion.fold").is_file():
        downloads.append('<a href="motion.fold" download>motion.fold</a>')
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{_e(scene)}: {"PASS" if passed else "FAIL"}</title>
<style>{STYLE}</style></head>
<body>
{'<p><a id="index" href="../index.html">&larr; every scene (index.html)</a></p>' if in_index else ""}
<h1>sim_origami: {_e(scene)}</h1>
{f"<p>{_e(doc['summary'])}</p>" if doc.get("summary") else ""}
<p id="verdict" class="verdict {"pass" if passed else "fail"}">{"PASS" if passed else "FAIL"}:
{sum(v["passed"] for v in verdicts)} of {len(verdicts)} checks passed</p>
<h2>Key numbers</h2>
<table>{"".join(f"<tr><th>{_e(k)}</th><td>{_e(v)}</td></tr>" for k, v in key)}</table>
<h2>Checks</h2>
<table id="checks"><tr><th>result</th><th>check</th><th>measured</th><th>tolerance</th><th>how</th></tr>
{_verdict_rows(verdicts)}
</table>
<h2>Branches</h2>
<table><tr><th>requested</th><th>followed</th><th>input (deg)</th><th>max path error (rad)</th>
<th>max closure residual (m)</th><th>steps</th></tr>
{branches}
</table>
<h2>Parameters</h2>
{params}
{adjusted}
{_view(view)}
{_pattern_svg(view["pattern"], doc.get("events", [])) if view and "pattern" in view else ""}
{_events(doc.get("events", []))}
{chr(10).join(figures)}
<h2>Files</h2>
<p>{" &middot; ".join(downloads)}</p>
<h2>Provenance</h2>
{_provenance(doc)}
</body></html>
"""


def write_page(doc: dict, out: str | Path, view: dict | None = None, in_index: bool = False) -> Path:
    """Write out/report.html (atomically), with the 3-D view of `view` (`report.motion_view`) if given."""
    out = Path(out)
    return write_text(out / "report.html", page(doc, out, view, in_index))


def write_thumbnail(out: str | Path) -> Path | None:
    """
    out/thumb.png, at most THUMB_WIDTH pixels wide, for the index: the middle rendered frame (the fold under way)
    if frames were rendered, else the curves plot; None without either.
    """
    out = Path(out)
    frames = sorted((out / "frames").glob("frame_*.png"))
    source = frames[len(frames) // 2] if frames else out / "curves.png"
    if not source.is_file():
        return None
    image = np.asarray(iio.imread(source))[..., :3].astype(float)
    k = max(1, -(-image.shape[1] // THUMB_WIDTH))  # whole pixels averaged k x k
    h, w = image.shape[0] // k * k, image.shape[1] // k * k
    small = image[:h, :w].reshape(h // k, k, w // k, k, 3).mean(axis=(1, 3)).round().astype(np.uint8)
    with atomic_path(out / "thumb.png") as tmp:
        iio.imwrite(tmp, small, extension=".png")
    return out / "thumb.png"


def index(docs: list[dict]) -> str:
    """
    The HTML of `validate --all`'s index: one row per scene (its thumbnail, name and summary linking its
    report.html in <scene>/, verdict, checks, errors, MuJoCo's step cost), then the versions and the totals.
    """
    passed = sum(d["passed"] for d in docs)
    rows = []
    for d in docs:
        name = _e(d["scene"])
        checks = d["verdicts"] + [v for b in d.get("branches", []) for v in b["verdicts"]]
        thumb = (f'<a href="{name}/report.html"><img class="thumb" alt="{name}" src="{name}/{_e(d["thumbnail"])}"></a>'
                 if d.get("thumbnail") else "")
        timings = d.get("timings_s", {})
        per_step = (f"{_num(timings['mujoco_step_cpu_s'] / timings['mujoco_steps'] * 1e3)}"
                    if timings.get("mujoco_steps") else "-")
        rows.append(
            f'<tr><td>{thumb}</td><td class="scene"><a href="{name}/report.html">{name}</a>'
            f"<br><small>{_e(d.get('summary', ''))}</small></td><td>{_status(d['passed'])}</td>"
            f"<td class=num>{sum(v['passed'] for v in checks)} / {len(checks)}</td><td>{_e(d['preset'])}</td>"
            f"<td class=num>{_num(d.get('angle_error_max_rad'))}</td>"
            f"<td class=num>{_num(d.get('closure_residual_max_m'))}</td><td class=num>{per_step}</td></tr>"
        )
    made = next((d["provenance"] for d in docs if d.get("provenance")), None)
    versions = ""
    if made:
        commit = f" (commit {_e(made['git_commit'])})" if made["git_commit"] else ""
        versions = (f'<p id="versions">sim_origami {_e(made["sim_origami"])}{commit}, MuJoCo {_e(made["mujoco"])}, '
                    f"Python {_e(made['python'])}, numpy {_e(made['numpy'])}; {_e(made['machine']['os'])}, "
                    f"{_e(made['machine']['cores'])} cores; {_e(made['date_utc'])}"
                    + (f"; <code>{_e(made['command'])}</code>" if made["command"] else "") + "</p>")
    checks = [v for d in docs for v in d["verdicts"] + [v for b in d.get("branches", []) for v in b["verdicts"]]]
    cpu = sum(d.get("timings_s", {}).get("total_cpu_s", 0.0) for d in docs)
    totals = (f'<p id="totals">{passed} of {len(docs)} scenes pass; {sum(v["passed"] for v in checks)} of '
              f"{len(checks)} checks; {_num(cpu)} s of CPU in the validations.</p>")
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>sim_origami: {passed} of {len(docs)} scenes pass</title>
<style>{STYLE} img.thumb {{ width: 160px; height: 120px; object-fit: contain; max-width: none; }}</style></head>
<body>
<h1>sim_origami validation</h1>
<p id="verdict" class="verdict {"pass" if passed == len(docs) else "fail"}">{passed} of {len(docs)} scenes pass</p>
{totals}
{versions}
<table id="scenes"><tr><th></th><th>scene</th><th>result</th><th>checks passed</th><th>preset</th>
<th>max path error (rad)</th><th>max closure residual (m)</th><th>MuJoCo CPU per step (ms)</th></tr>
{chr(10).join(rows)}
</table>
</body></html>
"""


def write_index(docs: list[dict], out: str | Path) -> Path:
    """Write out/index.html (atomically)."""
    return write_text(Path(out) / "index.html", index(docs))
