"""The `spinfold` package against the CLI it must agree with: the same numbers to the bit, the same
pixels, clear errors, the GIL released while C++ runs, no memory growth."""

import ast
import json
import math
import os
import pathlib
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import spinfold
from conftest import cli_samples

SCENES_DIR = pathlib.Path(__file__).resolve().parents[2] / "assets" / "scenes"
FAR_H2 = {"surface": {"kind": "pseudosphere", "radius": 1}, "initial": {"r": 22, "spin": 1}}


def flat(sample):
    """A JSON sample's numbers by flattened name (as spinfold.field_names())."""
    out = {}

    def walk(value, prefix):
        if isinstance(value, dict):
            for k, v in value.items():
                walk(v, f"{prefix}{k}.")
        elif isinstance(value, list):
            for i, v in enumerate(value):
                walk(v, f"{prefix}{i}.")
        else:
            out[prefix[:-1]] = value

    for key, value in sample.items():
        if key not in ("undefined", "events", "companions", "status", "status_detail", "integrator"):
            walk(value, key + ".")
    return out


def assert_same_numbers(result, samples):
    table = result.table()
    names = spinfold.field_names()
    assert table.shape == (len(samples), len(names))
    for row, sample in enumerate(samples):
        values = flat(sample)
        for column, name in enumerate(names):
            expected = values.get(name)
            got = table[row, column]
            if expected is None:
                assert math.isnan(got), (row, name)
            else:
                assert got == expected, (row, name, got, expected)  # to the bit: == on doubles
        assert result["status"][row] == sample["status"]
        assert result["steps"][row] == sample["steps"]


@pytest.mark.parametrize("preset", ["spin_vs_geodesic_sphere", "separable_radial_abc", "degenerate_crossing",
                                    "incompressible_breathing_ellipse", "pole_crossing_sphere"])
def test_simulate_equals_the_cli_to_the_bit(binary, preset):
    result = spinfold.simulate(preset, t_end=3, every=0.25)
    samples = cli_samples(binary, "--scene", preset, "--t-end", "3", "--every", "0.25")
    assert_same_numbers(result, samples)
    # Events at the same times, with the sample that first reports them.
    cli_events = [(e["t"], row) for row, s in enumerate(samples) for e in s["events"]]
    assert [(e["t"], e["sample"]) for e in result["events"]] == cli_events
    # Companions too.
    assert len(result.companions) == len(samples[0].get("companions", []))
    for i, companion in enumerate(result.companions):
        assert companion.label == samples[0]["companions"][i]["label"]
        assert_same_numbers(companion, [s["companions"][i] for s in samples])


def test_a_torus_scene_equals_the_cli_to_the_bit(binary, tmp_path):
    # A surface whose curvature varies: its chart's u, u_dot, p_u and K are columns, r is NaN.
    scene = {"surface": {"kind": "torus", "tube_radius": 0.6, "center_radius": 2.0},
             "potential": {"height": {"kind": "gravity", "g": 0.5}, "deformation": {"kind": "abc", "C": 0.3}},
             "friction": {"internal": 0.02},
             "initial": {"u": 0.3, "lambda": 1.2, "mu": 0.8, "speed": 1, "heading": 1.2, "spin": 0.4}}
    path = tmp_path / "torus.json"
    path.write_text(json.dumps(scene))
    result = spinfold.simulate(scene, t_end=2, every=0.5)
    assert_same_numbers(result, cli_samples(binary, str(path), "--t-end", "2", "--every", "0.5"))
    assert np.isnan(result["r"]).all() and not np.isnan(result["u"]).any() and not np.isnan(result["K"]).any()
    with pytest.raises(ValueError, match="initial.r"):
        spinfold.simulate(scene, t_end=1, initial__r=1.0)


def test_a_formula_surface_equals_the_cli_to_the_bit(binary, tmp_path):
    # No chart: X, V, e1, e2, n, K and the drift off F = 0 are columns, r and u are NaN.
    scene = {"surface": {"kind": "implicit", "F": "x^2/a^2 + y^2/b^2 + z^2/c^2 - 1",
                         "parameters": {"a": 2, "b": 1.5, "c": 1}},
             "potential": {"deformation": {"kind": "abc", "C": 0.3}},
             "initial": {"X": [1.0, 0.8, 0.5], "lambda": 1.2, "mu": 0.8, "speed": 0.7, "heading": 0.4,
                         "spin": 0.3}}
    path = tmp_path / "ellipsoid.json"
    path.write_text(json.dumps(scene))
    result = spinfold.simulate(scene, t_end=2, every=0.5)
    assert_same_numbers(result, cli_samples(binary, str(path), "--t-end", "2", "--every", "0.5"))
    assert np.isnan(result["r"]).all() and np.isnan(result["u"]).all()
    for name in ("V.0", "e1.2", "n.1", "K", "constraint_drift"):
        assert not np.isnan(result[name]).any(), name
    assert (result["constraint_drift"] < 1e-14).all()
    # On the surface: x²/a² + y²/b² + z²/c² = 1 at every sample, read by numpy.
    x, y, z = result["X"].T
    assert np.allclose(x**2 / 4 + y**2 / 2.25 + z**2, 1.0, atol=1e-13)
    # A parameter is a field of its own name: swept, and refused with its reason.
    sweep = spinfold.sweep(scene, {"surface.parameters.c": [0.8, 1.0, 1.2]}, t_end=1)
    assert list(sweep["surface.parameters.c"]) == [0.8, 1.0, 1.2]
    with pytest.raises(ValueError, match=r"surface\.F: at position 0"):
        spinfold.simulate({**scene, "surface": {"kind": "implicit", "F": "abs(x) + y^2 + z^2 - 1"}}, t_end=1)
    with pytest.raises(ValueError, match="initial.X"):
        spinfold.simulate({**scene, "initial": {"X": [0, 0, 0]},
                           "surface": {"kind": "implicit", "F": "x^2 + y^2 - z^2"}}, t_end=1)


def test_a_scene_as_dict_json_path_or_preset_and_overrides_run_the_same(binary, tmp_path):
    scene = {"surface": {"kind": "sphere"}, "initial": {"r": 0.8, "spin": 1.2}}
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    by_dict = spinfold.simulate(scene, t_end=2, every=0.5, integrator="dop853", tolerance=1e-11)
    by_text = spinfold.simulate(json.dumps(scene), t_end=2, every=0.5, integrator="dop853", tolerance=1e-11)
    by_path = spinfold.simulate(str(path), t_end=2, every=0.5, integrator="dop853", tolerance=1e-11)
    by_pathlib = spinfold.simulate(path, t_end=2, every=0.5, integrator="dop853", tolerance=1e-11)
    for other in (by_text, by_path, by_pathlib):
        assert np.array_equal(by_dict.table(), other.table(), equal_nan=True)
    samples = cli_samples(binary, str(path), "--t-end", "2", "--every", "0.5", "--integrator", "dop853",
                          "--tolerance", "1e-11")
    assert_same_numbers(by_dict, samples)
    assert by_dict.integrator == "dop853"
    # A dotted override: initial.spin through initial__spin.
    spun = spinfold.simulate(scene, t_end=1, every=1, initial__spin=0.0)
    assert spun["spin"][0] == 0.0


def test_far_out_on_h2_the_lost_values_are_nan_with_their_reasons(binary):
    result = spinfold.simulate(FAR_H2, t_end=1, every=0.5)
    assert np.isnan(result["p_phi"]).all()
    assert "p_phi" in result.reasons
    assert "p_phi" in result.undefined(0)
    assert np.isfinite(result["casimir"]).all()


def test_result_shapes_events_and_provenance():
    result = spinfold.simulate("degenerate_crossing", t_end=1, every=0.25)
    assert result["X"].shape == (5, 3)
    assert result["L"].shape == (5, 2, 2)
    assert result["M"].shape == (5, 3)
    assert result["events"].dtype.names == ("t", "sample", "kind")
    assert len(result["events"]) == 1 and abs(result["events"]["t"][0] - 0.5) < 1e-9
    assert result["events"]["kind"][0] == "det_L_zero"
    p = result.provenance
    assert p["software"] == "spinfold" and p["version"] == spinfold.__version__.split("+")[0]
    assert len(p["scene_hash"]) == 16
    assert p["integrator"]["runs"] == result.integrator
    assert result.status == "ok" and result.complete
    assert "r" in result and len(result) == len(list(result))


def test_max_steps_stops_a_run_and_says_so():
    result = spinfold.simulate("spinning_rigid_sphere", t_end=10, every=1, integrator="rk4", dt=0.001,
                               max_steps=2500)
    assert not result.complete
    assert result["t"][-1] == 2.0


def test_bad_arguments_raise_naming_the_field():
    with pytest.raises(ValueError, match="initial.r"):
        spinfold.simulate({"initial": {"r": -1}}, t_end=1)
    with pytest.raises(ValueError, match="no_such_preset"):
        spinfold.simulate("no_such_preset")
    with pytest.raises(ValueError, match="t_end"):
        spinfold.simulate("spinning_rigid_sphere", t_end=-1)
    with pytest.raises(ValueError, match="every"):
        spinfold.simulate("spinning_rigid_sphere", every=0)
    with pytest.raises(ValueError, match="every"):
        spinfold.simulate("spinning_rigid_sphere", t_end=1e9, every=1e-3)
    with pytest.raises(TypeError, match="scene"):
        spinfold.simulate(42)
    with pytest.raises(ValueError, match="scene"):
        spinfold.simulate('{"surface": ')
    with pytest.raises(ValueError, match="scenes\\[1\\]"):
        spinfold.run_many(["spinning_rigid_sphere", {"initial": {"r": -1}}], t_end=1)
    with pytest.raises(ValueError, match="view"):
        spinfold.render("spinning_rigid_sphere", view="hyperboloid")
    with pytest.raises(ValueError, match="layers"):
        spinfold.render("spinning_rigid_sphere", layers="surface,nope")
    with pytest.raises(TypeError, match="width"):
        spinfold.render("spinning_rigid_sphere", width=64.5)
    with pytest.raises(ValueError, match="width"):
        spinfold.render("spinning_rigid_sphere", width=8)
    with pytest.raises(ValueError, match="fields"):
        spinfold.sweep("spinning_rigid_sphere", {"initial.spin": [1]}, fields=["nope"])


def test_simulation_advanced_in_pieces_equals_one_run(binary):
    sim = spinfold.Simulation("separable_radial_abc")
    for until in (0.37, 1.1, 2.0):
        assert sim.advance(until)
    samples = cli_samples(binary, "--scene", "separable_radial_abc", "--t-end", "2", "--every", "2")
    assert sim.state["r"] == samples[-1]["r"] and sim.state["X"] == samples[-1]["X"]
    # The trajectory is replayed: the CLI's samples whatever the advances.
    trajectory = sim.trajectory(every=0.5)
    assert_same_numbers(trajectory, cli_samples(binary, "--scene", "separable_radial_abc", "--t-end", "2",
                                                "--every", "0.5"))


def test_simulation_patch_continues_refuses_or_restarts():
    sim = spinfold.Simulation("spinning_rigid_sphere")
    sim.advance(1.0)
    before = sim.state
    kind, reason = sim.patch({"body": {"mass": 2.0}})
    assert kind == "continued" and reason == "new parameters from t = 1 on, continuing from the current state"
    assert sim.t == 1.0 and sim.state["X"] == before["X"] and sim.scene["body"]["mass"] == 2.0
    with pytest.raises(ValueError, match="body.mass"):
        sim.patch({"body": {"mass": -1}})
    assert sim.scene["body"]["mass"] == 2.0 and sim.t == 1.0  # nothing changed
    with pytest.raises(TypeError):
        sim.patch([1, 2])
    assert sim.patch({"body": {"mass": 2.0}})[0] == "unchanged"
    kind, _ = sim.patch({"initial": {"r": 0.5}})
    assert kind == "restarted" and sim.t == 0.0
    sim.advance(0.5)
    sim.reset()
    assert sim.t == 0.0 and sim.scene["initial"]["r"] == 0.5
    # The retuned run's trajectory is that of the changes replayed.
    sim2 = spinfold.Simulation("spinning_rigid_sphere")
    sim2.advance(0.5)
    sim2.patch({"body": {"mass": 3.0}})
    sim2.advance(1.5)
    replay = sim2.trajectory(every=0.5)
    assert replay["X"][-1].tolist() == sim2.state["X"]


def test_run_many_equals_simulate_and_releases_the_gil():
    scenes = [{"initial": {"r": 0.5 + 0.01 * i, "spin": 1.0}, "integrator": {"name": "dop853"}} for i in range(40)]
    many = spinfold.run_many(scenes, t_end=200, every=10, threads=2)
    for scene, result in zip(scenes[:3], many[:3]):
        assert np.array_equal(spinfold.simulate(scene, t_end=200, every=10).table(), result.table(), equal_nan=True)
    # The GIL is released while C++ runs, shown by order, not by counting (a count against the clock
    # failed on a busy CI machine). With a switch interval far longer than the run, the interpreter
    # never takes the GIL from a thread: the only way this thread runs again while the other is
    # inside run_many is that run_many let the GIL go. A run that kept it would finish first.
    entered = threading.Event()
    finished = []

    def run():
        entered.set()
        spinfold.run_many(scenes, t_end=200000, every=1000, threads=1)  # about a second
        finished.append(True)

    interval = sys.getswitchinterval()
    sys.setswitchinterval(100.0)
    try:
        worker = threading.Thread(target=run)
        worker.start()
        entered.wait()
        ran_during_the_run = not finished
        worker.join()
    finally:
        sys.setswitchinterval(interval)
    assert finished and ran_during_the_run, "run_many kept the GIL: this thread ran only after it returned"


def test_sweep_rows_are_the_runs_of_simulate():
    rows = spinfold.sweep("spinning_rigid_sphere", {"initial.spin": [0.0, 0.5, 1.0], "body.mass": [1.0, 2.0]},
                          t_end=2, every=1, fields=["t", "r", "phi"])
    assert list(rows["initial.spin"]) == [0.0, 0.0, 0.5, 0.5, 1.0, 1.0]
    assert list(rows["body.mass"]) == [1.0, 2.0] * 3
    for i in range(6):
        scene = {"initial": {"spin": rows["initial.spin"][i]}, "body": {"mass": rows["body.mass"][i]}}
        one = spinfold.simulate("spinning_rigid_sphere", t_end=2, every=1,
                                initial__spin=float(rows["initial.spin"][i]), body__mass=float(rows["body.mass"][i]))
        assert rows["r"][i] == one["r"][-1] and rows["phi"][i] == one["phi"][-1], scene
    paired = spinfold.sweep("spinning_rigid_sphere", {"initial.spin": [0.0, 1.0], "body.mass": [1.0, 2.0]},
                            t_end=1, every=1, zip=True)
    assert list(paired["body.mass"]) == [1.0, 2.0]


def test_render_equals_the_cli_png_pixels(binary, tmp_path):
    for args in (dict(scene="spin_vs_geodesic_sphere", t=2.5, view=None),
                 dict(scene="spin_vs_geodesic_pseudosphere", t=1.0, view="disk")):
        png = tmp_path / "cli.png"
        command = [binary, "render", "--scene", args["scene"], "--t", str(args["t"]), "--width", "320",
                   "--height", "240", "--out", str(png)]
        if args["view"]:
            command += ["--view", args["view"]]
        subprocess.run(command, check=True)
        cli = spinfold.Frame.from_png(png.read_bytes())
        frame = spinfold.render(args["scene"], t=args["t"], view=args["view"], width=320, height=240)
        assert frame.pixels.shape == (240, 320, 4) and frame.pixels.dtype == np.uint8
        assert np.array_equal(frame.pixels[:, :, :3], cli.pixels[:, :, :3])
        # Opaque, as the PNG (RGB) is: the whole RGBA array equals the PNG read back (issue 35:
        # a translucent fill's alpha was left in Frame.pixels).
        assert np.array_equal(frame.pixels, cli.pixels)
        assert dict(cli.texts)["Software"] == dict(frame.texts)["Software"]
    # save() and _repr_png_ are that frame as PNG, with the provenance.
    frame.save(tmp_path / "py.png")
    again = spinfold.Frame.from_png((tmp_path / "py.png").read_bytes())
    assert np.array_equal(again.pixels[:, :, :3], frame.pixels[:, :, :3])
    assert frame._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"
    assert json.loads(dict(again.texts)["Source"])["t"] == 1.0


def test_memory_does_not_grow_over_a_thousand_runs():
    def resident_kib():
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") // 1024

    for _ in range(50):
        spinfold.simulate("spin_vs_geodesic_sphere", t_end=1, every=0.1)
    before = resident_kib()
    for _ in range(1000):
        spinfold.simulate("spin_vs_geodesic_sphere", t_end=1, every=0.1)
    assert resident_kib() - before < 8 * 1024


def test_presets_integrators_version_and_documentation():
    assert "spinning_rigid_sphere" in spinfold.presets()
    assert {"dop853", "exact"} <= {i["name"] for i in spinfold.integrators()}
    assert spinfold.__version__.startswith("0.")
    for name in spinfold.__all__:
        obj = getattr(spinfold, name)
        if callable(obj):
            assert obj.__doc__ and obj.__doc__.strip(), f"{name} has no docstring"
    # The stub of the compiled module declares every function it has.
    stub = pathlib.Path(spinfold.__file__).with_name("_core.pyi").read_text()
    declared = {node.name for node in ast.walk(ast.parse(stub)) if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    public = {name for name in dir(spinfold._core) if not name.startswith("_")}
    assert public <= declared, public - declared
