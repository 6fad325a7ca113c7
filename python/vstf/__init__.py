"""Spacetime ray tracer and its Visual Software Test Fixture, from Python.

Special relativity rendered (retarded time, aberration, Terrell rotation,
Lorentz contraction, Doppler), measured from the images and checked against
first-principles physics, as the ``vstf`` command does, with scenes from
fixture files or dicts and images as numpy arrays::

    import vstf
    scene = vstf.load("fixtures/flange.json")
    image = vstf.render(scene, t=20.0, model="relativistic")   # (H, W, 3) uint8
    result = vstf.check(scene, quick=True)
    print(result.passed, result.rows[0].quantity)

Every function is a thin layer over the harness's own library calls, so an
array holds exactly the pixels of the PNG ``vstf render`` writes for the
same scene and view. Errors are the harness's, as exception classes under
:class:`VstfError`. See docs/python.md.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, List, Optional, Sequence, Union

from . import _vstf
from ._vstf import (
    BudgetError,
    CheckError,
    FixtureError,
    GoldenError,
    NoFixtureError,
    NonFiniteError,
    NoProjectError,
    Scene,
    UsageError,
    VstfError,
    VstfIOError,
)

__version__ = _vstf.__version__

__all__ = [
    "Scene",
    "load",
    "scene",
    "render",
    "animate",
    "check",
    "debug",
    "limit_simd",
    "simd_level",
    "CheckResult",
    "Row",
    "Golden",
    "Viewer",
    "VstfError",
    "FixtureError",
    "NoProjectError",
    "NoFixtureError",
    "BudgetError",
    "VstfIOError",
    "CheckError",
    "NonFiniteError",
    "GoldenError",
    "UsageError",
]

PathLike = Union[str, "os.PathLike[str]"]
Time = Union[float, str]


def load(name_or_path: PathLike, *, root: Optional[PathLike] = None, force: bool = False) -> Scene:
    """A scene from a fixture file, or a fixture of the project around the
    current folder (or ``root``) by name. ``force`` lifts the memory budget.

    Raises :class:`FixtureError` (with ``file`` and ``path``, the JSON path of
    the field at fault), :class:`NoFixtureError` or :class:`NoProjectError`.
    """
    return Scene.load(os.fspath(name_or_path), None if root is None else os.fspath(root), force)


def scene(spec: dict, *, file: Optional[PathLike] = None, force: bool = False) -> Scene:
    """A scene from a dict written in the fixture schema (docs/fixtures.md),
    with exactly the file's validation and messages. ``file`` names it in
    errors (its stem is the scene's name) and anchors relative mesh paths.
    """
    return Scene.from_dict(spec, None if file is None else os.fspath(file), force)


def render(
    scene: Scene,
    *,
    view: Optional[str] = None,
    t: Optional[Time] = None,
    model: Optional[str] = None,
    width: Optional[int] = None,
    height: Optional[int] = None,
    spp: Optional[int] = None,
    doppler: bool = False,
    searchlight: bool = False,
    linear: bool = False,
    force: bool = False,
    aovs: bool = False,
):
    """One view of ``scene`` as a numpy array of shape (height, width, 3).

    ``view`` names a view (``scene.views``) and renders it exactly as
    ``vstf check`` does for its golden image; otherwise the fixture's camera
    with these settings: ``t`` the camera's lab time (a number, ``"auto"``
    or ``"auto:OBJECT"``), ``model`` one of ``"infinite"``, ``"classical"``,
    ``"relativistic"``, the size, samples per pixel, and the Doppler and
    searchlight effects. The array holds the PNG's 8-bit values (``uint8``,
    linear in radiance, as vstf writes its PNGs), or with ``linear`` the
    linear radiance (``float64``). The GIL is released while rendering.

    With ``aovs``, returns ``(image, aovs)``: a dict of per-pixel arrays of
    what the ray through each pixel's centre meets (NaN, or -1 for
    ``object``, where it meets nothing): ``event_t`` (the hit event's lab
    time: the retarded time), ``proper_time`` (the object's own time
    there), ``doppler`` (nu_camera / nu_surface), ``searchlight`` (D^4),
    ``object`` (index into ``scene.objects``), ``distance`` (lab distance
    from the camera) and ``normal`` (height, width, 3).
    """
    return _vstf.render(
        scene,
        view=view,
        t=t,
        model=model,
        width=width,
        height=height,
        spp=spp,
        doppler=doppler,
        searchlight=searchlight,
        linear=linear,
        force=force,
        aovs=aovs,
    )


def animate(
    scene: Scene,
    times: Iterable[float],
    *,
    model: Optional[str] = None,
    width: Optional[int] = None,
    height: Optional[int] = None,
    spp: Optional[int] = None,
    doppler: bool = False,
    searchlight: bool = False,
    linear: bool = False,
    force: bool = False,
    progress: Union[bool, Callable[[int, int], Any]] = True,
):
    """Frames at the camera times ``times`` as an array (frames, height,
    width, 3), from one 4D database (animation only advances the camera's
    time). ``progress`` shows a tqdm bar when tqdm is installed (or is
    called with (done, total) if a callable). Ctrl-C stops between frames
    with ``KeyboardInterrupt``.
    """
    times = [float(t) for t in times]
    callback, close = _progress(progress, len(times))
    try:
        return _vstf.animate(
            scene,
            times,
            model=model,
            width=width,
            height=height,
            spp=spp,
            doppler=doppler,
            searchlight=searchlight,
            linear=linear,
            force=force,
            progress=callback,
        )
    finally:
        close()


def _progress(progress, total):
    """A (callback, close) pair for ``animate``'s ``progress``."""
    if callable(progress):
        return progress, lambda: None
    if not progress:
        return None, lambda: None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None, lambda: None
    bar = tqdm(total=total, unit="frame")
    return (lambda done, _total: bar.update(done - bar.n)), bar.close


@dataclass(frozen=True)
class Row:
    """One checked quantity: measured from the images, expected from first
    principles, the paper's printed figure where it gives one, and the
    tolerance derived from the measurement. A check that could not be
    measured is a failing row with no numbers (``None``) and its ``error``.
    ``camera_t`` is the camera time of the view it was measured in where the
    view's ``t`` was solved (``"auto:OBJECT"``, ``seen_at_azimuth``)."""

    fixture: str
    quantity: str
    measured: Optional[float]
    expected: Optional[float]
    paper: Optional[float]
    tolerance: Optional[float]
    unit: str
    passed: bool
    error: Optional[str] = None
    camera_t: Optional[float] = None


@dataclass(frozen=True)
class Golden:
    """One view compared with its approved golden image."""

    fixture: str
    view: str
    passed: bool
    missing: bool
    max_diff: Optional[int]
    differing: int
    allowed_max_diff: int
    allowed_max_pixels: int
    worst_pixel: Optional[Sequence[int]]
    size: Sequence[int]
    pending: Optional[str]


@dataclass(frozen=True)
class CheckResult:
    """What ``check`` found: the judged rows and the golden comparisons."""

    rows: List[Row] = field(default_factory=list)
    goldens: List[Golden] = field(default_factory=list)

    @property
    def passed(self) -> bool:
        """Whether every row and every golden comparison passed."""
        return all(r.passed for r in self.rows) and all(g.passed for g in self.goldens)

    @classmethod
    def from_json(cls, text: str) -> "CheckResult":
        """The result from ``vstf check --json``'s text."""
        data = json.loads(text)
        rows = [Row(**{("passed" if k == "pass" else k): v for k, v in r.items()}) for r in data["rows"]]
        goldens = [Golden(**{("passed" if k == "pass" else k): v for k, v in g.items()}) for g in data["goldens"]]
        return cls(rows=rows, goldens=goldens)

    def to_pandas(self):
        """The rows as a pandas DataFrame (pandas must be installed)."""
        import pandas as pd

        return pd.DataFrame([r.__dict__ for r in self.rows])

    def plot(self, ax=None):
        """Measured minus expected for each row, with its tolerance as an
        error bar, on a matplotlib axis (made if not given); returns it."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(8, 0.3 * len(self.rows) + 1))
        names = [f"{r.fixture}: {r.quantity}" for r in self.rows]
        nan = float("nan")
        offsets = [nan if r.error else r.measured - r.expected for r in self.rows]
        tolerances = [nan if r.error else r.tolerance for r in self.rows]
        ax.errorbar(offsets, range(len(self.rows)), xerr=tolerances, fmt="o")
        ax.axvline(0.0, color="grey", linewidth=0.8)
        ax.set_yticks(range(len(self.rows)))
        ax.set_yticklabels(names)
        ax.set_xlabel("measured - expected (each row in its own unit)")
        return ax


def check(scene: Union[Scene, PathLike], *, quick: bool = False, goldens: bool = True) -> CheckResult:
    """Runs the scene's declared checks, as ``vstf check`` does (at the
    tests' lower effort when ``quick``); when the scene's file lies in a
    project's ``fixtures/`` and ``goldens``, compares its views with their
    golden images there (writing pending images for ``vstf approve``).

    A check that cannot be measured is a row with ``passed`` False and its
    ``error``, as are checks that measure and fail; the other checks are
    still measured.
    """
    if not isinstance(scene, Scene):
        scene = load(scene)
    return CheckResult.from_json(_vstf.check(scene, quick=quick, goldens=goldens))


def __getattr__(name):
    """``vstf.Viewer``, the notebook widget, imported on first use (it needs
    anywidget, which the rest of the package does not)."""
    if name == "Viewer":
        from .widget import Viewer

        return Viewer
    raise AttributeError(f"module 'vstf' has no attribute {name!r}")


def limit_simd(level: str) -> None:
    """Limits every search of this process to the vector level ``level``
    (``"baseline"``, the build's own, or ``"x86-64-v3"``, AVX2 where the
    CPU has it: the default) at the widest, as ``vstf --simd`` does. The
    images are the same to the bit at every level. Raises UsageError for
    any other name."""
    _vstf.limit_simd(level)


def simd_level() -> str:
    """The vector level searches run at in this process: the machine's
    widest, within ``limit_simd``'s limit."""
    return _vstf.simd_level()


def debug(scene: Scene, pixel: Sequence[int], *, candidates: bool = False, **view) -> dict:
    """Every variable along pixel (x, y)'s rays, as nested dicts (the JSON
    of ``vstf debug --log``): the camera event, each ray, the hits with
    their events, the shading. ``view`` takes ``render``'s view settings."""
    x, y = pixel
    return json.loads(_vstf.debug(scene, int(x), int(y), candidates=candidates, **view))
