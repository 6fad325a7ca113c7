"""The Python package against the repository's own fixtures and golden
images: scenes from files and dicts, arrays equal to the PNGs the command
line writes, checks, ray logs, and the typed errors for bad input."""

import copy
import json
import os
import shutil
import signal
import subprocess
import sys
import threading
import time
import re
import zlib
from pathlib import Path

import numpy as np
import pytest

import vstf

REPO = Path(__file__).resolve().parents[2]
FIXTURES = REPO / "fixtures"
GOLDEN = REPO / "golden"


def read_png(path):
    """An 8-bit RGB PNG as a (height, width, 3) array, decoded here from the
    format's definition (no imaging library shared with the code under
    test): zlib-compressed scanlines, each with its filter byte."""
    data = Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, header = 8, b"", None
    while pos < len(data):
        n = int.from_bytes(data[pos : pos + 4], "big")
        kind, body = data[pos + 4 : pos + 8], data[pos + 8 : pos + 8 + n]
        if kind == b"IHDR":
            header = body
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    w, h = int.from_bytes(header[0:4], "big"), int.from_bytes(header[4:8], "big")
    assert header[8] == 8 and header[9] == 2 and header[12] == 0, "8-bit RGB, not interlaced"
    raw, stride = zlib.decompress(idat), 3 * w
    out, prev = np.zeros((h, stride), dtype=np.int32), np.zeros(stride, dtype=np.int32)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = np.frombuffer(raw, np.uint8, stride, y * (stride + 1) + 1).astype(np.int32)
        cur = np.zeros(stride, dtype=np.int32)
        for x in range(stride):
            a = cur[x - 3] if x >= 3 else 0
            b, c = prev[x], (prev[x - 3] if x >= 3 else 0)
            if f == 0:
                p = 0
            elif f == 1:
                p = a
            elif f == 2:
                p = b
            elif f == 3:
                p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            cur[x] = (line[x] + p) & 0xFF
        out[y], prev = cur, cur
    return out.reshape(h, w, 3).astype(np.uint8)


def vstf_binary():
    """The `vstf` executable to compare with: $VSTF_BIN, or the workspace's
    release or test build."""
    named = os.environ.get("VSTF_BIN")
    if named:
        assert Path(named).is_file(), f"VSTF_BIN={named} is not a file"
        return named
    for candidate in [REPO / "target/release/vstf", REPO / "target/debug/vstf"]:
        if candidate.is_file():
            return str(candidate)
    pytest.skip("no vstf executable: set VSTF_BIN or run cargo build --release -p vstf")


def flange_dict():
    return json.loads((FIXTURES / "flange.json").read_text())


def moving(spec):
    """The index of the scene dict's one moving object."""
    return next(i for i, o in enumerate(spec["objects"]) if "worldline" in o)


def slug(name):
    """A golden image's file stem for a view (vstf's rule: lowercase
    letters, digits and single dashes)."""
    return re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-")


# Scenes


def test_a_fixture_loads_by_path_and_by_name():
    by_path = vstf.load(FIXTURES / "flange.json")
    by_name = vstf.load("flange", root=REPO)
    assert by_path.name == by_name.name == "flange"
    assert "stage floor" in by_path.objects
    assert by_path.views == by_name.views and len(by_path.views) >= 1


def test_an_unknown_name_is_a_no_fixture_error_with_a_hint():
    with pytest.raises(vstf.NoFixtureError) as e:
        vstf.load("flang", root=REPO)
    assert e.value.name == "flang"
    assert 'did you mean "flange"' in str(e.value)


def test_a_dict_scene_renders_as_its_file_does():
    from_file = vstf.load(FIXTURES / "flange.json")
    from_dict = vstf.scene(flange_dict(), file=FIXTURES / "flange.json")
    a = vstf.render(from_file, width=64, height=48, spp=1)
    b = vstf.render(from_dict, width=64, height=48, spp=1)
    assert np.array_equal(a, b)
    # Negative control: another speed is another picture.
    faster = flange_dict()
    faster["objects"][moving(faster)]["worldline"]["extrusion"] = [2000.0, 1000.0, 0.0, 0.0]
    c = vstf.render(vstf.scene(faster), width=64, height=48, spp=1)
    assert not np.array_equal(a, c)


def test_a_wrong_field_names_its_json_path():
    bad = flange_dict()
    bad["objects"][0]["materiall"] = {}
    with pytest.raises(vstf.FixtureError) as e:
        vstf.scene(bad, file="mine.json")
    assert e.value.file == "mine.json"
    assert e.value.path == "objects[0].materiall"
    assert "materiall" in str(e.value)


def test_a_speed_of_light_or_more_is_refused_at_its_field():
    bad = flange_dict()
    k = moving(bad)
    bad["objects"][k]["worldline"]["extrusion"] = [10.0, 10.0, 0.0, 0.0]
    with pytest.raises(vstf.FixtureError) as e:
        vstf.scene(bad)
    assert e.value.path.startswith(f"objects[{k}]")
    assert "1.000000c" in e.value.detail or "light" in e.value.detail


def test_a_non_dict_is_a_usage_error():
    with pytest.raises(vstf.UsageError, match="not list"):
        vstf.scene([1, 2, 3])
    with pytest.raises(vstf.FixtureError):
        vstf.scene({"camera": "here"})


def test_a_saved_scene_loads_and_renders_the_same(tmp_path):
    s = vstf.load(FIXTURES / "flange.json")
    out = tmp_path / "copy.json"
    s.save(out)
    again = vstf.load(out)
    assert again.name == "copy"
    assert np.array_equal(
        vstf.render(s, width=48, height=32, spp=1), vstf.render(again, width=48, height=32, spp=1)
    )
    with pytest.raises(vstf.VstfIOError) as e:
        s.save(out)
    assert e.value.filename == str(out)
    s.save(out, overwrite=True)


def test_a_saved_scene_is_accepted_by_vstf_check(tmp_path):
    project = tmp_path / "project"
    (project / "fixtures").mkdir(parents=True)
    vstf.load(FIXTURES / "sphere-relativistic.json").save(project / "fixtures" / "ball.json")
    run = subprocess.run(
        [vstf_binary(), "--root", str(project), "list", "--views"], capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr
    assert "ball" in run.stdout


# Images


def test_a_named_view_is_its_golden_image_bit_for_bit():
    for fixture in ["flange", "sphere-relativistic"]:
        s = vstf.load(FIXTURES / f"{fixture}.json")
        for view in s.views:
            golden = GOLDEN / fixture / f"{slug(view)}.png"
            assert golden.exists(), golden
            assert np.array_equal(vstf.render(s, view=view), read_png(golden)), (fixture, view)


def test_an_array_is_the_cli_png_bit_for_bit(tmp_path):
    out = tmp_path / "cli.png"
    args = ["--width", "96", "--height", "64", "--spp", "2", "--model", "classical", "--camera-t", "938.5"]
    run = subprocess.run(
        [vstf_binary(), "render", str(FIXTURES / "flange.json"), "--out", str(out)] + args,
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    s = vstf.load(FIXTURES / "flange.json")
    mine = vstf.render(s, width=96, height=64, spp=2, model="classical", t=938.5)
    assert mine.shape == (64, 96, 3) and mine.dtype == np.uint8
    assert np.array_equal(mine, read_png(out))
    # Negative control: the same view 230 t.units later, when the flange has
    # moved 2 l.units, differs.
    other = vstf.render(s, width=96, height=64, spp=2, model="classical", t=1168.5)
    assert not np.array_equal(other, read_png(out))


def test_every_simd_level_renders_the_same_array():
    s = vstf.load(FIXTURES / "teaser.json")
    best = vstf.simd_level()
    assert best in ("baseline", "x86-64-v3")
    default = vstf.render(s, width=96, height=54, linear=True)
    try:
        vstf.limit_simd("baseline")
        assert vstf.simd_level() == "baseline"
        baseline = vstf.render(s, width=96, height=54, linear=True)
    finally:
        vstf.limit_simd("x86-64-v3")
    assert vstf.simd_level() == best
    assert default.tobytes() == baseline.tobytes()
    # Negative control: a level that does not exist is refused.
    with pytest.raises(vstf.UsageError, match="x86-64-v3"):
        vstf.limit_simd("avx512")


def test_linear_radiance_quantises_to_the_8_bit_image():
    s = vstf.load(FIXTURES / "flange.json")
    linear = vstf.render(s, width=40, height=30, spp=1, linear=True)
    bytes_ = vstf.render(s, width=40, height=30, spp=1)
    assert linear.dtype == np.float64 and linear.shape == (30, 40, 3)
    assert np.array_equal(np.floor(np.clip(linear, 0, 1) * 255 + 0.5).astype(np.uint8), bytes_)
    assert linear.max() > 0.0


def test_auto_camera_time_is_the_cli_one():
    s = vstf.load(FIXTURES / "flange.json")
    auto = vstf.render(s, width=40, height=30, spp=1, t="auto")
    distance = float(np.linalg.norm(np.array([0.0, 9.0, 15.0])))
    at = vstf.render(s, width=40, height=30, spp=1, t=distance)
    assert np.array_equal(auto, at)
    with pytest.raises(vstf.UsageError, match='no object "nothing"'):
        vstf.render(s, width=40, height=30, t="auto:nothing")


def test_bad_view_settings_are_usage_errors():
    s = vstf.load(FIXTURES / "flange.json")
    with pytest.raises(vstf.UsageError, match="expected infinite, classical or relativistic"):
        vstf.render(s, model="galilean")
    with pytest.raises(vstf.UsageError, match="no view named"):
        vstf.render(s, view="nope")
    with pytest.raises(vstf.UsageError, match="leave t"):
        vstf.render(s, view=s.views[0], t=3.0)
    with pytest.raises(vstf.FixtureError):
        vstf.render(s, width=0)
    with pytest.raises(TypeError):
        vstf.render(s, width="wide")


def test_work_beyond_the_budget_is_refused_unless_forced():
    s = vstf.load(FIXTURES / "flange.json")
    with pytest.raises(vstf.BudgetError, match="force"):
        vstf.animate(s, [940.0] * 400, width=1920, height=1080, spp=16, progress=False)


def test_an_animation_is_its_frames():
    s = vstf.load(FIXTURES / "flange.json")
    seen = []
    stack = vstf.animate(s, [930.0, 940.0], width=32, height=24, spp=1, progress=lambda d, n: seen.append((d, n)))
    assert stack.shape == (2, 24, 32, 3)
    assert seen == [(1, 2), (2, 2)]
    for k, t in enumerate([930.0, 940.0]):
        assert np.array_equal(stack[k], vstf.render(s, t=t, width=32, height=24, spp=1))
    assert not np.array_equal(stack[0], stack[1])
    with pytest.raises(vstf.UsageError):
        vstf.animate(s, [], progress=False)


def test_the_gil_is_released_while_rendering():
    s = vstf.load(FIXTURES / "flange.json")
    done = threading.Event()
    worker = threading.Thread(
        target=lambda: (vstf.render(s, width=320, height=240, spp=16), done.set())
    )
    ticks = 0
    worker.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    # Python ran beside the render: with the GIL held, the loop would see
    # the render finished at its first turn.
    assert ticks > 5


# Checks and ray logs


def test_a_check_gives_the_rows_and_goldens_of_vstf_check(tmp_path):
    project = tmp_path / "project"
    (project / "fixtures").mkdir(parents=True)
    shutil.copy(FIXTURES / "sphere-relativistic.json", project / "fixtures")
    shutil.copytree(GOLDEN / "sphere-relativistic", project / "golden" / "sphere-relativistic")
    result = vstf.check(project / "fixtures" / "sphere-relativistic.json", quick=True)
    assert result.rows and result.passed
    assert all(r.fixture == "sphere-relativistic" for r in result.rows)
    assert [g.view for g in result.goldens] == ["view"] and result.goldens[0].passed
    row = result.rows[0]
    assert abs(row.measured - row.expected) <= row.tolerance


def test_a_changed_golden_fails_and_leaves_a_pending_image(tmp_path):
    # Negative control: one golden pixel changed by 40 levels fails the
    # comparison, and the pending images are written for `vstf approve`.
    project = tmp_path / "project"
    (project / "fixtures").mkdir(parents=True)
    shutil.copy(FIXTURES / "sphere-relativistic.json", project / "fixtures")
    s = vstf.load(project / "fixtures" / "sphere-relativistic.json")
    image = vstf.render(s, view="view")
    image[10, 10] = (image[10, 10].astype(int) + 40) % 256
    write_png(project / "golden" / "sphere-relativistic" / "view.png", image)
    result = vstf.check(s, quick=True)
    assert not result.passed and all(r.passed for r in result.rows)
    (g,) = result.goldens
    assert not g.passed and g.max_diff == 40 and g.differing == 1 and list(g.worst_pixel) == [10, 10]
    assert (Path(g.pending) / "actual.png").is_file()
    # Without goldens, only the rows count.
    assert vstf.check(s, quick=True, goldens=False).passed


def write_png(path, rgb):
    """An (h, w, 3) uint8 array as an 8-bit RGB PNG (filter 0 on every line)."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))

    def chunk(kind, body):
        crc = zlib.crc32(kind + body).to_bytes(4, "big")
        return len(body).to_bytes(4, "big") + kind + body + crc

    header = w.to_bytes(4, "big") + h.to_bytes(4, "big") + bytes([8, 2, 0, 0, 0])
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(
        b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")
    )


def test_debug_logs_the_pixels_rays():
    s = vstf.load(FIXTURES / "sphere-relativistic.json")
    log = vstf.debug(s, (120, 90), view="view")
    assert log["fixture"] == "sphere-relativistic"
    assert log["pixel"] == [120, 90]
    assert log["steps"]
    with pytest.raises(vstf.UsageError, match="outside"):
        vstf.debug(s, (100000, 0), view="view")


def test_ctrl_c_stops_an_animation_between_frames():
    code = (
        "import sys, vstf\n"
        f"s = vstf.load({str(FIXTURES / 'flange.json')!r})\n"
        "vstf.animate(s, [940.0] * 500, width=160, height=120, spp=1,\n"
        "             progress=lambda done, n: print(done, flush=True))\n"
        "print('finished', flush=True)\n"
    )
    child = subprocess.Popen(
        [sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    assert child.stdout.readline().strip() == "1"
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=60)
    assert child.returncode != 0
    assert "KeyboardInterrupt" in err
    assert "finished" not in out


def test_aovs_agree_with_first_principles_on_a_fast_sphere():
    """sphere-relativistic: a sphere of radius 1 (V_obj, contracted to an
    ellipsoid of x semi-axis 1/gamma) moving at 0.9c along x, 10 l.units in
    front of a camera at rest at the origin at t = 0, looking along -z
    (vfov 30). For the ray through a pixel's centre, direction d, the event
    seen is s*(d) at t = -s with the smallest s where the contracted sphere
    is met; written here from those formulas, not from the renderer."""
    s = vstf.load(FIXTURES / "sphere-relativistic.json")
    w, h = 96, 72
    image, aov = vstf.render(s, width=w, height=h, spp=1, aovs=True)
    beta = 0.9
    gamma = 1.0 / np.sqrt(1.0 - beta * beta)
    tan_half = np.tan(np.radians(30.0) / 2.0)
    hits = misses = 0
    for px, py in [(48, 36), (44, 30), (52, 40), (40, 36), (56, 36), (48, 33), (5, 5), (90, 60)]:
        u = ((px + 0.5) / w * 2.0 - 1.0) * tan_half * w / h
        v = (1.0 - (py + 0.5) / h * 2.0) * tan_half
        d = np.array([u, v, -1.0]) / np.sqrt(u * u + v * v + 1.0)
        # Centre at lab time t = -s: (-81 + 0.9 (t + 100), 0, -10); the
        # point s*d minus it, with x stretched by gamma, has length 1.
        c0 = np.array([-81.0 + beta * 100.0, 0.0, -10.0])
        a_vec = d + np.array([beta, 0.0, 0.0])  # d(point - centre)/ds
        scale = np.array([gamma, 1.0, 1.0])
        A, B = scale * a_vec, scale * (-c0)
        qa, qb, qc = A @ A, 2.0 * A @ B, B @ B - 1.0
        disc = qb * qb - 4 * qa * qc
        if disc <= 0:
            misses += 1
            assert aov["object"][py, px] == -1 and np.isnan(aov["event_t"][py, px])
            assert np.isnan(aov["normal"][py, px]).all()
            continue
        hits += 1
        s_hit = (-qb - np.sqrt(disc)) / (2 * qa)
        t_hit = -s_hit
        assert aov["object"][py, px] == 0
        assert aov["event_t"][py, px] == pytest.approx(t_hit, abs=1e-9)
        assert aov["distance"][py, px] == pytest.approx(s_hit, abs=1e-9)
        # The body's clocks are synchronised in its rest frame: the clock at
        # the hit reads the rest-frame time since the start event (t = -100,
        # x = -81), gamma (dt - beta dx).
        dt, dx = t_hit + 100.0, s_hit * d[0] + 81.0
        assert aov["proper_time"][py, px] == pytest.approx(gamma * (dt - beta * dx), abs=1e-9)
        doppler = 1.0 / (gamma * (1.0 + beta * d[0]))
        assert aov["doppler"][py, px] == pytest.approx(doppler, rel=1e-9)
        assert aov["searchlight"][py, px] == pytest.approx(doppler**4, rel=1e-9)
        offset = s_hit * d - np.array([-81.0 + beta * (t_hit + 100.0), 0.0, -10.0])
        normal = offset * np.array([gamma * gamma, 1.0, 1.0])
        normal /= np.linalg.norm(normal)
        # Turned to the side the sphere's own frame shows:
        # the light seen leaves the first point met outwards in that frame,
        # so the outward normal, also on the trailing side seen by
        # aberration (where the lab would see the inside: normal @ -d < 0).
        assert np.allclose(aov["normal"][py, px], normal, atol=1e-9)
    assert hits >= 5 and misses >= 2
    # The image and the AOVs agree on what is lit.
    lit = image.sum(axis=2) > 0
    assert np.array_equal(lit, aov["object"] >= 0)


def test_a_scene_built_from_typed_parts_is_its_dict():
    from vstf.build import Camera, Image, Light, Material, Object, View, Worldline, build, fixture, quad

    parts = dict(
        camera=Camera(position=(0, 0, 0), t=10.0, look_at=(0, 0, -1), vfov_deg=30.0),
        objects=[
            Object("face", quad((-0.5, -0.5, 0), (1, 0, 0), (0, 1, 0)), kind="V_obj",
                   worldline=Worldline(start=(-100, -90, 0, -10), velocity=(0.9, 0, 0), proper_lifetime=200),
                   material=Material(color=(0.9, 0.3, 0.2)))
        ],
        light=Light(position=(0, 20, 20), ambient=0.5),
        image=Image(width=48, height=32),
        views=[View("now")],
    )
    built = build(**parts, file="face.json")
    as_dict = fixture(**parts)
    assert as_dict["objects"][0]["worldline"] == {"start": [-100, -90, 0, -10], "velocity": [0.9, 0, 0],
                                                  "proper_lifetime": 200}
    assert "position" not in as_dict["objects"][0]
    assert built.views == ["now"] and built.objects == ["face"]
    image = vstf.render(built)
    assert np.array_equal(image, vstf.render(vstf.scene(as_dict)))
    assert image.any()
    # A mistake in a part is named at its JSON path, as in a file.
    parts["objects"][0].worldline.velocity = (1.5, 0, 0)
    with pytest.raises(vstf.FixtureError) as e:
        build(**parts, file="face.json")
    assert e.value.path.startswith("objects[0]")


def test_ctrl_c_stops_a_long_single_render():
    # A frame 256 times the size of a timed small one: far longer than the
    # few seconds the interrupt is given.
    s = vstf.load(FIXTURES / "flange.json")
    started = time.monotonic()
    vstf.render(s, width=160, height=120, spp=64, force=True)
    estimate = 256 * (time.monotonic() - started)
    code = (
        "import vstf\n"
        f"s = vstf.load({str(FIXTURES / 'flange.json')!r})\n"
        "print('rendering', flush=True)\n"
        "vstf.render(s, width=2560, height=1920, spp=64, force=True)\n"
        "print('finished', flush=True)\n"
    )
    child = subprocess.Popen(
        [sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    assert child.stdout.readline().strip() == "rendering"
    time.sleep(1.0)
    child.send_signal(signal.SIGINT)
    interrupted = time.monotonic()
    out, err = child.communicate(timeout=60)
    stopped_in = time.monotonic() - interrupted
    assert "KeyboardInterrupt" in err and "finished" not in out
    assert stopped_in < min(5.0, estimate / 4), (stopped_in, estimate)


def test_a_non_array_where_an_array_belongs_names_the_field():
    bad = flange_dict()
    bad["camera"]["position"] = "above the stage"
    with pytest.raises(vstf.FixtureError) as e:
        vstf.scene(bad, file="mine.json")
    assert e.value.path == "camera.position"
    bad = flange_dict()
    bad["objects"][0]["mesh"]["cuboid"]["min"] = [1.0, 2.0]
    with pytest.raises(vstf.FixtureError) as e:
        vstf.scene(bad, file="mine.json")
    assert e.value.path == "objects[0].mesh.cuboid.min"


def test_typed_checks_are_measured_and_the_result_tabulates_and_plots():
    from vstf.build import Camera, Check, Image, Light, Material, Object, View, Worldline, analytic_sphere, build

    ball = Object("ball", analytic_sphere(1.0), kind="V_obj",
                  worldline=Worldline(start=(-100, -81, 0, -10), extrusion=(200, 180, 0, 0)),
                  material=Material(color=(0.3, 0.8, 0.9)))
    scene = build(
        Camera(position=(0, 0, 0), t=0.0, look_at=(0, 0, -1), vfov_deg=30.0), [ball],
        light=Light(position=(0, 20, 20), color=(0, 0, 0), ambient=1.0), image=Image(width=320, height=240, spp=4),
        views=[View("view")],
        checks=[Check("radius", "outline", {"view": "view", "object": "ball", "read": "radius"}),
                Check("rms", "outline", {"view": "view", "object": "ball", "read": "rms"})],
        background=(0, 0, 0), file="ball.json",
    )
    result = vstf.check(scene, quick=True)
    assert [r.quantity for r in result.rows] == ["radius", "rms"] and result.passed
    pd = pytest.importorskip("pandas")
    table = result.to_pandas()
    assert list(table["quantity"]) == ["radius", "rms"] and table["passed"].all()
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    ax = result.plot()
    assert [t.get_text() for t in ax.get_yticklabels()] == ["ball: radius", "ball: rms"]
    # A kind that does not exist is named at its path.
    with pytest.raises(vstf.FixtureError) as e:
        build(Camera(position=(0, 0, 0)), [ball], checks=[Check("x", "outlines", {})], file="ball.json")
    assert e.value.path.startswith("checks[0]")


def test_a_check_that_cannot_be_measured_is_a_failing_row_beside_the_others():
    from vstf.build import Camera, Check, Image, Light, Material, Object, View, Worldline, analytic_sphere, build

    ball = Object("ball", analytic_sphere(1.0), kind="V_obj",
                  worldline=Worldline(start=(-100, -81, 0, -10), extrusion=(200, 180, 0, 0)),
                  material=Material(color=(0.3, 0.8, 0.9)))
    away = Object("away", analytic_sphere(1.0), position=(0, 0, 50))  # behind the camera
    scene = build(
        Camera(position=(0, 0, 0), t=0.0, look_at=(0, 0, -1), vfov_deg=30.0), [ball, away],
        light=Light(position=(0, 20, 20), color=(0, 0, 0), ambient=1.0), image=Image(width=320, height=240, spp=4),
        views=[View("view")],
        checks=[Check("radius", "outline", {"view": "view", "object": "ball", "read": "radius"}),
                Check("away radius", "outline", {"view": "view", "object": "away", "read": "radius"})],
        background=(0, 0, 0), file="two.json",
    )
    result = vstf.check(scene, quick=True)
    good, bad = result.rows
    assert good.passed and good.error is None and good.measured is not None
    assert not bad.passed and "checks[1]" in bad.error and bad.measured is None
    assert not result.passed
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    result.plot()
