"""One table of inputs through every front door: the CLI (`spinfold render`/`simulate`: exit 2, the
reason on stderr), the HTTP API (422 application/problem+json naming the field) and Python
(ValueError, or TypeError for a value of the wrong type, naming the argument). A front door
translates; it does not decide: each refuses a value with the rule and the words of the library
that owns it (render/view_parameters.h, engine/run_limits.h, the scene's validation), so the field
and the reason are the same everywhere. Good inputs give the same numbers and pixels everywhere.
"""

import json
import math
import os
import subprocess
import tempfile
import urllib.error
import urllib.parse
import urllib.request

import numpy as np
import pytest

import spinfold

SCENE = "spinning_rigid_sphere"
NA = None  # the front door has no such input


def cli_flag(name):
    return "--" + name.replace("_", "-")


# ---- the table ----------------------------------------------------------------------------------
# (kind, field, value as Python gives it, value as text (CLI, query), reason, Python's error type)
# kind: "view" (render: CLI --NAME, query NAME=, render(NAME=)), "run" (simulate: CLI --NAME,
# simulate(NAME=); no HTTP input), "scene" (a scene field: CLI --dt/--tolerance or a scene file,
# POST /api/v1/sessions, simulate(dt=) or a dict).
PITCH = "must be a number from -1.55 to 1.55 [rad]"
SIDE = "must be a whole number from 16 to 4096 [pixels]"
SCALE = "must be a number in (0, 10]"
DISTANCE = "must be a number from 1.2 to 100 [radii]"
YAW = "must be a number from -100 to 100 [rad]"
TRAIL = "must be a number >= 0 [time]"
SHOWN = "must be a number from 16 to 4096 [pixels]"
MAX_STEPS = "must be a whole number from 1 to 9007199254740992"
T_END = "must be a number >= 0 [time]"
EVERY = "must be a number > 0 [time]"

BAD = [
    # view parameters: out of range, NaN, infinite, huge, negative, not whole, wrong type
    ("view", "pitch", 3.0, "3", PITCH, ValueError),
    ("view", "pitch", 2, "2", PITCH, ValueError),
    ("view", "pitch", math.nan, "nan", PITCH, ValueError),
    ("view", "pitch", math.inf, "inf", PITCH, ValueError),
    ("view", "pitch", "0.3", "abc", PITCH, TypeError),
    ("view", "yaw", 1e3, "1000", YAW, ValueError),
    ("view", "distance", 0.5, "0.5", DISTANCE, ValueError),
    ("view", "distance", -math.inf, "-inf", DISTANCE, ValueError),
    ("view", "width", 2**40, "1099511627776", SIDE, ValueError),
    ("view", "width", 5000, "5000", SIDE, ValueError),
    ("view", "width", -16, "-16", SIDE, ValueError),
    ("view", "height", 8, "8", SIDE, ValueError),
    ("view", "width", 64.5, "64.5", SIDE, TypeError),
    ("view", "width", "640", "six", SIDE, TypeError),
    ("view", "scale", 0.0, "0", SCALE, ValueError),
    ("view", "scale", 11, "11", SCALE, ValueError),
    ("view", "scale", math.nan, "nan", SCALE, ValueError),
    ("view", "trail", -1.0, "-1", TRAIL, ValueError),
    ("view", "view", "cube", "cube", "must be sphere", ValueError),
    ("view", "view", 1, "1", "must be sphere", TypeError),
    ("view", "layers", "body,glitter", "body,glitter", "'glitter' is not one of surface, grid", ValueError),
    ("view", "layers", [1], NA, "must be a comma-separated list of surface", TypeError),
    ("view", "motion", "orbit", "orbit", "must be steady or follow", ValueError),
    ("view", "shown", 8.0, "8", SHOWN, ValueError),
    # run limits
    ("run", "max_steps", -1, "-1", MAX_STEPS, ValueError),
    ("run", "max_steps", 0, "0", MAX_STEPS, ValueError),
    ("run", "max_steps", 2**64, "18446744073709551616", MAX_STEPS, ValueError),
    ("run", "max_steps", 2.5, "2.5", MAX_STEPS, ValueError),
    ("run", "max_steps", "10", "ten", MAX_STEPS, TypeError),
    ("run", "t_end", -1.0, "-1", T_END, ValueError),
    ("run", "t_end", math.inf, "inf", T_END, ValueError),
    ("run", "t_end", None, NA, T_END, TypeError),
    ("run", "t_end", "10", NA, T_END, TypeError),
    ("run", "every", 0.0, "0", EVERY, ValueError),
    ("run", "every", math.nan, "nan", EVERY, ValueError),
    # scene fields: the scene's validation, whichever door the value comes in by
    ("scene", "integrator.dt", -1.0, "-1", "must be > 0", ValueError),
    ("scene", "integrator.dt", math.nan, "nan", "must be a finite number", ValueError),
    ("scene", "integrator.dt", math.inf, "inf", "must be a finite number", ValueError),
    ("scene", "integrator.dt", 1e300, "1e300", "must be at most 1e100 in magnitude", ValueError),
    ("scene", "integrator.tolerance", -1.0, "-1", "must be", ValueError),
    ("scene", "initial.r", -1.0, "-1", "must be", ValueError),
]

# A few values that every door takes, with the same result.
GOOD_VIEWS = [
    {"width": 96, "height": 72},
    {"width": 96, "height": 72, "pitch": 0.3},
    {"width": 96, "height": 72, "yaw": 0.3, "pitch": 0.2, "distance": 4.0, "layers": "surface,body,trail"},
    {"width": 80, "height": 64, "view": "disk", "scale": 0.5, "trail": 0.5},
]


def row_id(row):
    kind, field, value, _, _, error = row
    return f"{kind}-{field}-{value!r}-{error.__name__}"


# ---- the doors ----------------------------------------------------------------------------------

def cli(binary, *args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=120)


def scene_file(field, value_text, tmp_path):
    """A scene file with one field set (the default preset's scene otherwise)."""
    document = json.loads(spinfold._scene_text(SCENE))
    node = document
    parts = field.split(".")
    for part in parts[:-1]:
        node = node.setdefault(part, {})
    node[parts[-1]] = float(value_text)
    path = os.path.join(tmp_path, "scene.json")
    with open(path, "w", encoding="utf-8") as file:
        # NaN and infinities as JSON cannot hold them: the file carries what a person would write
        file.write(json.dumps(document, allow_nan=True))
    return path


def cli_refusal(binary, kind, field, text, tmp_path):
    """The CLI's exit code and stderr for one bad value (None when the CLI has no such input)."""
    if text is NA:
        return None
    out = os.path.join(tmp_path, "x.png")
    if kind == "view":
        result = cli(binary, "render", "--scene", SCENE, "--t", "0.1", "--out", out, f"{cli_flag(field)}={text}")
    elif kind == "run":
        base = {"t_end": "0.1", "every": "0.1"}
        base[field] = text
        result = cli(binary, "simulate", "--scene", SCENE, "--quiet",
                     *(f"{cli_flag(key)}={value}" for key, value in base.items()))
    elif field in ("integrator.dt", "integrator.tolerance"):
        flag = "--" + field.split(".")[1]
        result = cli(binary, "simulate", "--scene", SCENE, "--t-end", "0.1", "--quiet", f"{flag}={text}")
    else:
        if not math.isfinite(float(text)):
            return None
        result = cli(binary, "simulate", scene_file(field, text, tmp_path), "--t-end", "0.1", "--quiet")
    return result


def http_refusal(server, session_id, kind, field, value, text):
    """The API's status, content type and problem for one bad value (None: no such input)."""
    if kind == "view" and text is not NA:
        url = f"{server}/api/v1/sessions/{session_id}/frame.png?" + urllib.parse.urlencode({field: text})
        request = urllib.request.Request(url)
    elif kind == "scene" and isinstance(value, float) and math.isfinite(value):
        document = json.loads(spinfold._scene_text(SCENE))
        node = document
        parts = field.split(".")
        for part in parts[:-1]:
            node = node.setdefault(part, {})
        node[parts[-1]] = value
        request = urllib.request.Request(f"{server}/api/v1/sessions", data=json.dumps(document).encode(),
                                         headers={"Content-Type": "application/json"}, method="POST")
    else:
        return None
    try:
        with urllib.request.urlopen(request, timeout=60) as answer:
            return answer.status, answer.headers.get("Content-Type"), answer.read()
    except urllib.error.HTTPError as error:
        return error.code, error.headers.get("Content-Type"), json.loads(error.read())


def python_call(kind, field, value):
    if kind == "view":
        if field in ("yaw", "pitch", "distance"):
            return lambda: spinfold.render(SCENE, t=0.1, width=64, height=48, **{field: value})
        return lambda: spinfold.render(SCENE, t=0.1, **{field: value})
    if kind == "run":
        arguments = {"t_end": 0.1, "every": 0.1, field: value}
        return lambda: spinfold.simulate(SCENE, **arguments)
    if field.startswith("integrator."):
        return lambda: spinfold.simulate(SCENE, t_end=0.1, **{field.split(".")[1]: value})
    return lambda: spinfold.simulate(SCENE, t_end=0.1, **{field.replace(".", "__"): value})


@pytest.fixture(scope="module")
def session_id(server):
    return spinfold.Client(server).create(SCENE).id


# ---- bad inputs: every door refuses, naming the field, with the same reason ---------------------

@pytest.mark.parametrize("row", BAD, ids=row_id)
def test_every_front_door_refuses_alike(row, binary, server, session_id, tmp_path):
    kind, field, value, text, reason, error = row
    name = field.split(".")[-1] if kind != "scene" else field

    # Python: the error type, the argument named, the reason in the shared words
    with pytest.raises(error) as caught:
        python_call(kind, field, value)()
    message = str(caught.value)
    assert name in message and reason in message, message

    # the CLI: exit 2, the option (or the scene field) named, the same reason
    result = cli_refusal(binary, kind, field, text, str(tmp_path))
    if result is not None:
        assert result.returncode == 2, (result.returncode, result.stderr)
        named = cli_flag(field) if kind != "scene" else field
        assert named in result.stderr and reason in result.stderr, result.stderr
        if text is not NA and kind != "scene":
            assert f"(got '{text}')" in result.stderr, result.stderr

    # HTTP: 422 problem+json, the field named, the same reason
    answer = http_refusal(server, session_id, kind, field, value, text)
    if answer is not None:
        status, content_type, problem = answer
        assert status == 422, (status, problem)
        assert content_type.startswith("application/problem+json"), content_type
        errors = problem.get("errors", [])
        assert any(e.get("field") == field and reason in e.get("reason", "") for e in errors), problem


def test_the_table_reaches_every_door():
    """Each view parameter and each Python run limit is in the table (a new one must be added)."""
    fields = {row[1] for row in BAD}
    assert set(spinfold._core.view_parameter_names()) <= fields
    assert {"max_steps", "t_end", "every"} <= fields


# ---- other refusals Python shares with the CLI ---------------------------------------------------

def test_python_refuses_what_the_cli_refuses_by_the_same_rules(binary):
    with pytest.raises(ValueError, match=r"camera: pitch must be a number from -1\.55 to 1\.55 \[rad\]"):
        spinfold.render(SCENE, t=1, camera=(0.3, 3.0, 0.5))
    assert "--camera: pitch must be a number from -1.55 to 1.55 [rad]" in cli(
        binary, "render", "--scene", SCENE, "--camera", "0.3,3,0.5", "--out", "/tmp/unused.png").stderr
    with pytest.raises(ValueError, match=r"camera: must be \(yaw, pitch, distance\), three numbers"):
        spinfold.render(SCENE, camera=(0, 0))
    with pytest.raises(TypeError, match="camera: must be"):
        spinfold.render(SCENE, camera="abc")
    with pytest.raises(TypeError, match="^t: must be a number >= 0"):
        spinfold.render(SCENE, t="1")
    with pytest.raises(ValueError, match="^t: must be a number >= 0"):
        spinfold.render(SCENE, t=-1)
    with pytest.raises(ValueError, match="^threads: must be a whole number from 1 to 4096"):
        spinfold.run_many([SCENE], t_end=0.1, threads=2**40)
    with pytest.raises(TypeError, match="^scenes: must be an iterable"):
        spinfold.run_many(None)
    # The sweep library's words, as the CLI's --set initial.spin=nan says them.
    with pytest.raises(ValueError, match="initial.spin: not a finite number \\(got 'nan'\\)"):
        spinfold.sweep(SCENE, {"initial.spin": [1.0, math.nan]}, t_end=0.1)
    # The CLI's sweep limit (engine/run_limits.h), refused before anything is allocated.
    with pytest.raises(ValueError, match="more than 10000000 runs"):
        spinfold.sweep(SCENE, {"initial.spin": range(10**4), "body.mass": range(1, 10**4 + 1)})


def test_simulation_patch_names_the_field():
    sim = spinfold.Simulation(SCENE)
    with pytest.raises(ValueError, match="body.mass: must be a finite number"):
        sim.patch({"body": {"mass": math.nan}})
    with pytest.raises(TypeError, match="body.mass"):
        sim.patch({"body": {"mass": object()}})
    # A NumPy value is a number like any other.
    assert sim.patch({"body": {"mass": np.float64(2.0)}})[0] == "continued"
    assert sim.scene["body"]["mass"] == 2.0
    with pytest.raises(ValueError, match="^max_steps: must be a whole number from 1"):
        sim.advance(1.0, max_steps=-1)


# ---- good inputs: the same numbers and pixels through every door ---------------------------------

def png_pixels(data):
    """The RGB of a PNG (the CLI writes RGB, a Frame is RGBA: the comparison is of the colours)."""
    return spinfold.Frame.from_png(data).pixels[:, :, :3]


@pytest.mark.parametrize("given", GOOD_VIEWS, ids=lambda g: ",".join(f"{k}={v}" for k, v in g.items()))
def test_a_render_is_the_same_picture_from_the_cli_and_python(given, binary, tmp_path):
    out = os.path.join(str(tmp_path), "frame.png")
    args = ["render", "--scene", SCENE, "--t", "1", "--out", out]
    for key, value in given.items():
        args += [cli_flag(key), str(value)]
    result = cli(binary, *args)
    assert result.returncode == 0, result.stderr
    with open(out, "rb") as file:
        from_cli = png_pixels(file.read())
    frame = spinfold.render(SCENE, t=1, **given)
    assert np.array_equal(frame.pixels[:, :, :3], from_cli)
    assert np.array_equal(png_pixels(frame.png()), from_cli)


def test_a_run_is_the_same_numbers_from_the_cli_and_python(binary):
    result = cli(binary, "simulate", "--scene", SCENE, "--t-end", "2", "--every", "0.5", "--max-steps", "100000",
                 "--dt", "0.01", "--quiet")
    assert result.returncode == 0, result.stderr
    last = json.loads(result.stdout.splitlines()[-1])
    run = spinfold.simulate(SCENE, t_end=2, every=0.5, max_steps=100000, dt=0.01)
    assert run["t"][-1] == last["t"]
    assert run["r"][-1] == last["r"] and run["phi"][-1] == last["phi"]
    assert list(run["X"][-1]) == last["X"]


def test_a_whole_camera_is_the_aimed_camera_with_all_three_parts_replaced(binary, tmp_path):
    """--camera a,b,c and --yaw a --pitch b --distance c: one rule (render::place_camera) in the CLI,
    Python and the API: the camera aimed at the body, every part given replacing the aimed one."""
    out = os.path.join(str(tmp_path), "whole.png")
    result = cli(binary, "render", "--scene", SCENE, "--t", "1", "--width", "96", "--height", "72",
                 "--camera", "0.3,0.2,4", "--out", out)
    assert result.returncode == 0, result.stderr
    with open(out, "rb") as file:
        from_cli = png_pixels(file.read())
    whole = spinfold.render(SCENE, t=1, width=96, height=72, camera=(0.3, 0.2, 4))
    parts = spinfold.render(SCENE, t=1, width=96, height=72, yaw=0.3, pitch=0.2, distance=4)
    assert np.array_equal(whole.pixels[:, :, :3], from_cli)
    assert np.array_equal(parts.pixels[:, :, :3], from_cli)


# ---- summaries, events and chaos indicators: the engine's words at every door that takes them ----
# (simulate and sweep in the CLI and Python; the HTTP API has none). Each row: the CLI option and
# Python argument, the text, and the reason engine/run_summary.cpp or engine/chaos_indicators.cpp words.
MONITOR_BAD = [
    ("--summary", "summaries", "nope", "summary 'nope': unknown field 'nope' for this scene"),
    ("--summary", "summaries", "r.maxx", "or FIELD.REDUCTION, REDUCTION one of min, max, mean"),
    ("--event", "events", "r:sideways:1", "event 'r:sideways:1': the direction must be up, down or any"),
    ("--event", "events", "r:up:x", "event 'r:up:x': the level: must be a number (got 'x')"),
    ("--event", "events", "r:up:1:stop=0", "stop: must be a whole number from 1 to 9007199254740992 (got '0')"),
    ("--event", "events", "u:up:1", "unknown field 'u' for this scene (one of r, phi,"),
]


@pytest.mark.parametrize("row", MONITOR_BAD, ids=lambda row: f"{row[0]}={row[2]}")
def test_summaries_and_events_refuse_alike_at_every_door(row, binary):
    option, argument, text, reason = row
    for command in (["simulate", "--scene", SCENE, "--t-end", "1", "--quiet"],
                    ["sweep", SCENE, "--set", "initial.r=1", "--t-end", "1", "--quiet"]):
        result = cli(binary, *command, option, text)
        assert result.returncode == 2, (command[0], result.stderr)
        assert f"spinfold: {option}: " in result.stderr and reason in result.stderr, result.stderr
    for call in (lambda: spinfold.simulate(SCENE, t_end=1, **{argument: [text]}),
                 lambda: spinfold.sweep(SCENE, {"initial.r": [1]}, t_end=1, **{argument: [text]}),
                 lambda: spinfold.run_many([SCENE], t_end=1, **{argument: [text]})):
        with pytest.raises(ValueError) as caught:
            call()
        assert f"{argument}: " in str(caught.value) and reason in str(caught.value), str(caught.value)


def test_the_chaos_interval_is_refused_alike(binary):
    reason = "must be a number > 0 [time] (got -1)"
    for command in (["simulate", "--scene", SCENE], ["sweep", SCENE, "--set", "initial.r=1"]):
        result = cli(binary, *command, "--t-end", "1", "--quiet", "--chaos", "--chaos-interval", "-1")
        assert result.returncode == 2 and f"--chaos-interval: {reason}" in result.stderr, result.stderr
    with pytest.raises(ValueError, match=r"chaos_interval: must be a number > 0 \[time\] \(got -1\)"):
        spinfold.sweep(SCENE, {"initial.r": [1]}, t_end=1, chaos=True, chaos_interval=-1)
