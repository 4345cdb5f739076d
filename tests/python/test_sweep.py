"""spinfold.sweep and `spinfold sweep` are two doors to one library (sweep/): the README's two sweep
examples give the same rows to the bit, and bad input is refused the same way."""

import csv
import json
import math
import pathlib
import re
import shlex
import subprocess

import numpy as np
import pytest

import spinfold

README = pathlib.Path(__file__).resolve().parents[2] / "README.md"


def readme_examples():
    """The CLI's sweep command and Python's spinfold.sweep call, as README.md has them."""
    text = README.read_text(encoding="utf-8")
    cli = re.search(r"^spinfold sweep spinning_rigid_sphere (?:[^\n]*\\\n)*[^\n]*", text, re.M).group(0)
    start = text.index("table = spinfold.sweep(")
    depth, end = 0, start
    for end in range(text.index("(", start), len(text)):
        depth += {"(": 1, ")": -1}.get(text[end], 0)
        if depth == 0:
            break
    return cli.replace("\\\n", " "), text[start + len("table = "):end + 1]


def read_cli_rows(path):
    with open(path, newline="") as file:
        lines = [line for line in file if not line.startswith("#")]
    rows = list(csv.reader(lines))
    return rows[0], rows[1:]


def csv_name(name):
    """A column's name in a CSV header: dots written '_' (numpy.genfromtxt drops dots from names)."""
    return name.replace(".", "_")


def same_cell(cell, value):
    if isinstance(value, (float, np.floating)):
        if math.isnan(value):
            return cell == ""
        return cell != "" and float(cell) == value
    if isinstance(value, (int, np.integer)):
        return int(cell) == int(value)
    return cell == str(value)


def test_the_readme_examples_give_the_same_rows_to_the_bit(binary, tmp_path):
    command, call = readme_examples()
    args = shlex.split(command)
    assert args[:2] == ["spinfold", "sweep"] and "--out" in args
    args[args.index("--out") + 1] = str(tmp_path / "spins.csv")
    subprocess.run([binary, *args[1:], "--quiet"], check=True)
    columns, rows = read_cli_rows(tmp_path / "spins.csv")
    table = eval(call, {"spinfold": spinfold, "np": np})  # noqa: S307 - the README's own line
    assert [csv_name(name) for name in table] == columns
    assert len(rows) == len(table["index"]) == 80
    for j, name in enumerate(table):
        if name == "seconds":
            continue
        for i, row in enumerate(rows):
            assert same_cell(row[j], table[name][i]), (name, i, row[j], table[name][i])
    # Bit for bit: the values read back from the CLI's shortest text are the same doubles.
    spins = np.array([float(row[columns.index("initial_spin")]) for row in rows])
    assert np.array_equal(spins.view(np.uint64), table["initial.spin"].view(np.uint64))
    assert set(table["status"]) == {"ok"}


def test_the_grid_is_numpys_linspace_to_the_bit():
    # Structured and random (a, b, n), across signs, scales and counts; the CLI's grid is the same function.
    rng = np.random.default_rng(51)
    cases = [(0, 2, 31), (0, 2, 40), (0.1, 0.7, 3), (0.7, 0.1, 7), (-3, 5, 1), (0, 1e-320, 4), (1e-3, 1e3, 101)]
    cases += [(float(a), float(b), int(n)) for a, b, n in zip(rng.normal(0, 10, 500), rng.normal(0, 10, 500),
                                                               rng.integers(1, 400, 500))]
    for a, b, n in cases:
        ours = np.array(spinfold.grid(a, b, n), dtype=np.float64)
        assert np.array_equal(ours.view(np.uint64), np.linspace(a, b, n).view(np.uint64)), (a, b, n)
    rows = spinfold.sweep("spinning_rigid_sphere", {"initial.spin": "0:2:31"}, t_end=0.5, every=0.5)
    assert np.array_equal(np.asarray(rows["initial.spin"]).view(np.uint64), np.linspace(0, 2, 31).view(np.uint64))


def test_python_refuses_like_the_cli_naming_the_field():
    with pytest.raises(ValueError, match=r"vary\['initial.lambda'\]: initial.lambda: must be > 0"):
        spinfold.sweep("spinning_rigid_sphere", {"initial.lambda": [-1.0, 1.0]})
    with pytest.raises(ValueError, match=r"vary\['initial.phi'\]: the sweep would be more than 10000000 runs"):
        spinfold.sweep("spinning_rigid_sphere", {"initial.r": "1:2:10000", "initial.phi": "0:1:10000"})
    with pytest.raises(ValueError, match=r"vary\['initial.r'\]: a range is a:b:n"):
        spinfold.sweep("spinning_rigid_sphere", {"initial.r": "0:1:20000000"})
    with pytest.raises(ValueError, match="no scene field 'initial.nope'"):
        spinfold.sweep("spinning_rigid_sphere", {"initial.nope": [1]})
    with pytest.raises(ValueError, match="t_end: must be"):
        spinfold.sweep("spinning_rigid_sphere", {"initial.r": [1]}, t_end=-1)
    with pytest.raises(ValueError, match="zip: every varied field"):
        spinfold.sweep("spinning_rigid_sphere", {"initial.r": [1, 2], "initial.phi": [0]}, zip=True)


def test_default_columns_are_the_clis(binary, tmp_path):
    out = tmp_path / "rows.csv"
    subprocess.run([binary, "sweep", "spinning_rigid_sphere", "--set", "initial.r=1,1.5", "--t-end", "1",
                    "--out", str(out)], check=True)
    columns, rows = read_cli_rows(out)
    table = spinfold.sweep("spinning_rigid_sphere", {"initial.r": [1, 1.5]}, t_end=1)
    assert [csv_name(name) for name in table] == columns
    assert "drift.p_phi" in table and "seconds" in table


def test_summaries_and_events_are_the_clis_to_the_bit_and_numpy_columns(binary, tmp_path):
    out = tmp_path / "rows.csv"
    subprocess.run([binary, "sweep", "trapped_spin_bump", "--set", "initial.spin=0:0.3:4", "--t-end", "15",
                    "--fields", "t,u", "--summary", "u,energy_error.max", "--event", "u:up:0.5",
                    "--event", "phi:any:0:period=6.283185307179586:name=turn", "--quiet", "--out", str(out)],
                   check=True)
    columns, rows = read_cli_rows(out)
    table = spinfold.sweep("trapped_spin_bump", {"initial.spin": "0:0.3:4"}, t_end=15, fields="t,u",
                           summaries="u,energy_error.max",
                           events=["u:up:0.5", "phi:any:0:period=6.283185307179586:name=turn"])
    assert [csv_name(name) for name in table] == columns
    for name in ("u.max", "u.t_min", "energy_error.max", "u_up_0.5.count", "turn.t_first", "turn.at.u"):
        assert name in table, name
    for j, name in enumerate(table):
        if name == "seconds":
            continue
        for i, row in enumerate(rows):
            assert same_cell(row[j], table[name][i]), (name, i, row[j], table[name][i])
    assert table["turn.count"].dtype == np.uint64
    assert table["u.max"].dtype == np.float64
    assert np.all(table["u.min"] <= table["u.mean"]) and np.all(table["u.mean"] <= table["u.max"])
    # Where a run never crossed, its times are NaN, its count 0.
    never = table["u_up_0.5.count"] == 0
    assert np.all(np.isnan(table["u_up_0.5.t_first"][never]))


def test_summaries_and_events_refuse_like_the_cli():
    with pytest.raises(ValueError, match=r"summaries: summary 'r': unknown field 'r' for this scene \(one of u, phi"):
        spinfold.sweep("trapped_spin_bump", {"initial.spin": [0]}, summaries="r")
    with pytest.raises(ValueError, match=r"events: event 'u:up': write FIELD:DIRECTION:LEVEL"):
        spinfold.sweep("trapped_spin_bump", {"initial.spin": [0]}, events="u:up")


def test_chaos_indicators_are_the_clis_and_tell_chaos_from_order(binary, tmp_path):
    scene = pathlib.Path(__file__).resolve().parents[2] / "examples" / "chaotic_anisotropic_pseudosphere.json"
    out = tmp_path / "chaos.csv"
    subprocess.run([binary, "sweep", str(scene), "--set", "potential.deformation.A=0.1,0", "--t-end", "100",
                    "--fields", "t", "--chaos", "--quiet", "--out", str(out)], check=True)
    columns, rows = read_cli_rows(out)
    table = spinfold.sweep(str(scene), {"potential.deformation.A": [0.1, 0]}, t_end=100, fields="t", chaos=True)
    assert [csv_name(name) for name in table] == columns
    for j, name in enumerate(table):
        if name != "seconds":
            for i, row in enumerate(rows):
                assert same_cell(row[j], table[name][i]), (name, i, row[j], table[name][i])
    assert table["chaos.lyapunov"][0] > 0.3 and table["chaos.megno_mean"][0] > 10
    with pytest.raises(ValueError, match=r"chaos_interval: must be a number > 0 \[time\] \(got -1\)"):
        spinfold.sweep(str(scene), {"potential.deformation.A": [0.1]}, chaos=True, chaos_interval=-1)


def test_npz_rows_and_trajectories_load_in_numpy_as_the_csv(binary, tmp_path):
    common = [binary, "sweep", "spinning_rigid_sphere", "--set", "initial.r=1,1.5", "--t-end", "2",
              "--summary", "r.max", "--quiet"]
    subprocess.run([*common, "--out", str(tmp_path / "rows.csv"), "--trajectories", str(tmp_path / "csv"),
                    "--trajectory-fields", "t,r,X", "--trajectory-format", "csv"], check=True)
    subprocess.run([*common, "--out", str(tmp_path / "rows.npz"), "--trajectories", str(tmp_path / "npz"),
                    "--trajectory-fields", "t,r,X", "--trajectory-format", "npz"], check=True)
    columns, rows = read_cli_rows(tmp_path / "rows.csv")
    archive = np.load(tmp_path / "rows.npz")
    assert [csv_name(name) for name in archive.files if name != "provenance"] == columns
    for j, name in enumerate(archive.files):
        if name in ("seconds", "provenance"):
            continue
        for i, row in enumerate(rows):
            assert same_cell(row[j], archive[name][i].item()), (name, i, row[j], archive[name][i])
    assert '"sweep"' in str(archive["provenance"][0])
    for run in (0, 1):
        text = np.genfromtxt(tmp_path / "csv" / f"{run}.csv", delimiter=",", names=True, comments="#")
        arrays = np.load(tmp_path / "npz" / f"{run}.npz")
        assert arrays.files == ["t", "r", "X.0", "X.1", "X.2", "provenance"]
        for name in ("t", "r", "X.0", "X.1", "X.2"):
            assert np.array_equal(arrays[name], text[csv_name(name)]), name


def test_simulate_and_run_many_give_each_runs_summary_as_the_sweep_does():
    kwargs = dict(summaries="r", events=["r:up:1.3", "phi:any:0:period=6.283185307179586:name=turn"])
    table = spinfold.sweep("separable_radial_abc", {"initial.r": [1.2, 1.1]}, t_end=20, **kwargs)
    one = spinfold.simulate("separable_radial_abc", t_end=20, **kwargs)
    many = spinfold.run_many(["separable_radial_abc", "separable_radial_abc"], t_end=20, **kwargs)
    assert set(one.summary) == {"r.min", "r.max", "r.mean", "r.final", "r.t_min", "r.t_max", "r_up_1.3.count",
                                "r_up_1.3.t_first", "r_up_1.3.t_last", "r_up_1.3.at.r", "turn.count", "turn.t_first",
                                "turn.t_last", "turn.at.r"}
    for name, value in one.summary.items():
        assert value == table[name][0] or (math.isnan(value) and math.isnan(table[name][0])), name
        assert many[1].summary[name] == value or math.isnan(value), name
    assert one.summary["r.final"] == one["r"][-1]
    with pytest.raises(ValueError, match=r"scenes\[1\]: summaries: summary 'r': unknown field 'r'"):
        spinfold.run_many(["separable_radial_abc", "trapped_spin_bump"], t_end=1, summaries="r")
    with pytest.raises(ValueError, match=r"events: event 'r:up': write FIELD:DIRECTION:LEVEL"):
        spinfold.simulate("separable_radial_abc", t_end=1, events="r:up")


def test_a_period_below_the_fields_precision_stops_each_run_with_its_status_at_once():
    # Issue 48: each step visited every level it crossed, so this ran until killed (Ctrl-C could
    # not stop it); now each run stops with event_unresolved in its first step.
    import time
    start = time.monotonic()
    rows = spinfold.sweep("spinning_rigid_sphere", {"initial.spin": [0.5, 1.0]}, t_end=10.0,
                          events=["phi:any:0:period=1e-300"])
    assert time.monotonic() - start < 5.0
    assert list(rows["status"]) == ["event_unresolved", "event_unresolved"]


def test_wrong_types_are_refused_naming_the_argument():
    # Issue 48: a bare "'int' object is not iterable" before.
    with pytest.raises(TypeError, match=r"events: must be a text or a sequence of texts \(got 5\)"):
        spinfold.sweep("spinning_rigid_sphere", {"initial.spin": "0,1"}, events=5)
    with pytest.raises(TypeError, match=r"summaries: must be a text or a sequence of texts"):
        spinfold.simulate("spinning_rigid_sphere", 1.0, summaries=7)
    with pytest.raises(TypeError, match=r"vary\['initial.spin'\]: must be a text such as '0:2:40'"):
        spinfold.sweep("spinning_rigid_sphere", {"initial.spin": 5})


def test_nan_or_infinity_in_a_scene_dict_is_refused_naming_the_field():
    scene = {"surface": {"kind": "sphere", "radius": 1.0}, "initial": {"r": 0.5, "spin": math.nan}}
    with pytest.raises(ValueError, match=r"scene.initial.spin: must be a finite number \(got nan\)"):
        spinfold.simulate(scene, 1.0)
    scene["initial"]["spin"] = math.inf
    with pytest.raises(ValueError, match=r"base.initial.spin: must be a finite number \(got inf\)"):
        spinfold.sweep(scene, {"initial.r": "0.1,0.2"})


def test_ctrl_c_stops_a_sweep_after_the_runs_in_progress():
    import os
    import signal
    import sys
    import time
    code = ("import spinfold, sys; print('started', flush=True); "
            "spinfold.sweep('spin_vs_geodesic_torus', {'initial.spin': '0:1:2000'}, t_end=1000.0)")
    child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, env=dict(os.environ))
    assert child.stdout.readline().strip() == "started"
    time.sleep(1.0)
    child.send_signal(signal.SIGINT)
    start = time.monotonic()
    _, err = child.communicate(timeout=30)
    assert time.monotonic() - start < 10.0
    assert child.returncode != 0
    assert "KeyboardInterrupt" in err


def test_simulate_and_run_many_give_the_clis_chaos_indicators(binary):
    # simulate(chaos=True) is `spinfold simulate --chaos` to the bit (issue 51 item 6: it had none).
    out = subprocess.run([binary, "simulate", "spin_vs_geodesic_torus", "--t-end", "40", "--every", "10",
                          "--fields", "t", "--chaos"], check=True, capture_output=True, text=True).stdout
    cli = json.loads(out.strip().splitlines()[-1])["summary"]
    one = spinfold.simulate("spin_vs_geodesic_torus", t_end=40, every=10, chaos=True).summary
    many = spinfold.run_many(["spin_vs_geodesic_torus", "spinning_rigid_sphere"], t_end=40, every=10, chaos=True)
    for name in ("chaos.lyapunov", "chaos.megno", "chaos.megno_mean", "chaos.lyapunov_time", "chaos.t"):
        assert one[name] == cli[name] and many[0].summary[name] == cli[name], name
    assert one["chaos.t"] == 40 and 1.0 < one["chaos.megno_mean"] < 3.0
    assert "chaos.megno" in many[1].summary
    assert "chaos.megno" not in spinfold.simulate("spin_vs_geodesic_torus", t_end=1).summary


def test_every_crossing_is_a_result_of_its_own(binary, tmp_path):
    # simulate(events="...:record") gives each crossing's sample, as `--crossings` writes it.
    result = spinfold.simulate("spin_vs_geodesic_torus", t_end=60, events=["u:up:0:record", "u:down:1"])
    section = result.crossings["u_up_0"]
    assert list(result.crossings) == ["u_up_0"]
    assert len(section["t"]) == result.summary["u_up_0.count"] >= 2
    assert section["t"][0] == result.summary["u_up_0.t_first"] and section["t"][-1] == result.summary["u_up_0.t_last"]
    assert np.all(np.abs(section["u"]) < 1e-9) and np.all(np.diff(section["t"]) > 0)
    out = tmp_path / "c.csv"
    subprocess.run([binary, "simulate", "spin_vs_geodesic_torus", "--t-end", "60", "--fields", "t,phi,speed",
                    "--event", "u:up:0:record", "--crossings", str(out)], check=True, capture_output=True)
    table = np.genfromtxt(out, delimiter=",", names=True, comments="#", dtype=None, encoding="utf-8")
    assert np.array_equal(table["t"], section["t"]) and np.array_equal(table["phi"], section["phi"])
    assert np.array_equal(table["occurrence"], np.arange(1, len(section["t"]) + 1))


def test_options_are_strict_and_told_apart_from_scene_fields():
    # A yes-or-no option takes True or False only: "yes" was accepted as true (issue 51, item 6).
    for bad in ("yes", 1, None):
        with pytest.raises(TypeError, match=r"chaos: must be True or False"):
            spinfold.sweep("spinning_rigid_sphere", {"initial.spin": "0:1:2"}, t_end=0.5, chaos=bad)
    with pytest.raises(TypeError, match=r"zip: must be True or False"):
        spinfold.sweep("spinning_rigid_sphere", {"initial.spin": "0:1:2"}, t_end=0.5, zip="no")
    # A misspelt option is named as one, not as an unknown scene field.
    with pytest.raises(TypeError, match=r"summary: not an option \(did you mean summaries=\?\)"):
        spinfold.simulate("spinning_rigid_sphere", t_end=0.5, summary="r")
    for bad in ("yes", 1):
        with pytest.raises(TypeError, match=r"chaos: must be True or False"):
            spinfold.simulate("spinning_rigid_sphere", t_end=0.5, chaos=bad)
        with pytest.raises(TypeError, match=r"chaos: must be True or False"):
            spinfold.run_many(["spinning_rigid_sphere"], t_end=0.5, chaos=bad)
    with pytest.raises(TypeError, match=r"chaos_interval: must be a number"):
        spinfold.simulate("spinning_rigid_sphere", t_end=0.5, chaos=True, chaos_interval="1")
    with pytest.raises(TypeError, match=r"chaos_interval: must be a number"):
        spinfold.sweep("spinning_rigid_sphere", {"initial.spin": "0:1:2"}, t_end=0.5, chaos=True, chaos_interval="1")
    with pytest.raises(ValueError, match=r"chaos_interval: must be a number > 0 \[time\] \(got -1\)"):
        spinfold.simulate("spinning_rigid_sphere", t_end=0.5, chaos=True, chaos_interval=-1)
    with pytest.raises(ValueError, match=r"chaos_interval: must be at most the run's length"):
        spinfold.run_many(["spinning_rigid_sphere"], t_end=0.5, chaos=True, chaos_interval=2)
    # Scene fields and the flags still pass.
    assert spinfold.simulate("spinning_rigid_sphere", t_end=0.5, initial__spin=0.5, tolerance=1e-9) is not None
