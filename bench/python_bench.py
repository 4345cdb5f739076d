"""The Python package's three figures (issue 25), each a ratio of two timings from one run:

1. 10^5 samples into NumPy: spinfold.simulate against `spinfold simulate` in a subprocess with its
   JSON Lines parsed into the same arrays (what a notebook did before the package);
2. run_many of 200 scenes with threads=2 against threads=1;
3. one short simulate (1,000 samples) from Python against the engine's own time for it (the
   C++ sampling loop, measured inside the module): the overhead of the binding.

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py build/spinfold
"""

import json
import subprocess
import sys
import time

import numpy as np

import spinfold


def best_of(repeats, run):
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - start)
    return best


def subprocess_numpy(binary, args):
    """The old way: the CLI's JSON Lines parsed line by line into arrays of every numeric field."""
    out = subprocess.run([binary, "simulate", *args], check=True, capture_output=True, text=True).stdout
    names = spinfold.field_names()
    rows = []
    for line in out.splitlines()[1:]:
        sample = json.loads(line)
        flat = {}
        for key, value in sample.items():
            if isinstance(value, list):
                for i, v in enumerate(value):
                    if isinstance(v, list):
                        for j, w in enumerate(v):
                            flat[f"{key}.{i}.{j}"] = w
                    else:
                        flat[f"{key}.{i}"] = v
            elif isinstance(value, dict) and key in ("actions", "frequencies"):
                for k, v in value.items():
                    flat[f"{key}.{k}"] = v
            else:
                flat[key] = value
        rows.append([np.nan if flat.get(n) is None else flat[n] for n in names])
    return np.array(rows, dtype=float)


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "build/spinfold"
    print(f"spinfold {spinfold.__version__}")

    # 1. 10^5 samples.
    scene, t_end, every = "spinning_rigid_sphere", 10000.0, 0.1
    args = ["--scene", scene, "--t-end", str(t_end), "--every", str(every), "--integrator", "dop853"]
    ours = best_of(3, lambda: spinfold.simulate(scene, t_end, every, integrator="dop853"))
    theirs = best_of(1, lambda: subprocess_numpy(binary, args))
    check = spinfold.simulate(scene, t_end, every, integrator="dop853").table()
    assert np.array_equal(check, subprocess_numpy(binary, args), equal_nan=True), "not the same numbers"
    print(f"1. 1e5 samples into NumPy: spinfold.simulate {ours:.3f} s, subprocess + JSON Lines {theirs:.2f} s: "
          f"{theirs / ours:.1f}x (target >= 20x)")

    # 2. run_many, 2 threads against 1.
    w5 = json.loads(spinfold._scene_text("separable_radial_abc"))  # physics.md W5: a deforming body
    scenes = []
    for i in range(200):
        scene = json.loads(json.dumps(w5))
        scene["initial"]["r"] = 0.5 + 0.004 * i
        scene["integrator"] = {"name": "dop853", "tolerance": 1e-10}
        scenes.append(scene)
    one = best_of(3, lambda: spinfold.run_many(scenes, t_end=200, every=2, threads=1))
    two = best_of(3, lambda: spinfold.run_many(scenes, t_end=200, every=2, threads=2))
    print(f"2. run_many of 200 W5 scenes (T = 200, dop853): threads=1 {one:.3f} s, threads=2 {two:.3f} s: {one / two:.2f}x "
          f"(target >= 1.8x on 2 cores)")

    # 3. One short call: Python's wall time against the engine's own time inside the module.
    short = dict(t_end=100.0, every=0.1, integrator="dop853")
    wall = best_of(20, lambda: spinfold.simulate(scene, **short))
    engine = min(spinfold._core.engine_seconds(spinfold._scene_text(scene), 100.0, 0.1, "dop853")
                 for _ in range(20))
    print(f"3. one simulate of 1,001 samples: {wall * 1e3:.3f} ms from Python, {engine * 1e3:.3f} ms in the "
          f"engine: overhead {100 * (wall - engine) / engine:.1f}% (target <= 10%)")


if __name__ == "__main__":
    main()
