"""spinfold's CSV files read as they are by numpy.genfromtxt(names=True, comments="#") and
pandas.read_csv(comment="#"): the names line first (dots written '_', which survive numpy's name
cleaning), the provenance after it as comment lines, and the same doubles as the JSON Lines."""

import csv
import json
import subprocess

import numpy as np
import pandas as pd

FIELDS = "t,r,phi,X,L.0,energy_error,det_L"
NAMES = ["t", "r", "phi", "X_0", "X_1", "X_2", "L_0_0", "L_0_1", "energy_error", "det_L"]


def simulate(binary, *args):
    return subprocess.run([binary, "simulate", "--scene", "separable_radial_abc", "--t-end", "3", "--every",
                           "0.5", *args], check=True, capture_output=True, text=True).stdout


def json_samples(binary):
    lines = simulate(binary).splitlines()
    return [json.loads(line) for line in lines[1:]]


def expected_columns(samples):
    """The JSON Lines samples' values under the CSV's names, in its order."""
    return {
        "t": [s["t"] for s in samples], "r": [s["r"] for s in samples], "phi": [s["phi"] for s in samples],
        **{f"X_{i}": [s["X"][i] for s in samples] for i in range(3)},
        **{f"L_0_{j}": [s["L"][0][j] for s in samples] for j in range(2)},
        "energy_error": [s["energy_error"] for s in samples], "det_L": [s["det_L"] for s in samples],
    }


def test_genfromtxt_reads_a_simulate_csv_as_it_is(binary, tmp_path):
    path = tmp_path / "run.csv"
    path.write_text(simulate(binary, "--format", "csv", "--fields", FIELDS))
    table = np.genfromtxt(path, delimiter=",", names=True, comments="#")
    assert list(table.dtype.names) == NAMES
    expected = expected_columns(json_samples(binary))
    assert len(table) == 7
    for name in NAMES:  # the same doubles, bit for bit
        assert np.array_equal(table[name].view(np.uint64), np.array(expected[name]).view(np.uint64)), name


def test_pandas_reads_a_simulate_csv_as_it_is(binary, tmp_path):
    path = tmp_path / "run.csv"
    path.write_text(simulate(binary, "--format", "csv", "--fields", FIELDS))
    frame = pd.read_csv(path, comment="#")
    assert list(frame.columns) == NAMES
    expected = expected_columns(json_samples(binary))
    for name in NAMES:
        # pandas' default float parser is not correctly rounded (within a few ulps) ...
        assert np.allclose(frame[name], expected[name], rtol=4e-15, atol=0), name
    # ... its round-trip parser gives the same doubles, bit for bit.
    exact = pd.read_csv(path, comment="#", float_precision="round_trip")
    for name in NAMES:
        assert exact[name].tolist() == expected[name], name


def test_every_default_column_survives_numpys_name_cleaning(binary, tmp_path):
    path = tmp_path / "all.csv"
    path.write_text(simulate(binary, "--format", "csv"))
    header = path.read_text().splitlines()[0].split(",")
    table = np.genfromtxt(path, delimiter=",", names=True, comments="#", dtype=None, encoding="utf-8")
    assert list(table.dtype.names) == header
    assert table["status"][-1] == "ok"
    assert list(pd.read_csv(path, comment="#").columns) == header


def test_both_read_a_sweep_csv_and_its_varied_fields(binary, tmp_path):
    path = tmp_path / "rows.csv"
    subprocess.run([binary, "sweep", "spinning_rigid_sphere", "--set", "initial.r=0.5:1.5:5", "--set",
                    "initial.spin=0,0.5", "--t-end", "1", "--fields", "r,X", "--quiet", "--out", str(path)],
                   check=True)
    table = np.genfromtxt(path, delimiter=",", names=True, comments="#", dtype=None, encoding="utf-8")
    assert table.dtype.names[:7] == ("index", "initial_r", "initial_spin", "r", "X_0", "X_1", "X_2")
    assert list(table["initial_r"]) == [0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.25, 1.25, 1.5, 1.5]
    assert list(table["initial_spin"][:2]) == [0.0, 0.5]
    frame = pd.read_csv(path, comment="#", float_precision="round_trip")
    assert list(frame.columns) == list(table.dtype.names)
    assert frame["X_2"].tolist() == list(table["X_2"])
    assert set(frame["status"]) == {"ok"}


def test_an_npz_loads_in_numpy_with_the_csvs_numbers(binary, tmp_path):
    """`simulate --out run.npz`: numpy.load, nothing of spinfold needed; every column the CSV's, to
    the bit (null cells NaN in both), the text columns as text, the provenance beside them."""
    csv_path, npz_path = tmp_path / "run.csv", tmp_path / "run.npz"
    csv_path.write_text(simulate(binary, "--format", "csv"))
    subprocess.run([binary, "simulate", "--scene", "separable_radial_abc", "--t-end", "3", "--every", "0.5",
                    "--out", str(npz_path)], check=True)
    lines = [line for line in csv_path.read_text().splitlines() if not line.startswith("#")]
    cells = list(csv.reader(lines))
    text = {name: [row[j] for row in cells[1:]] for j, name in enumerate(cells[0])}  # the cells as written
    numbers = np.genfromtxt(csv_path, delimiter=",", names=True, comments="#")  # empty cells NaN
    with np.load(npz_path) as arrays:
        names = [name for name in arrays.files if name != "provenance"]
        assert [name.replace(".", "_") for name in names] == list(numbers.dtype.names)
        for name in names:
            column = arrays[name]
            if column.dtype == np.float64:
                expected = numbers[name.replace(".", "_")]
                assert np.array_equal(np.isnan(column), np.isnan(expected)), name
                same = ~np.isnan(column)
                assert np.array_equal(column[same].view(np.uint64), expected[same].view(np.uint64)), name
            else:
                assert [str(v) for v in column] == text[name.replace(".", "_")], name
        assert json.loads(str(arrays["provenance"][0]))["software"] == "spinfold"
