"""The notebook viewer's kernel side: each change is rendered off the
calling thread, stale requests are dropped, the newest is what is shown,
and a click gives what the pixel's ray meets."""

import json
import time
from pathlib import Path

import numpy as np
import pytest

import vstf

pytest.importorskip("anywidget")

FIXTURES = Path(__file__).resolve().parents[2] / "fixtures"


def wait_for(condition, seconds=60.0):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if condition():
            return
        time.sleep(0.01)
    raise AssertionError("timed out")


def shown(viewer):
    return np.frombuffer(viewer.pixels, np.uint8).reshape(viewer.height, viewer.width, 3)


def test_the_viewer_shows_the_scene_and_follows_its_sliders():
    scene = vstf.load(FIXTURES / "flange.json")
    v = vstf.Viewer(scene, width=64, height=48)
    wait_for(lambda: v.frame >= 1 and v.status == "")
    assert v.has_mover and v.speed == pytest.approx(17.32 / 2000.0)
    assert v.t_min < v.t == scene.camera_t < v.t_max
    assert np.array_equal(shown(v), vstf.render(scene, t=scene.camera_t, width=64, height=48, spp=1))
    v.model = "classical"
    v.t = 941.0
    wait_for(lambda: v.status == "" and np.array_equal(
        shown(v), vstf.render(scene, t=941.0, model="classical", width=64, height=48, spp=1)))
    v.speed = 0.9
    faster = scene.with_speed(0.9)
    wait_for(lambda: v.status == "" and np.array_equal(
        shown(v), vstf.render(faster, t=941.0, model="classical", width=64, height=48, spp=1)))
    v.close()


def test_stale_requests_are_dropped_and_the_newest_is_shown():
    scene = vstf.load(FIXTURES / "flange.json")
    v = vstf.Viewer(scene, width=160, height=120)
    wait_for(lambda: v.frame >= 1)
    before = v.frame
    started = time.monotonic()
    times = np.linspace(930.0, 950.0, 60)
    for t in times:  # as a dragged slider sends them, faster than frames render
        v.t = float(t)
    asked_in = time.monotonic() - started
    final = vstf.render(scene, t=float(times[-1]), width=160, height=120, spp=1)
    wait_for(lambda: np.array_equal(shown(v), final))
    rendered = v.frame - before
    assert asked_in < 1.0  # the notebook's thread never waited for a render
    assert 1 <= rendered < len(times)
    v.close()


def test_a_click_shows_what_the_pixels_ray_meets():
    scene = vstf.load(FIXTURES / "sphere-relativistic.json")
    v = vstf.Viewer(scene, width=96, height=72)
    v.pixel = [48, 36]
    wait_for(lambda: v.debug != "")
    d = json.loads(v.debug)
    assert d["object"] == "sphere" and d["pixel"] == [48, 36]
    assert d["event"]["t"] < 0.0  # seen as it was when its light left
    v.pixel = [1, 1]
    wait_for(lambda: json.loads(v.debug)["pixel"] == [1, 1])
    assert json.loads(v.debug)["object"] is None
    v.close()


def test_a_speed_at_or_above_c_is_refused():
    scene = vstf.load(FIXTURES / "flange.json")
    with pytest.raises(vstf.UsageError, match="below 1"):
        scene.with_speed(1.0)
    with pytest.raises(vstf.UsageError, match="exactly one"):
        vstf.load(FIXTURES / "teaser.json").with_speed(0.5)
