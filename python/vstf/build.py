"""Small typed helpers that write a scene in the fixture schema
(docs/fixtures.md), for building scenes in code rather than as dicts:

    from vstf.build import Camera, Light, Material, Object, Worldline, quad, build
    cube_face = Object("face", quad((-0.5, -0.5, 0), (1, 0, 0), (0, 1, 0)), kind="V_obj",
                       worldline=Worldline(start=(-100, -90, 0, -10), velocity=(0.9, 0, 0), proper_lifetime=200),
                       material=Material(color=(0.9, 0.3, 0.2)))
    scene = build(Camera(position=(0, 0, 0), t=10, look_at=(0, 0, -1)), [cube_face])

Each helper is a dataclass whose fields are the schema's; ``build`` turns
them into the fixture dict and loads it with ``vstf.scene``, so the
validation and its messages (file, JSON path) are the file's. A field left
``None`` is left out, taking the schema's default.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any, Dict, List, Optional, Sequence

Vec3 = Sequence[float]
Event = Sequence[float]


def _plain(value):
    """Dataclasses as dicts without their None fields; tuples as lists."""
    if hasattr(value, "__dataclass_fields__"):
        return {f.name: _plain(getattr(value, f.name)) for f in fields(value) if getattr(value, f.name) is not None}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    return value


@dataclass
class Camera:
    """A pinhole camera: where it is at lab time ``t``, where it looks, its
    vertical field of view in degrees, and its lab velocity (below c)."""

    position: Vec3
    t: float = 0.0
    look_at: Optional[Vec3] = None
    up: Optional[Vec3] = None
    vfov_deg: Optional[float] = None
    velocity: Optional[Vec3] = None


@dataclass
class Light:
    """The one point light, at rest in the lab, and the ambient term."""

    position: Vec3
    color: Optional[Vec3] = None
    ambient: Optional[float] = None


@dataclass
class Material:
    """A surface: colour (linear RGB), diffuse, specular, shininess and
    mirror fractions."""

    color: Vec3 = (0.8, 0.8, 0.8)
    diffuse: Optional[float] = None
    specular: Optional[float] = None
    shininess: Optional[float] = None
    mirror: Optional[float] = None


@dataclass
class Worldline:
    """Uniform motion of an object's reference point: its ``start`` event
    (t, x, y, z) and either ``velocity`` (fraction of c) with
    ``proper_lifetime``, or ``extrusion`` (dt, dx, dy, dz) as in paper 3.1."""

    start: Event
    velocity: Optional[Vec3] = None
    proper_lifetime: Optional[float] = None
    extrusion: Optional[Event] = None


@dataclass
class Object:
    """An object: its name, its mesh (one of the mesh helpers below), its
    kind (``"H_obj"`` lab-frame sizes, or ``"V_obj"`` rest-frame sizes,
    Lorentz-contracted), its worldline (or a fixed ``position``), its
    material, and optionally further named ``materials`` with the triangles
    of each (``faces``: name -> triangle indices from 0)."""

    name: str
    mesh: Dict[str, Any]
    kind: Optional[str] = None
    worldline: Optional[Worldline] = None
    position: Optional[Vec3] = None
    material: Material = field(default_factory=Material)
    materials: Optional[Dict[str, Material]] = None
    faces: Optional[Dict[str, List[int]]] = None


@dataclass
class View:
    """A named view of the scene: its camera time and model, if not the
    fixture's."""

    name: str
    t: Optional[float] = None
    model: Optional[str] = None


@dataclass
class Check:
    """A declared check: its name, its kind (``"edge"``, ``"outline"``,
    ``"doppler"``, ... as docs/checks.md lists them) with that kind's
    fields, and the paper's printed figure where it gives one (a separate
    column, never the expectation)."""

    name: str
    kind: str
    fields: Dict[str, Any] = field(default_factory=dict)
    paper: Optional[float] = None

    def to_dict(self) -> Dict[str, Any]:
        out = {"name": self.name, "measure": {self.kind: _plain(self.fields)}}
        if self.paper is not None:
            out["paper"] = self.paper
        return out


@dataclass
class Image:
    """Image size, samples per pixel and the colour effects of motion."""

    width: int = 320
    height: int = 240
    spp: Optional[int] = None
    doppler: Optional[bool] = None
    searchlight: Optional[bool] = None


def quad(corner: Vec3, u: Vec3, v: Vec3) -> Dict[str, Any]:
    """The parallelogram corner, corner+u, corner+u+v, corner+v."""
    return {"quad": {"corner": list(corner), "u": list(u), "v": list(v)}}


def cuboid(low: Vec3, high: Vec3) -> Dict[str, Any]:
    """An axis-aligned box between two corners."""
    return {"cuboid": {"min": list(low), "max": list(high)}}


def sphere(radius: float, segments: int = 32) -> Dict[str, Any]:
    """A tessellated sphere about the reference point."""
    return {"sphere": {"radius": radius, "segments": segments}}


def analytic_sphere(radius: float) -> Dict[str, Any]:
    """An exact sphere about the reference point."""
    return {"analytic_sphere": {"radius": radius}}


def obj(path: str) -> Dict[str, Any]:
    """A Wavefront OBJ file, relative to the scene's file."""
    return {"obj": {"path": str(path)}}


def ply(path: str) -> Dict[str, Any]:
    """A Stanford PLY file (ASCII or binary), relative to the scene's file."""
    return {"ply": {"path": str(path)}}


def mesh_file(path: str, format: Optional[str] = None) -> Dict[str, Any]:
    """A mesh file in ``format`` (``"obj"`` or ``"ply"``), or else the one
    its extension names, relative to the scene's file."""
    spec: Dict[str, Any] = {"path": str(path)}
    if format is not None:
        spec["format"] = format
    return {"file": spec}


def triangles(vertices: Sequence[Vec3], indices: Sequence[Sequence[int]]) -> Dict[str, Any]:
    """Explicit triangles: vertex positions and three 0-based indices each."""
    return {"triangles": {"vertices": [list(v) for v in vertices], "indices": [list(i) for i in indices]}}


def fixture(
    camera: Camera,
    objects: List[Object],
    *,
    light: Optional[Light] = None,
    image: Optional[Image] = None,
    model: str = "relativistic",
    views: Sequence[View] = (),
    checks: Sequence[Any] = (),
    description: str = "",
    background: Optional[Vec3] = None,
) -> Dict[str, Any]:
    """The fixture dict these parts make (``json.dump`` it to get a file)."""
    out = {
        "description": description,
        "camera": _plain(camera),
        "light": _plain(light or Light(position=(0.0, 20.0, 20.0))),
        "model": model,
        "image": _plain(image or Image()),
        "objects": [_plain(o) for o in objects],
        "views": [_plain(v) for v in views],
        "checks": [c.to_dict() if isinstance(c, Check) else _plain(c) for c in checks],
    }
    if background is not None:
        out["background"] = list(background)
    return out


def build(camera: Camera, objects: List[Object], *, file: Optional[str] = None, **rest):
    """The scene these parts make, loaded and validated by ``vstf.scene``."""
    from . import scene

    return scene(fixture(camera, objects, **rest), file=file)
