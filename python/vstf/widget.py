"""A notebook viewer of a scene (anywidget): the image, a camera-time
slider, a speed slider when one object moves (kept below c), the model,
the Doppler and searchlight effects, and a click on a pixel showing what
its ray meets. Each frame is ``vstf.render``'s array; renders run on a
worker thread, which always takes the newest request and drops the ones
that went stale while it worked, so dragging a slider stays responsive.
"""

from __future__ import annotations

import json
import threading
from pathlib import Path
from typing import Optional, Tuple

import anywidget
import traitlets

from . import _vstf

MODELS = ("infinite", "classical", "relativistic")


class Viewer(anywidget.AnyWidget):
    """``Viewer(scene, width=320, height=240, t_range=None)`` in a notebook
    cell shows the scene; ``t_range`` is (earliest, latest) camera time, by
    default the fixture's time plus or minus the light time across it."""

    _esm = Path(__file__).with_name("widget.js")
    _css = Path(__file__).with_name("widget.css")

    pixels = traitlets.Bytes(b"").tag(sync=True)
    width = traitlets.Int(320).tag(sync=True)
    height = traitlets.Int(240).tag(sync=True)
    frame = traitlets.Int(0).tag(sync=True)
    t = traitlets.Float(0.0).tag(sync=True)
    t_min = traitlets.Float(0.0).tag(sync=True)
    t_max = traitlets.Float(1.0).tag(sync=True)
    speed = traitlets.Float(0.0).tag(sync=True)
    speed_max = traitlets.Float(0.99).tag(sync=True)
    has_mover = traitlets.Bool(False).tag(sync=True)
    model = traitlets.Unicode("relativistic").tag(sync=True)
    doppler = traitlets.Bool(False).tag(sync=True)
    searchlight = traitlets.Bool(False).tag(sync=True)
    pixel = traitlets.List([]).tag(sync=True)
    debug = traitlets.Unicode("").tag(sync=True)
    status = traitlets.Unicode("").tag(sync=True)

    def __init__(self, scene, *, width: int = 320, height: int = 240, t_range: Optional[Tuple[float, float]] = None):
        t0 = scene.camera_t
        span = max(10.0, scene.look_distance or 0.0)
        low, high = t_range if t_range is not None else (t0 - span, t0 + span)
        speed = scene.mover_speed
        super().__init__(
            width=width,
            height=height,
            t=t0,
            t_min=low,
            t_max=high,
            has_mover=speed is not None,
            speed=speed or 0.0,
        )
        self._scene = scene
        self._wanted = threading.Condition()
        self._request = None
        self._closed = False
        self._worker = threading.Thread(target=self._work, name="vstf-viewer", daemon=True)
        self._worker.start()
        self.observe(self._changed, names=["t", "speed", "model", "doppler", "searchlight"])
        self.observe(self._clicked, names=["pixel"])
        self._ask(("render", self._settings()))

    def _settings(self):
        return dict(
            t=self.t,
            model=self.model if self.model in MODELS else None,
            width=self.width,
            height=self.height,
            spp=1,
            doppler=self.doppler,
            searchlight=self.searchlight,
            speed=self.speed if self.has_mover else None,
        )

    def _changed(self, _change):
        self._ask(("render", self._settings()))

    def _clicked(self, change):
        if len(change["new"]) == 2:
            self._ask(("debug", self._settings(), tuple(change["new"])))

    def _ask(self, request):
        """Replaces any request still waiting: only the newest is rendered."""
        with self._wanted:
            self._request = request
            self._wanted.notify()

    def _work(self):
        while True:
            with self._wanted:
                while self._request is None and not self._closed:
                    self._wanted.wait()
                if self._closed:
                    return
                request, self._request = self._request, None
            try:
                self._serve(request)
            except Exception as e:  # shown in the widget: a notebook has no stderr to read
                self.status = f"{type(e).__name__}: {e}"

    def _serve(self, request):
        kind, settings = request[0], dict(request[1])
        speed = settings.pop("speed")
        scene = self._scene if speed is None or speed == self._scene.mover_speed else self._scene.with_speed(speed)
        if kind == "render":
            self.status = "rendering"
            image = _vstf.render(scene, **settings)
            self.pixels = image.tobytes()
            self.frame += 1
            self.status = ""
        else:
            x, y = request[2]
            self.debug = json.dumps(summary(json.loads(_vstf.debug(scene, x, y, **settings))))

    def close(self):
        with self._wanted:
            self._closed = True
            self._wanted.notify()
        super().close()


def summary(log: dict) -> dict:
    """The first primary ray's hit from a ``vstf debug`` log: the pixel, the
    camera event, the object, the event seen (lab time and place), the
    object's own time there, and the colour."""
    out = {"pixel": log["pixel"], "camera_t": log["camera_t"], "rgb8": log["rgb8"], "object": None}
    for step in log["steps"]:
        if step["step"] == "hit" and step["kind"] == "primary":
            out.update(object=step["object"], event=step["event"], proper_time=step["proper_time"])
            break
    return out
