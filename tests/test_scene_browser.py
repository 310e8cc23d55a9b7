"""The interactive scene page in a real browser (headless Debian chromium).

The page written by ``Scene.to_html`` plays by itself on the page's timer, so the frame it shows
is a function of the page's clock: headless chromium's virtual time (``--virtual-time-budget``)
advances that clock deterministically, however loaded the machine is. The autoplaying page is
opened at two virtual-time budgets and its DOM read (``--dump-dom``): the frame shown advances with
the budget, and the slider, the time panel and the plotted points all show that frame. A screenshot
of the page (without autoplay: headless chromium does not finish a screenshot of a page that keeps
redrawing) must show a picture, and the browser must log no JavaScript error. Skipped when chromium
is absent outside CI; in CI (``CI=true``) ``.ci/run`` installs it, so its absence is a failure. The
last test (no browser) checks that the command line prices and refuses a page like a GIF.
"""
from __future__ import annotations

import html
import json
import os
import re
import shutil
import subprocess

import numpy as np
import pytest

pytest.importorskip("plotly")
Image = pytest.importorskip("PIL.Image")

import hyperrotor as hr  # noqa: E402
from hyperrotor.classical import Scene, hypercube_vertices  # noqa: E402

#: Written into the page copies under test: every error (uncaught or console.error) becomes a log
#: line, and after every redraw the graph div gets the x coordinates of the points it plots.
_HOOK = ("<script>window.addEventListener('error',function(e){console.log('HRJSERROR '+e.message)});"
         "var _ce=console.error;console.error=function(){console.log('HRJSERROR '+Array.prototype.join.call("
         "arguments,' '));_ce.apply(console,arguments)};"
         "var _hrw=setInterval(function(){var gd=document.querySelector('.js-plotly-plot');if(!gd||!gd.on){return;}"
         "clearInterval(_hrw);gd.on('plotly_afterplot',function(){gd.setAttribute('data-probe-x',"
         "JSON.stringify(gd.data[1].x));});},20);</script>")
#: Virtual times (ms) at which the autoplaying page is read: the autoplay shows the next frame 80 ms
#: after the previous one is drawn (frames 5 and 10 here, well short of the 40 frames of one loop).
#: Each frame drawn costs real time (software WebGL), so the budgets are short.
BUDGETS = (300, 700)


def _chromium() -> str:
    exe = shutil.which("chromium") or ("/usr/bin/chromium" if os.path.exists("/usr/bin/chromium") else None)
    if exe is None:
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail("chromium is missing in CI: .ci/run must install Debian's chromium (apt-get install -y chromium)")
        pytest.skip("chromium is not installed (apt-get install -y chromium); the CI installs it")
    return exe


def _chrome(exe: str, page, profile, budget_ms: int, action: list[str]) -> subprocess.CompletedProcess:
    cmd = [exe, "--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader", "--disable-quic",
           "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync",
           "--hide-scrollbars", f"--user-data-dir={profile}", f"--virtual-time-budget={budget_ms}",
           "--window-size=1000,700", "--enable-logging=stderr", "--v=0", *action, f"file://{page}"]
    # headless chromium's virtual time occasionally never ends (seen about once in ten runs on a loaded
    # machine, with any page): one retry with a fresh profile, then a failure
    for attempt in range(2):
        try:
            return subprocess.run(cmd, capture_output=True, text=True, timeout=120)
        except subprocess.TimeoutExpired:
            if attempt:
                raise
            cmd[cmd.index(f"--user-data-dir={profile}")] = f"--user-data-dir={profile}-retry"
    raise AssertionError("unreachable")


def _shown(dom: str) -> dict:
    """What the page shows in its DOM: the frame, the slider's and the time panel's times, the points' x."""
    def attr(pattern):
        m = re.search(pattern, dom)
        return html.unescape(m.group(1)) if m else None
    panel = attr(r'<text class="annotation-text"[^>]*data-unformatted="([^"]*)"')
    probe = attr(r'data-probe-x="([^"]*)"')
    frame = attr(r'data-frame="(\d+)"')
    return {"frame": -1 if frame is None else int(frame),  # -1: the page says nothing of its frame
            "slider": attr(r'<text class="slider-label"[^>]*data-unformatted="([^"]*)"'),
            "panel": re.match(r"<b>(t = [^<]*)</b>", panel).group(1) if panel else None,
            "x": None if probe is None else [np.nan if v is None else v for v in json.loads(probe)]}


@pytest.fixture(scope="module")
def shots(tmp_path_factory):
    exe = _chromium()
    tmp = tmp_path_factory.mktemp("scene_browser")
    N = 4
    scene = Scene(hr.RigidBody(hr.Inertia.quartet(0.5, axis=N, N=N)), 0.3 * np.arange(1, 7), np.linspace(0, 12, 40),
                  points=hypercube_vertices(N), axes=(1, 2, 3, 4))
    page, still = tmp / "scene.html", tmp / "still.html"
    scene.to_html(page)
    scene.to_html(still, auto_play=False)
    text = page.read_text(encoding="utf-8")
    probe, still_probe = tmp / "probe.html", tmp / "still_probe.html"
    probe.write_text(text.replace("<head>", "<head>" + _HOOK, 1), encoding="utf-8")
    still_probe.write_text(still.read_text(encoding="utf-8").replace("<head>", "<head>" + _HOOK, 1), encoding="utf-8")
    logs, doms = [], []
    for budget in BUDGETS:
        proc = _chrome(exe, probe, tmp / f"profile{budget}", budget, ["--dump-dom"])
        assert "</html>" in proc.stdout, f"chromium dumped no page (exit {proc.returncode}):\n{proc.stderr[-2000:]}"
        logs.append(proc.stderr)
        doms.append(_shown(proc.stdout))
    png = tmp / "still.png"
    proc = _chrome(exe, still_probe, tmp / "profile_still", 100, [f"--screenshot={png}"])  # drawn at load
    assert png.exists(), f"chromium wrote no screenshot (exit {proc.returncode}):\n{proc.stderr[-2000:]}"
    logs.append(proc.stderr)
    image = np.asarray(Image.open(png).convert("RGB")).astype(np.int16)
    frames = [[np.nan if v is None else v for v in f.data[1].x] for f in scene.to_plotly().frames]
    times = [f"t = {x:.4g}" for x in scene.t]
    return text, logs, doms, image, frames, times


def test_page_is_self_contained(shots):
    text, *_ = shots
    # plotly.js is inside the page, and nothing is loaded from elsewhere (no src=, no link to a stylesheet)
    assert re.search(r"<script[^>]*\bsrc\s*=", text, re.I) is None
    assert re.search(r"<link[^>]*\bhref\s*=", text, re.I) is None
    assert "Plotly.newPlot" in text and len(text) > 3_000_000  # the library itself (MBs), not a loader


def test_page_draws_something(shots):
    image = shots[3]
    non_white = np.any(image < 235, axis=-1)
    assert non_white.mean() > 0.05, f"only {non_white.mean():.3%} of the screenshot is drawn: a blank page"
    assert len(np.unique(image.reshape(-1, 3), axis=0)) > 50  # a picture, not a flat colour
    # the 3D view (left two thirds) holds the body, not only the panel and the controls
    view = np.any(image[100:600, :600] < 200, axis=-1)   # edges, points and tick labels (~1.2%)
    assert view.mean() > 0.004, f"only {view.mean():.3%} of the 3D view is drawn: no body"


def test_page_animates(shots):
    """The autoplay advances with the page's clock, and the view, the slider and the panel move together."""
    _, _, doms, _, frames, times = shots
    shown = [d["frame"] for d in doms]
    assert 1 <= shown[0] < shown[1], f"frames shown at virtual times {BUDGETS} ms: {shown} (the page does not play)"
    for budget, d, k in zip(BUDGETS, doms, shown):
        assert d["slider"] == times[k] and d["panel"] == times[k], (budget, k, d["slider"], d["panel"])
        np.testing.assert_array_equal(d["x"], frames[k], err_msg=f"points plotted at {budget} ms are not frame {k}'s")
    assert not np.array_equal(frames[shown[0]], frames[shown[1]])  # and the body has moved


def test_page_logs_no_javascript_error(shots):
    logs = shots[1]
    for log in logs:
        bad = [line for line in log.splitlines()
               if "CONSOLE" in line and ("HRJSERROR" in line or "Uncaught" in line)]
        assert not bad, "JavaScript errors:\n" + "\n".join(bad)
        assert "HRJSERROR" not in log


# -- the page's size budget is the GIF's (no browser needed) -------------------------------------
@pytest.mark.parametrize("suffix", [".gif", ".html"])
def test_command_line_page_is_refused_like_the_gif(capsys, tmp_path, suffix):
    """``hyperrotor scene``: an HTML page too large for the budget is refused before any work, by the
    same frames x (points + edges) pricing and the same options as the GIF."""
    from hyperrotor.cli import main

    out = tmp_path / f"big{suffix}"
    assert main(["scene", "--N", "8", "--frames", "5000", "--output", str(out)]) == 2
    err = capsys.readouterr().err
    assert "(256 points, 1024 edges, 5000 frames)" in err and "over the budget of 2 GiB (--max-memory" in err
    assert not list(tmp_path.iterdir())
    assert main(["scene", "--N", "8", "--frames", "5000", "--max-memory", "64G", "--max-seconds", "1",
                 "--output", str(out)]) == 2   # and the time budget, priced from the same sizes
    assert "--max-seconds" in capsys.readouterr().err and not list(tmp_path.iterdir())
