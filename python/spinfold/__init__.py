"""Spinfold: affinely-rigid bodies moving on the sphere and the pseudosphere, from Python.

The engine runs in C++ (the module ``spinfold._core``) with the GIL released; results come back as
NumPy arrays. Every number equals what ``spinfold simulate`` prints for the same scene, to the bit.

    >>> import spinfold
    >>> run = spinfold.simulate("spin_vs_geodesic_sphere", t_end=10, every=0.1)
    >>> run["r"][-1], run["X"].shape
    >>> spinfold.render("spin_vs_geodesic_sphere", t=10)   # a Frame; a notebook shows it

A scene is a preset's name, a path to a scene file, JSON text or a dict (README, "Scene format").
Undefined values (φ at a pole, α and β of a round body) are NaN; ``result.undefined(i)`` gives the
reasons of sample i and ``result.reasons`` every reason met in the run.
"""

from __future__ import annotations

import builtins
import difflib
import json
import math
import numbers
import os
from typing import Any, Iterable, Iterator, Mapping, Sequence

import numpy as np

from . import _core
from .client import Client, ServerError, Session

__all__ = [
    "__version__",
    "presets",
    "integrators",
    "field_names",
    "simulate",
    "run_many",
    "sweep",
    "sweep_fields",
    "grid",
    "Result",
    "Simulation",
    "render",
    "Frame",
    "Client",
    "Session",
    "ServerError",
]

__version__ = f"{_core.version()}+{_core.commit()}" if _core.commit() != "unknown" else _core.version()
"""The version (it follows CHANGELOG.md) and the commit the module was built from."""

_VALUE_NAMES: list[str] = _core.value_names()
_PRESETS: dict[str, tuple[str, str]] = {name: (description, text) for name, description, text in _core.presets()}
_GROUPS = {"X": (3,), "L": (2, 2), "M": (3,)}
_EVENT_DTYPE = np.dtype([("t", "f8"), ("sample", "i8"), ("kind", "U16")])


def presets() -> dict[str, str]:
    """The embedded preset scenes: name -> description (``spinfold scenes``)."""
    return {name: description for name, (description, _) in _PRESETS.items()}


def integrators() -> list[dict[str, Any]]:
    """The integrator catalog: name, order, symplectic, adaptive, exact, summary."""
    return _core.integrators()


def field_names() -> list[str]:
    """The numeric fields of a sample, flattened (``X.0``, ``L.1.0``, ``actions.J_r``)."""
    return list(_VALUE_NAMES)


def _non_finite_path(value: Any, path: str) -> tuple[str, float] | None:
    """The dotted path and value of the first NaN or infinity in a scene given as Python values."""
    if isinstance(value, float) and not math.isfinite(value):
        return path, value
    items = value.items() if isinstance(value, Mapping) else \
        ((f"[{i}]", v) for i, v in enumerate(value)) if isinstance(value, (list, tuple)) else ()
    for key, item in items:
        found = _non_finite_path(item, f"{path}{key}" if str(key).startswith("[") else f"{path}.{key}")
        if found:
            return found
    return None


def _scene_text(scene: Any, field: str = "scene") -> str:
    """JSON text of a scene given as a mapping, JSON text, or a name: a scene file if a file has
    that name, else a preset's name (the one rule of every CLI command, codec/scene_source.h)."""
    if isinstance(scene, Mapping):
        bad = _non_finite_path(scene, field)
        if bad:
            # JSON has no NaN or infinity: refused as the scene's rule refuses a number out of range.
            raise ValueError(f"{bad[0]}: must be a finite number (got {bad[1]!r})")
        try:
            return json.dumps(scene, allow_nan=False)
        except (TypeError, ValueError) as error:
            raise TypeError(f"{field}: not a JSON document ({error})") from None
    if isinstance(scene, os.PathLike):
        scene = os.fspath(scene)
    if not isinstance(scene, str):
        raise TypeError(f"{field}: must be a preset name, a path, JSON text or a dict (got {type(scene).__name__})")
    if scene.lstrip().startswith("{"):
        return scene
    return _core.scene_text(scene, field)


def _with_overrides(text: str, overrides: Mapping[str, Any], options: Sequence[str] = ()) -> str:
    """Applies `integrator=`, `dt=`, `tolerance=` (as the CLI's flags) and dotted paths, checked by the
    scene's validation (ValueError naming each refused field, NaN and infinities included). A keyword
    that is none of those but close to one of the function's `options` is a misspelt option, not a
    scene field: TypeError naming it and the option meant (``summary=`` for ``summaries=``)."""
    if not overrides:
        return text
    pairs = []
    for key, value in overrides.items():
        if key in ("chaos", "chaos_interval"):
            raise TypeError(f"{key}: not an option here (a run's option: spinfold.simulate, run_many and sweep "
                            f"have it), not a scene field")
        if "__" not in key and key not in ("integrator", "dt", "tolerance"):
            meant = difflib.get_close_matches(key, list(options), n=1, cutoff=0.75)
            if meant:
                raise TypeError(f"{key}: not an option (did you mean {meant[0]}=?); a scene field is "
                                f"written with __ for its dots, such as initial__spin")
        path = {"integrator": "integrator.name", "dt": "integrator.dt", "tolerance": "integrator.tolerance"}.get(
            key, key.replace("__", ".")
        )
        pairs.append((path, value))
    return _core.apply_overrides(text, pairs)


# ---- arguments: Python's syntax here, the rules in C++ ------------------------------------------
# Each number is checked by the rule every front door shares (the view-parameter table,
# render/view_parameters.h, and the run limits, engine/run_limits.h), refused in its words:
# ``pitch: must be a number from -1.55 to 1.55 [rad] (got 3.0)`` as the CLI's ``--pitch: … (got '3')``.
# A value of the wrong type (a string for a number, None) is a TypeError naming the argument; it is
# never converted.


def _real(value: Any) -> float | None:
    """A number as a float (an int beyond a float's range as ±inf), or None for a non-number."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        return None
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf


def _run_limit(name: str, value: Any) -> float:
    """A run limit (t_end, every, t, max_steps, threads) checked by its row (engine/run_limits.h)."""
    x = _real(value)
    if x is None:
        raise TypeError(f"{name}: {_core.run_limit_expectation(name)} (got {value!r} of type {type(value).__name__})")
    why = _core.run_limit_refusal(name, x)
    if why:
        raise ValueError(f"{name}: {why} (got {value!r})")
    return x


def _view_number(name: str, value: Any, label: str | None = None) -> float:
    """A number of the view-parameter table checked by its row; `label` names the argument it came
    in (camera) when that is not `name`."""
    x = _real(value)
    prefix = f"{label}: {name}" if label else f"{name}:"
    if x is None or (name in ("width", "height") and not isinstance(value, (int, np.integer))):
        raise TypeError(f"{prefix} {_core.view_expectation(name)} (got {value!r})")
    why = _core.view_refusal(name, x)
    if why:
        raise ValueError(f"{prefix} {why} (got {value!r})")
    return x


def _view_text(name: str, value: Any) -> str:
    """A text of the view-parameter table (view, layers) checked by its row."""
    if not isinstance(value, str):
        raise TypeError(f"{name}: {_core.view_expectation(name)} (got {value!r})")
    why = _core.view_refusal(name, value)
    if why:
        raise ValueError(f"{name}: {why} (got {value!r})")
    return value


class Result(Mapping[str, np.ndarray]):
    """One run's samples: a mapping of NumPy arrays, one per field, one row per sample.

    Keys: the scalar fields (``t``, ``r``, ``phi``, …, ``actions.J_r``, ``frequencies.r``), ``X``
    and ``M`` as (n, 3), ``L`` as (n, 2, 2), ``steps``, ``status`` (a string per sample) and
    ``events`` (a structured array of ``t``, ``sample``, ``kind``). Undefined values are NaN.
    """

    def __init__(self, raw: dict[str, Any]):
        values = raw["values"]
        columns: dict[str, np.ndarray] = {}
        for i, name in enumerate(_VALUE_NAMES):
            group = name.split(".", 1)[0]
            if group not in _GROUPS:
                columns[name] = values[:, i]
        for group, shape in _GROUPS.items():
            index = [i for i, n in enumerate(_VALUE_NAMES) if n.split(".", 1)[0] == group]
            columns[group] = values[:, index].reshape((values.shape[0],) + shape)
        columns["steps"] = raw["steps"]
        columns["status"] = np.array(raw["status_names"] or ["ok"], dtype="U32")[raw["status_codes"]]
        events = np.empty(len(raw["event_t"]), dtype=_EVENT_DTYPE)
        events["t"] = raw["event_t"]
        events["sample"] = raw["event_row"]
        events["kind"] = "det_L_zero"
        columns["events"] = events
        self._columns = columns
        self._values = values
        self._undefined_sets: list[dict[str, str]] = raw["undefined_sets"]
        self._undefined_row: np.ndarray = raw["undefined_row"]
        self.label: str = raw.get("label", "")
        """A companion's label ("" for the main body)."""
        self.summary: dict[str, float] = {k: (math.nan if v is None else float(v))
                                          for k, v in raw.get("summary", {}).items()}
        """The run's summaries and events (``simulate(..., summaries=…, events=…)``), by column name."""
        self.integrator: str = raw["integrator"]
        """The integrator that ran (``auto`` resolved)."""
        self.status_detail: str = raw["status_detail"]
        """The final status in one sentence."""
        self.companions: list[Result] = [Result(c) for c in raw.get("companions", [])]
        """One Result per companion body, in scene order."""
        self.crossings: dict[str, Result] = {c["label"]: Result(c) for c in raw.get("crossings", [])}
        """Each recording event's crossings (``events="phi:up:0:record"``) by its name: one row per
        occurrence, the main body's sample there (a Poincaré section)."""
        self.provenance: dict[str, Any] = json.loads(raw["provenance"]) if "provenance" in raw else {}
        """Version, commit, scene hash, integrator and command (README, "Tables and provenance")."""
        self.complete: bool = raw.get("budget_left", True)
        """False when ``max_steps`` ran out before ``t_end``."""

    def __getitem__(self, key: str) -> np.ndarray:
        try:
            return self._columns[key]
        except KeyError:
            raise KeyError(f"{key!r} is not a field (fields: {', '.join(self._columns)})") from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._columns)

    def __len__(self) -> int:
        return len(self._columns)

    @property
    def status(self) -> str:
        """The run's final status: ``ok``, or why it stopped (README, "One sample")."""
        return str(self._columns["status"][-1]) if len(self._columns["status"]) else "ok"

    @property
    def samples(self) -> int:
        """The number of samples (rows)."""
        return self._values.shape[0]

    def undefined(self, i: int) -> dict[str, str]:
        """The reasons of the values that are NaN in sample `i`: field -> reason."""
        return dict(self._undefined_sets[int(self._undefined_row[i])])

    @property
    def reasons(self) -> dict[str, str]:
        """Every undefined field met in the run with its (first) reason."""
        out: dict[str, str] = {}
        for reasons in self._undefined_sets:
            for field, reason in reasons.items():
                out.setdefault(field, reason)
        return out

    def table(self) -> np.ndarray:
        """The numeric fields as one (n, len(field_names())) array, in field_names() order."""
        return self._values

    def __repr__(self) -> str:
        return (
            f"<spinfold.Result {self.samples} samples, t = {self['t'][0] if self.samples else 0:g}.."
            f"{self['t'][-1] if self.samples else 0:g}, {self.integrator}, status {self.status}>"
        )


def _texts(value: Any, name: str) -> list[str]:
    """A text or a sequence of texts, as a list; TypeError naming the argument otherwise."""
    if isinstance(value, str):
        return [value]
    if not isinstance(value, Sequence) or not all(isinstance(x, str) for x in value):
        raise TypeError(f"{name}: must be a text or a sequence of texts (got {value!r})")
    return list(value)


def _monitor_texts(summaries: str | Sequence[str], events: str | Sequence[str]) -> tuple[list[str], list[str]]:
    """The CLI's --summary (comma-separated) and --event texts as lists."""
    summaries = summaries.split(",") if isinstance(summaries, str) else _texts(summaries, "summaries")
    return [x for x in summaries if x], _texts(events, "events")


_SIMULATE_OPTIONS = ("t_end", "every", "max_steps", "summaries", "events", "chaos", "chaos_interval")


def _chaos_interval(chaos: Any, chaos_interval: Any) -> float | None:
    """`chaos` (True or False) and its interval as the core takes them: the interval, or None."""
    if not _flag("chaos", chaos):
        return None
    interval = _real(chaos_interval)
    if interval is None:
        raise TypeError(f"chaos_interval: must be a number (got {chaos_interval!r})")
    return interval


def _flag(name: str, value: Any) -> bool:
    """A yes-or-no option: True or False (a NumPy bool too), never a text or a number taken for one."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name}: must be True or False (got {value!r})")
    return bool(value)


def simulate(scene: Any, t_end: float = 10.0, every: float = 0.5, *, max_steps: int | None = None,
             summaries: str | Sequence[str] = (), events: str | Sequence[str] = (), chaos: bool = False,
             chaos_interval: float = 1.0, **overrides: Any) -> Result:
    """Runs a scene and samples it at t = 0, every, 2·every, … and t_end.

    `scene`: a preset name, a path, JSON text or a dict. Keyword overrides: ``integrator``, ``dt``,
    ``tolerance`` (as the CLI's flags) or any scene field with ``__`` for its dots
    (``initial__spin=1.5``). The numbers are those of ``spinfold simulate`` to the bit.
    `max_steps` bounds the step attempts (``result.complete`` is False when they ran out).
    `summaries` and `events`: the CLI's ``--summary`` and ``--event``; their values are
    ``result.summary`` (``{"r.max": …, "r_up_1.2.count": …}``, NaN where there is none).
    `chaos`: the CLI's ``--chaos``, the maximal Lyapunov exponent and MEGNO in ``result.summary``
    (``chaos.lyapunov``, ``chaos.megno``, ``chaos.megno_mean``, ``chaos.lyapunov_time``, ``chaos.t``),
    a shadow run restarted every `chaos_interval` (docs/numerics.md, "Chaos and predictability").
    """
    t_end, every = _run_limit("t_end", t_end), _run_limit("every", every)
    steps = None if max_steps is None else _run_limit("max_steps", max_steps)
    interval = _chaos_interval(chaos, chaos_interval)
    text = _with_overrides(_scene_text(scene), overrides, _SIMULATE_OPTIONS)
    watched, crossings = _monitor_texts(summaries, events)
    return Result(_core.simulate(text, t_end, every, steps, "python: spinfold.simulate", watched, crossings,
                                 interval))


def run_many(scenes: Iterable[Any], t_end: float = 10.0, every: float = 0.5, *,
             threads: int | None = None, summaries: str | Sequence[str] = (),
             events: str | Sequence[str] = (), chaos: bool = False, chaos_interval: float = 1.0) -> list[Result]:
    """Runs many scenes on C++ threads (`threads`; None: one per core) with the GIL released.

    Each run is what ``simulate`` gives for that scene (its `summaries`, `events` and `chaos`
    indicators in ``result.summary``). A refused scene raises ValueError naming its index before
    anything runs.
    """
    if isinstance(scenes, (str, bytes, Mapping)) or not isinstance(scenes, Iterable):
        raise TypeError(f"scenes: must be an iterable of scenes (got {type(scenes).__name__})")
    t_end, every = _run_limit("t_end", t_end), _run_limit("every", every)
    count = None if threads is None else _run_limit("threads", threads)
    texts = [_scene_text(s, f"scenes[{i}]") for i, s in enumerate(scenes)]
    watched, crossings = _monitor_texts(summaries, events)
    interval = _chaos_interval(chaos, chaos_interval)
    raw = _core.run_many(texts, t_end, every, count, "python: spinfold.run_many", watched, crossings, interval)
    return [Result(r) for r in raw]


def grid(a: float, b: float, n: int) -> np.ndarray:
    """The values of a sweep's ``a:b:n`` (``spinfold sweep --set FIELD=a:b:n``): n values from a to
    b, ``np.linspace(a, b, n)`` to the bit (NumPy's formula, k·((b − a)/(n − 1)) + a, the last b)."""
    return np.array(_core.grid(float(a), float(b), int(n)))


def sweep_fields() -> list[str]:
    """The names `fields` of :func:`sweep` accepts (``spinfold sweep --list-fields``)."""
    return list(_core.sweep_fields())


def sweep(base: Any, vary: Mapping[str, Any], t_end: float = 10.0, every: float = 0.5, *,
          fields: str | Sequence[str] | None = None, zip: bool = False, max_steps: int | None = None,
          threads: int | None = None, summaries: str | Sequence[str] = (),
          events: str | Sequence[str] = (), chaos: bool = False,
          chaos_interval: float = 1.0) -> dict[str, np.ndarray]:
    """``spinfold sweep`` from Python, through the same library: the same definition gives the
    CLI's rows to the bit. `base` with the fields of `vary` (a scene path such as ``"initial.spin"``
    -> its values: a text as ``--set`` takes it, ``"0:2:40"`` (:func:`grid`) or ``"auto,dop853"``,
    or a sequence of values) set to each combination (the Cartesian product, the last field varying
    fastest, or paired with `zip`), run on C++ threads with the GIL released. `fields`: the CLI's
    ``--fields`` (None: its default; :func:`sweep_fields`). Returns the CLI's columns, one row per
    run in order: ``index``, the varied fields, `fields`, ``events``, ``status``, ``detail``,
    ``steps``, ``seconds`` (numbers as float arrays, NaN where undefined; counts as integers).
    `summaries` and `events`: the CLI's ``--summary`` and ``--event`` (``"r"``, ``"r.max"``;
    ``"r:up:1.2"``, ``"phi:any:0:period=6.283185307179586"``, ``"r:up:1.2:stop=3"``): reductions
    over each run's own steps and level crossings located in them, one column each
    (``r.max``, ``r_up_1.2.count``, ``r_up_1.2.t_first``; docs/numerics.md). `chaos`: the CLI's
    ``--chaos``, the maximal Lyapunov exponent and MEGNO of each run (``chaos.lyapunov``,
    ``chaos.megno``, ``chaos.megno_mean``, ``chaos.lyapunov_time``, ``chaos.t``), a shadow run
    restarted every `chaos_interval`.
    Bad input (an unknown field, a value out of range, more than 10⁷ runs) raises ValueError naming
    it before anything runs.
    """
    if not isinstance(vary, Mapping):
        raise TypeError(f"vary: must be a mapping of field paths to values (got {type(vary).__name__})")
    zip, chaos = _flag("zip", zip), _flag("chaos", chaos)
    if fields is None:
        fields = _core.default_sweep_fields()
    elif not isinstance(fields, str):
        fields = ",".join(fields)
    if threads is not None:
        _run_limit("threads", threads)
    if max_steps is not None:
        _run_limit("max_steps", max_steps)
    _run_limit("t_end", t_end)
    _run_limit("every", every)
    axes = []
    for path, values in vary.items():
        if isinstance(values, str):
            axes.append((str(path), values, None))
            continue
        if isinstance(values, np.ndarray):
            values = values.tolist()
        if not isinstance(values, (list, tuple, range)):
            raise TypeError(f"vary['{path}']: must be a text such as '0:2:40' or 'auto,dop853', or a sequence "
                            f"of values (got {values!r})")
        values = [v.item() if isinstance(v, np.generic) else v for v in values]
        if any(isinstance(v, float) and not math.isfinite(v) for v in values):
            # JSON has no NaN or inf: the values as --set writes them, refused by the library's rule.
            axes.append((str(path), ",".join(repr(v) for v in values), None))
            continue
        try:
            text = json.dumps([v.item() if isinstance(v, np.generic) else v for v in values], allow_nan=False)
        except (TypeError, ValueError) as error:
            raise ValueError(f"vary['{path}']: not a list of numbers or names ({error})") from None
        axes.append((str(path), None, text))
    summaries, events = _monitor_texts(summaries, events)
    checked = _chaos_interval(chaos, chaos_interval)  # None without chaos: the core ignores the interval then
    interval = 1.0 if checked is None else checked
    names, rows = _core.sweep(_scene_text(base, "base"), axes, bool(zip), float(t_end), float(every), fields,
                              summaries, events, bool(chaos), interval, max_steps, threads or 0,
                              "python: spinfold.sweep")
    out: dict[str, np.ndarray] = {}
    for j, name in enumerate(names):
        column = [row[j] for row in rows]
        if all(isinstance(v, int) for v in column) and column:
            out[name] = np.array(column, dtype=np.uint64 if all(v >= 0 for v in column) else np.int64)
        elif all(v is None or isinstance(v, (int, float)) for v in column):
            out[name] = np.array([np.nan if v is None else float(v) for v in column], dtype=np.float64)
        else:
            out[name] = np.array(["" if v is None else str(v) for v in column], dtype=str)
    return out


class Simulation:
    """A run steered step by step, as a server session: advance, read, patch, reset, trajectory."""

    def __init__(self, scene: Any = None, **overrides: Any):
        """`scene`: a preset name, a path, JSON text or a dict (None: the default preset)."""
        text = _scene_text(_core.default_preset() if scene is None else scene)
        self._run = _core.Simulation(_with_overrides(text, overrides))

    @property
    def t(self) -> float:
        """The run's time."""
        return self._run.t

    def advance(self, until: float, *, max_steps: int | None = None) -> bool:
        """Advances to `until` (False when `max_steps` attempts ran out first; call again to go on)."""
        if _real(until) is None:
            raise TypeError(f"until: must be a number (got {until!r})")
        steps = None if max_steps is None else _run_limit("max_steps", max_steps)
        return self._run.advance(float(until), steps)

    @property
    def state(self) -> dict[str, Any]:
        """The current sample as a dict (the JSON sample; null values are None)."""
        return json.loads(self._run.state())

    def sample(self) -> dict[str, Any]:
        """The current sample with the det L = 0 events since the previous sample() call."""
        return json.loads(self._run.sample())

    @property
    def scene(self) -> dict[str, Any]:
        """The parameters in force now."""
        return json.loads(self._run.scene())

    def patch(self, changes: Mapping[str, Any]) -> tuple[str, str]:
        """Applies a JSON merge patch of the scene: the run continues under the new parameters
        (``("continued", reason)``) or, where the server's session would, starts over at t = 0
        (``("restarted", reason)``). A refused patch raises ValueError and changes nothing."""
        if not isinstance(changes, Mapping):
            raise TypeError(f"changes: must be a mapping (got {type(changes).__name__})")
        kind, reason = self._run.patch(dict(changes))  # NaN, NumPy values: checked in C++, naming the field
        return kind, reason

    def reset(self) -> None:
        """Back to t = 0 with the parameters in force."""
        self._run.reset()

    def trajectory(self, every: float = 0.5) -> Result:
        """The samples at 0, every, … up to now, replayed from the changes: the same however the
        run was advanced."""
        return Result(self._run.trajectory(_run_limit("every", every)))

    def __repr__(self) -> str:
        return f"<spinfold.Simulation t = {self.t:g}>"


class Frame:
    """A rendered picture: ``pixels`` is an (H, W, 4) uint8 RGBA array, rows top-down."""

    def __init__(self, pixels: np.ndarray, texts: Sequence[tuple[str, str]] = (), status: str = "ok"):
        self.pixels = pixels
        self.texts = list(texts)
        """The PNG text chunks written by save() and _repr_png_ (the provenance)."""
        self.status = status
        """The run's status at the frame's time."""

    @property
    def width(self) -> int:
        return int(self.pixels.shape[1])

    @property
    def height(self) -> int:
        return int(self.pixels.shape[0])

    def png(self) -> bytes:
        """The frame as PNG bytes (the encoder of ``spinfold render``, with the provenance)."""
        rgba = np.ascontiguousarray(self.pixels, dtype=np.uint8)
        return _core.encode_png(rgba.tobytes(), self.width, self.height, self.texts)

    def save(self, path: str | os.PathLike) -> None:
        """Writes the frame as a PNG file."""
        with open(path, "wb") as file:
            file.write(self.png())

    def _repr_png_(self) -> bytes:
        return self.png()

    @classmethod
    def from_png(cls, data: bytes) -> "Frame":
        """A frame from PNG bytes of 8-bit RGB or RGBA (what the server and ``spinfold render``
        write), with its text chunks."""
        return _decode_png(data)

    def __repr__(self) -> str:
        return f"<spinfold.Frame {self.width}x{self.height}>"


def _decode_png(data: bytes) -> Frame:
    import struct
    import zlib

    if not isinstance(data, (bytes, bytearray)) or data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("png: not PNG data")
    pos, idat, texts = 8, b"", []
    width = height = channels = 0
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            if depth != 8 or colour not in (2, 6) or body[12] != 0:
                raise ValueError("png: only 8-bit RGB or RGBA without interlacing")
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        elif kind == b"tEXt":
            key, _, text = body.partition(b"\0")
            texts.append((key.decode("latin-1"), text.decode("latin-1")))
        elif kind == b"iTXt":  # UTF-8 text (a non-ASCII provenance): flag, method, language, keyword
            key, _, rest = body.partition(b"\0")
            compressed, rest = rest[0], rest[2:]
            _, _, rest = rest.partition(b"\0")
            _, _, text = rest.partition(b"\0")
            texts.append((key.decode("latin-1"), (zlib.decompress(text) if compressed else text).decode("utf-8")))
        elif kind == b"IEND":
            break
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(height, 1 + width * channels)
    rows = raw[:, 1:].astype(np.int32)
    bpp = channels
    for y in range(height):  # undo the row filters (PNG spec §9); spinfold's own PNGs use none
        f = raw[y, 0]
        if f == 0:
            continue
        line, prior = rows[y], rows[y - 1] if y else np.zeros_like(rows[y])
        for x in range(line.size):
            a = line[x - bpp] if x >= bpp else 0
            b = prior[x]
            c = prior[x - bpp] if x >= bpp else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            else:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    pixels = rows.astype(np.uint8).reshape(height, width, channels)
    if channels == 3:
        pixels = np.concatenate([pixels, np.full((height, width, 1), 255, np.uint8)], axis=2)
    return Frame(pixels, texts)


def render(scene: Any, t: float = 0.0, *, view: str | None = None, width: int = 640, height: int = 480,
           layers: str | Sequence[str] | None = None,
           camera: tuple[float, float, float] | None = None, scale: float = 0.25,
           trail: float | None = None, yaw: float | None = None, pitch: float | None = None,
           distance: float | None = None, motion: str | None = None,
           shown: float | None = None) -> Frame:
    """The picture ``spinfold render`` draws of the scene at time `t` (the same pixels).

    `view`: sphere, hyperboloid, disk, plane, klein, halfplane, tractricoid, conformal, …
    (None: the surface's own); `layers`: a comma-separated string or a list (None: the layers on
    by default, as everywhere: the view-parameter table's); `camera`: (yaw, pitch, distance) for the
    3-D views, or `yaw`, `pitch`, `distance` one by one (None: aimed at the body; a part given
    replaces that part of the aimed camera, as the CLI's ``--camera`` and ``--yaw``); `motion`:
    how a sequence's camera moves (steady, follow), read as every door reads it; one frame is aimed
    either way; `shown`: the width the picture will be shown at, which sizes its text overlay
    (None: as drawn).

    Each value is checked by the view-parameter table (render/view_parameters.h) and refused in the
    CLI's and the API's words: ValueError naming the parameter (``pitch: must be a number from
    -1.55 to 1.55 [rad] (got 3.0)``); TypeError for a value of the wrong type (never converted).
    """
    t = _run_limit("t", t)
    given: list[tuple[str, Any]] = [("width", _view_number("width", width)),
                                    ("height", _view_number("height", height))]
    if view is not None:
        given.append(("view", _view_text("view", view)))
    if layers is not None:
        if not isinstance(layers, str):
            if isinstance(layers, (bytes, Mapping)) or not isinstance(layers, Iterable):
                raise TypeError(f"layers: {_core.view_expectation('layers')} (got {layers!r})")
            items = list(layers)
            if not all(isinstance(item, str) for item in items):
                raise TypeError(f"layers: {_core.view_expectation('layers')} (got {layers!r})")
            layers = ",".join(items)
        given.append(("layers", _view_text("layers", layers)))
    given.append(("scale", _view_number("scale", scale)))
    if camera is not None:
        shape = "must be (yaw, pitch, distance), three numbers"
        if isinstance(camera, (str, bytes, Mapping)) or not isinstance(camera, Iterable):
            raise TypeError(f"camera: {shape} (got {camera!r})")
        parts = list(camera)
        if len(parts) != 3:
            raise ValueError(f"camera: {shape} (got {camera!r})")
        for name, value in builtins.zip(("yaw", "pitch", "distance"), parts):
            given.append((name, _view_number(name, value, "camera")))
    for name, value in (("yaw", yaw), ("pitch", pitch), ("distance", distance), ("trail", trail),
                        ("shown", shown)):
        if value is not None:
            given.append((name, _view_number(name, value)))
    if motion is not None:
        given.append(("motion", _view_text("motion", motion)))
    raw = _core.render(_scene_text(scene), t, given, "python: spinfold.render")
    pixels = np.frombuffer(raw["rgba"], dtype=np.uint8).reshape(raw["height"], raw["width"], 4).copy()
    return Frame(pixels, [tuple(t) for t in raw["texts"]], raw["status"])
