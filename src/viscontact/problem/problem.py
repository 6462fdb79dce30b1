"""Validated physical description of one simulation, free of file formats.

These frozen dataclasses are what the numerical core consumes. ``viscontact.io.case`` turns a TOML
case file into them; a script may build them directly. All quantities are SI (m, s, N, Pa).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, Callable, Literal

import numpy as np

from viscontact.errors import ParameterError
from viscontact.numerics.grid import Grid, shifted_periodic_x
from viscontact.physics.materials import Material
from viscontact.problem.adhesion import AdhesionSettings
from viscontact.problem.shapes import Shape, Sphere

if TYPE_CHECKING:
    from viscontact.bodies.base import Body

NormalControl = Literal["load", "displacement"]
TangentialMode = Literal["none", "frictionless_sliding", "gross_sliding", "partial_slip", "rolling"]
#: every tangential mode (:class:`TangentialLoading`)
TANGENTIAL_MODES = ("none", "frictionless_sliding", "gross_sliding", "partial_slip", "rolling")
SlipCondition = Literal["total", "incremental"]
TimeScheme = Literal["constant", "linear"]

#: phase codes written to ``phase(t)``
PHASE_INDENTATION, PHASE_PARTIAL_SLIP, PHASE_GROSS_SLIDING, PHASE_ROLLING = 0, 1, 2, 3
#: what each phase code means (labels of figures and of the ``phase`` variable)
PHASE_NAMES = {PHASE_INDENTATION: "indentation", PHASE_PARTIAL_SLIP: "partial slip",
               PHASE_GROSS_SLIDING: "gross sliding", PHASE_ROLLING: "rolling"}


def is_number(value: object) -> bool:
    """A real number (Python or numpy), not a boolean."""
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))


def is_integer(value: object) -> bool:
    """An integer (Python or numpy), not a boolean."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


def _check_number(key: str, value: object, unit: str, *, low: float = 0.0, strict: bool = True) -> None:
    """Raise :class:`ParameterError` naming ``key`` unless ``value`` is a finite number > ``low``
    (``strict``) or >= ``low``."""
    ok = is_number(value) and bool(np.isfinite(value)) and (value > low if strict else value >= low)
    if not ok:
        raise ParameterError(key, f"must be a finite number {'>' if strict else '>='} {low:g}{unit}, got {value!r}")


def _check_integer(key: str, value: object, low: int = 1) -> None:
    """Raise :class:`ParameterError` naming ``key`` unless ``value`` is an integer >= ``low``."""
    if not is_integer(value) or value < low:
        raise ParameterError(key, f"must be an integer >= {low}, got {value!r}")


@dataclass(frozen=True)
class PiecewiseLinear:
    """A piecewise-linear history f(t) through the points (times[i], values[i]).

    Held constant before the first and after the last point.
    """

    times: tuple[float, ...]
    values: tuple[float, ...]

    @classmethod
    def constant(cls, value: float) -> "PiecewiseLinear":
        return cls((0.0,), (float(value),))

    def __call__(self, t: float) -> float:
        return float(np.interp(t, self.times, self.values))

    def sample(self, t: np.ndarray) -> np.ndarray:
        """f at each of the times ``t`` [s] at once (float64, what calling it at each gives)."""
        return np.interp(np.asarray(t, dtype=float), self.times, self.values).astype(float)

    @property
    def reference(self) -> float:
        """The largest value of the history (used to normalise: Hertz a0, p0)."""
        return float(max(self.values))

    def turning_points(self) -> tuple[tuple[float, float, float, int], ...]:
        """The history's reversals, in time order: (first time [s], last time [s] of the extreme held
        there — the same time unless a plateau holds it —, the extreme, +1 for a peak or -1 for a
        trough). A change of slope without a change of direction is none."""
        return tuple(zip(*(a.tolist() for a in self.turning_arrays())))

    def turning_arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """:meth:`turning_points` as four arrays (first times, last times, extremes, directions),
        computed at once (a history of 20,000 points took seconds point by point)."""
        values = np.asarray(self.values)
        times = np.asarray(self.times, dtype=float)
        starts = np.flatnonzero(np.r_[True, np.diff(values) != 0])  # plateaus of equal values: [start, end]
        ends = np.r_[starts[1:] - 1, values.size - 1]
        g = np.arange(1, max(starts.size - 1, 1))
        i, j = starts[g], ends[g]
        before, after = np.sign(values[i] - values[i - 1]), np.sign(values[starts[g + 1]] - values[j])
        keep = before != after
        return (times[i[keep]], times[j[keep]], values[i[keep]].astype(float), before[keep].astype(int))

    def turning_reach(self, dt: float, last: int) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`turning_steps` as two arrays (the steps, the values the steps reach there), computed
        at once."""
        first, held_until, _, direction = self.turning_arrays()
        steps = np.ceil(first / dt - 1e-9)  # the first step on or after each turning point
        beyond = np.flatnonzero(steps > last)
        k = steps[:beyond[0] if beyond.size else steps.size].astype(np.int64)
        held_until, direction = held_until[:k.size], direction[:k.size]
        at_k, before_k = np.interp(k * dt, self.times, self.values), np.interp((k - 1) * dt, self.times, self.values)
        on = k * dt <= held_until + 1e-9 * dt  # a step on the turning point or its plateau
        later = on | (direction * at_k >= direction * before_k)  # else the more extreme of the steps around it
        return np.where(later, k, k - 1), np.where(later, at_k, before_k)

    def turning_steps(self, dt: float, last: int) -> tuple[tuple[int, float], ...]:
        """For each turning point that steps t = k ``dt`` (k <= ``last``) reach: (the step nearest to it,
        the value the steps reach there): the first step on its plateau where one falls there, else the
        more extreme of the steps just before and after it."""
        return tuple(zip(*(a.tolist() for a in self.turning_reach(dt, last))))


def check_history(history: PiecewiseLinear, key: str) -> None:
    """Raise :class:`ParameterError` naming the case key ``key`` unless ``history`` has as many
    times as values (one at least), all finite numbers, its times >= 0 s and strictly increasing;
    the values are the caller's to check (a normal load, a tangential displacement)."""
    times, values = history.times, history.values
    if len(times) != len(values) or len(times) == 0:  # len: numpy arrays of times are sequences too
        raise ParameterError(key, f"must be a non-empty list of [t, value] pairs, got {len(times)} times and "
                             f"{len(values)} values")
    if not all(is_number(v) and np.isfinite(v) for v in (*times, *values)):
        raise ParameterError(key, "must contain finite numbers only")
    if times[0] < 0 or np.any(np.diff(times) <= 0):
        raise ParameterError(key, "times must be >= 0 s and strictly increasing")


@dataclass(frozen=True)
class NormalLoading:
    """Normal boundary condition (seed Eqs. 7-8): load W(t) [N] or approach delta_z(t) [m].

    ``tensile``: the history may go below zero (a pull, a retraction past the first touch), which
    only an adhesive surface allows (:class:`Problem` refuses it without ``adhesion``)."""

    control: NormalControl
    history: PiecewiseLinear
    tensile: bool = field(default=False, repr=False)

    def __post_init__(self) -> None:
        """The one place that checks a normal loading (the case layer delegates here).

        Raises
        ------
        ParameterError
            ``normal.control`` not ``"load"`` or ``"displacement"``; ``normal.history`` (a held
            value too: a history of one point) not finite, negative or nowhere > 0, its times not
            >= 0 s and strictly increasing, or times and values of different lengths.
        """
        if self.control not in ("load", "displacement"):
            raise ParameterError("normal.control", f"must be 'load' or 'displacement', got {self.control!r}")
        check_history(self.history, "normal.history")  # a held value is a history of one point
        values = self.history.values
        if (min(values) < 0 and not self.tensile) or not max(values) > 0:
            hint = " (a tensile load or a retraction below zero needs [adhesion])" if min(values) < 0 else ""
            raise ParameterError("normal.history",
                                 f"values must be >= 0 (N or m) with a positive maximum, got {values!r}{hint}")


@dataclass(frozen=True)
class TangentialLoading:
    """Tangential motion of the indenter.

    Attributes
    ----------
    mode
        ``none`` (pure indentation), ``frictionless_sliding`` (seed case 1),
        ``gross_sliding`` (q_x = mu_f p from t = 0, seed case 2) or ``partial_slip``
        (delta_x ramped at ``displacement_rate`` until the stick zone of a contact vanishes, then
        sliding; the stuck points move with delta_x since the contact began; or delta_x following
        ``displacement_history``, which may reverse: fretting, stopped if the stick zone vanishes)
        or ``rolling`` (the indenter rolls in +x at ``rolling_speed`` with a held ``creepage`` or a
        held ``tangential_force``: :mod:`viscontact.solvers.rolling`).
    friction_coefficient
        Coulomb coefficient mu_f [-].
    displacement_rate
        d(delta_x)/dt during partial slip [m/s].
    displacement_history
        delta_x(t) [m] of partial slip instead of ``displacement_rate``: piecewise linear from
        delta_x(0) = 0 (held after its last point, as :class:`PiecewiseLinear`), of either sign and
        reversing (fretting). It needs ``slip = "incremental"``
        (a reversal unloads the stuck points from where they are; the total slip has no memory of
        that). The indenter never slides under it: a step whose contact has no stuck point left (an
        amplitude beyond gross slip) stops the run (:class:`~viscontact.errors.ParameterError`
        naming the time), and ``sliding_speed`` is not needed (``time.dt`` is free).
    sliding_speed
        Speed v of the indenter in +x once sliding [m/s]; in rolling, set to ``rolling_speed`` (the
        frame moves with the indenter's centre).
    rolling_speed
        Rolling: speed V of the indenter's centre in +x [m/s] (> 0).
    creepage
        Rolling: the held creepage xi = (V_c - V) / V [-] of the indenter's circumferential speed V_c
        (xi < 0: braking, the traction on the body points in +x); None under a held force.
    tangential_force
        Rolling: the held traction force sum q_x dA [N] (the ``friction_force``; |F| < mu_f W), the
        creepage found at each step; None under a held creepage.
    steps_per_cell
        k >= 1: time steps per grid cell of sliding (v dt = dx / k).
    slip
        How partial slip reads the slip s_x = u_x - delta_x of seed Eqs. 9, 11. ``"total"`` (the
        seed's): a stuck point has s_x = 0 at every step, without memory; exact while the contact
        does not grow and the loading is monotonic (a held approach), but a point entering a growing
        contact (a rising load, creep under a held load) is then forced to u_x = delta_x as if it had
        stuck since the contact began. ``"incremental"`` (Mindlin-Deresiewicz): a stuck point keeps
        its s_x, the slip condition acts on the step's change of s_x, and a point entering the
        contact sticks where it is. No effect outside partial slip.
    """

    mode: TangentialMode = "none"
    friction_coefficient: float = 0.0
    displacement_rate: float = 0.0
    sliding_speed: float = 0.0
    steps_per_cell: int = 1
    slip: SlipCondition = "total"
    displacement_history: PiecewiseLinear | None = None
    rolling_speed: float = 0.0
    creepage: float | None = None
    tangential_force: float | None = None

    def __post_init__(self) -> None:
        """What each mode needs; the one place that decides it (the case layer delegates here).

        Raises
        ------
        ParameterError
            A sliding mode without a speed > 0 m/s (partial slip under a displacement history
            needs none), partial slip without exactly one of a displacement rate > 0 m/s and a
            displacement history, or without a friction coefficient > 0 (with mu_f = 0 nothing would
            ever stick); a displacement history outside partial slip, not starting at 0 m, or with
            the total slip.
        """
        if self.mode not in TANGENTIAL_MODES:
            raise ParameterError("tangential.mode", f"must be one of {', '.join(map(repr, TANGENTIAL_MODES))}, "
                                 f"got {self.mode!r}")
        self._check_rolling()
        for name, unit in (("friction_coefficient", ""), ("displacement_rate", " m/s"), ("sliding_speed", " m/s")):
            _check_number(f"tangential.{name}", getattr(self, name), unit, strict=False)
        _check_integer("tangential.steps_per_cell", self.steps_per_cell)
        history = self.displacement_history
        if history is not None:
            self._check_history(history)
        if self.frame_moves and not self.sliding_speed > 0:
            raise ParameterError("tangential.sliding_speed", f"must be > 0 m/s with mode = '{self.mode}', "
                                 f"got {self.sliding_speed:g}")
        if self.mode == "partial_slip":
            if history is None and not self.displacement_rate > 0:
                raise ParameterError("tangential.displacement_rate",
                                     f"must be > 0 m/s with mode = 'partial_slip' (or give "
                                     f"tangential.displacement_history instead), got {self.displacement_rate:g}")
            if not self.friction_coefficient > 0:
                raise ParameterError("tangential.friction_coefficient",
                                     f"must be > 0 with mode = 'partial_slip', got {self.friction_coefficient:g}")
        if self.slip not in ("total", "incremental"):
            raise ParameterError("tangential.slip", f"must be 'total' or 'incremental', got {self.slip!r}")

    def _check_rolling(self) -> None:
        """Rolling needs ``rolling_speed`` > 0 m/s and exactly one of ``creepage`` and
        ``tangential_force`` (finite numbers); its frame moves at the rolling speed (``sliding_speed``
        is set to it; the case refuses a ``sliding_speed`` of its own), one cell per step. The rolling
        keys are refused in the other modes."""
        rolling_keys = {"rolling_speed": self.rolling_speed != 0, "creepage": self.creepage is not None,
                        "tangential_force": self.tangential_force is not None}
        if self.mode != "rolling":
            given = [key for key, set_ in rolling_keys.items() if set_]
            if given:
                raise ParameterError(f"tangential.{given[0]}", f"only with mode = 'rolling', got mode = '{self.mode}'")
            return
        _check_number("tangential.rolling_speed", self.rolling_speed, " m/s")
        if (self.creepage is None) == (self.tangential_force is None):
            raise ParameterError("tangential.creepage", "give exactly one of tangential.creepage (held, the traction "
                                 "found) and tangential.tangential_force (N, held, the creepage found) with mode = "
                                 "'rolling'")
        for name in ("creepage", "tangential_force"):
            value = getattr(self, name)
            if value is not None and not (is_number(value) and np.isfinite(value)):
                raise ParameterError(f"tangential.{name}", f"must be a finite number, got {value!r}")
        if self.tangential_force is not None and not self.friction_coefficient > 0:
            raise ParameterError("tangential.friction_coefficient", "must be > 0 with a held "
                                 "tangential.tangential_force (frictionless rolling carries none), got "
                                 f"{self.friction_coefficient:g}")
        if self.steps_per_cell != 1:
            raise ParameterError("tangential.steps_per_cell", "must be 1 with mode = 'rolling' (the rolling "
                                 f"frame moves by one cell per step), got {self.steps_per_cell!r}")
        object.__setattr__(self, "sliding_speed", float(self.rolling_speed))

    def _check_history(self, history: PiecewiseLinear) -> None:
        key = "tangential.displacement_history"
        check_history(history, key)
        if self.mode != "partial_slip":
            raise ParameterError(key, f"only with mode = 'partial_slip', got mode = '{self.mode}'")
        if self.displacement_rate != 0:
            raise ParameterError(key, "give exactly one of tangential.displacement_rate (a ramp until gross sliding) "
                                 f"and tangential.displacement_history, got both (displacement_rate = "
                                 f"{self.displacement_rate:g} m/s)")
        if history(0.0) != 0.0:
            raise ParameterError(key, f"must start at delta_x = 0 m at t = 0 s (the indenter's position at t = 0), "
                                 f"got {history(0.0):g} m")
        if self.slip != "incremental":
            raise ParameterError("tangential.slip", "must be 'incremental' with tangential.displacement_history: the "
                                 "total slip has no memory of the load path, so on a reversal of delta_x it would "
                                 "force every stuck point back to u_x = delta_x instead of unloading it from where "
                                 "it is (Mindlin-Deresiewicz)")

    def delta_x(self, t: float) -> float:
        """The tangential displacement of partial slip at time ``t`` [s] (m): the history, or the ramp."""
        if self.displacement_history is not None:
            return self.displacement_history(t)
        return self.displacement_rate * t

    @property
    def frame_moves(self) -> bool:
        """Whether the indenter may slide, ``time.dt`` then tied to ``sliding_speed`` (v dt = dx / k):
        every sliding mode but partial slip under a displacement history, which stops instead."""
        return self.slides and self.displacement_history is None

    @property
    def slides(self) -> bool:
        return self.mode != "none"

    @property
    def incremental_slip(self) -> bool:
        """Whether partial slip keeps the slip of its stuck points (``slip = "incremental"``)."""
        return self.mode == "partial_slip" and self.slip == "incremental"

    @property
    def has_shear(self) -> bool:
        """Whether this mode puts a shear traction q_x on the surface (``gross_sliding``,
        ``partial_slip``, ``rolling``); in ``none`` and ``frictionless_sliding`` q_x = 0 by definition."""
        return self.mode in ("gross_sliding", "partial_slip", "rolling")

    @property
    def rolls(self) -> bool:
        """Whether the indenter rolls (``mode = "rolling"``)."""
        return self.mode == "rolling"

    @property
    def effective_friction(self) -> float:
        """mu_f acting in this mode: 0 for ``none`` and ``frictionless_sliding``."""
        return self.friction_coefficient if self.has_shear else 0.0


#: most depths, and most times, of the subsurface stress output (output.subsurface_depths, _times)
MAX_SUBSURFACE_POINTS = 4096
#: most steps a run may take (t_end / dt): beyond, the counts and estimates drawn from it overflow, and
#: no run would end
MAX_STEPS = 10**9


@dataclass(frozen=True)
class TimeStepping:
    """Time discretisation.

    ``scheme = "linear"`` (the default) treats tractions as linear within a step (exact
    integration of the exponential compliance over the step; second order, stable for every dt).
    ``"constant"`` is the seed's: tractions constant within a step, increments act at the start of
    the step (first order, with a stability limit on dt).
    """

    t_end: float
    dt: float
    scheme: TimeScheme = "linear"

    def __post_init__(self) -> None:
        """``time.t_end`` a finite number >= 0 s, ``time.dt`` > 0 s (else :class:`ParameterError`)."""
        _check_number("time.t_end", self.t_end, " s", strict=False)
        _check_number("time.dt", self.dt, " s")
        if self.t_end / self.dt > MAX_STEPS:
            raise ParameterError("time.dt", f"time.t_end / time.dt = {self.t_end:.4g} s / {self.dt:.4g} s is "
                                 f"{self.t_end / self.dt:.3g} steps, more than the {MAX_STEPS:.0e} a run can take: "
                                 "check time.t_end and time.dt (when sliding, dt defaults to one cell of sliding per "
                                 "tangential.steps_per_cell steps: check tangential.sliding_speed and grid.half_width)")

    @property
    def n_steps(self) -> int:
        """Number of steps, the one at t = 0 included."""
        return int(np.floor(self.t_end / self.dt + 1e-9)) + 1


@dataclass(frozen=True)
class SolverSettings:
    """Tolerances and iteration caps. Failing to converge raises ``ConvergenceError``.

    Every field is checked on construction (:class:`~viscontact.errors.ParameterError` naming its
    ``solver.`` key and the allowed range), and the combinations no machine can run (``device = "gpu"``
    with ``fft = "pyfftw"`` or ``history = "direct"``). The settings describe the run; whether this
    machine can make it (CuPy and a CUDA device for ``"gpu"``, pyFFTW for ``"pyfftw"``) is decided at
    the start of the run (:func:`viscontact.running.preflight.check_machine`), so a case for a GPU loads,
    validates, is estimated and fingerprinted anywhere.
    """

    tolerance: float = 1e-8           # relative change of the traction field per CG iteration
    max_iterations: int = 2000        # per constrained CG solve
    coupling_tolerance: float = 1e-8  # relative change between normal/tangential alternations
    max_coupling_iterations: int = 100
    workers: int = -1                 # scipy.fft workers (-1: all cores above 512^2 cells, 1 below)
    history: Literal["recursive", "direct"] = "recursive"  # direct: literal sum of seed Eq. 5 (reference)
    coupling: bool = True             # False: drop the (1 - 2 nu) normal/tangential cross terms
    fft: Literal["scipy", "pyfftw"] = "scipy"  # DC-FFT transforms (viscontact.numerics.fftbackends); pyfftw: extra "fast"
    mixed_precision: bool = True      # CG search directions and preconditioner in float32 (viscontact.numerics.constrained)
    device: Literal["cpu", "gpu"] = "cpu"  # array backend: numpy, or CuPy on a CUDA GPU (viscontact.numerics.arrays)

    def __post_init__(self) -> None:
        for name in ("tolerance", "coupling_tolerance"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 < value < 1:
                raise ParameterError(f"solver.{name}", f"must be a number in (0, 1), got {value!r}")
        for name in ("max_iterations", "max_coupling_iterations"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
                raise ParameterError(f"solver.{name}", f"must be an integer >= 1, got {value!r}")
        w = self.workers
        if not is_integer(w) or w == 0 or w < -1:
            raise ParameterError("solver.workers", f"must be -1 (all cores) or an integer >= 1, got {w!r}")
        if self.history not in ("recursive", "direct"):
            raise ParameterError("solver.history", f"must be 'recursive' or 'direct', got {self.history!r}")
        for name in ("coupling", "mixed_precision"):
            if not isinstance(getattr(self, name), (bool, np.bool_)):
                raise ParameterError(f"solver.{name}", f"must be true or false, got {getattr(self, name)!r}")
        if self.device not in ("cpu", "gpu"):
            raise ParameterError("solver.device", f"must be 'cpu' or 'gpu', got {self.device!r}")
        if self.device == "gpu" and self.fft == "pyfftw":
            raise ParameterError("solver.fft", "'pyfftw' transforms on the CPU: with solver.device = 'gpu' "
                                 "the transforms are cuFFT's; use 'scipy' (the default)")
        if self.device == "gpu" and self.history == "direct":  # refused here, before any file: --dry-run too
            raise ParameterError("solver.history", "'direct' (the reference sum) runs on the CPU only: with "
                                 "solver.device = 'gpu' use 'recursive' (the default)")
        if self.fft not in ("scipy", "pyfftw"):
            raise ParameterError("solver.fft", f"must be 'scipy' or 'pyfftw', got {self.fft!r}")


@dataclass(frozen=True)
class OutputSettings:
    """What is recorded: every ``every``-th step (and always the last) and which fields."""

    every: int = 1
    fields: tuple[str, ...] = ("pressure", "shear_x", "stick")
    #: depths z [m] of the subsurface stress output in the section y = 0 (empty: none)
    subsurface_depths: tuple[float, ...] = ()
    #: times [s] of the subsurface output (the nearest recorded steps); None: the last recorded step
    subsurface_times: tuple[float, ...] | None = None

    def __post_init__(self) -> None:
        """``output.every`` an integer >= 1, ``output.fields`` a tuple or list of field names, the
        subsurface depths and times finite numbers >= 0 (else :class:`ParameterError`)."""
        from viscontact.problem.records import StepRecord

        _check_integer("output.every", self.every)
        fields = self.fields
        if not isinstance(fields, (tuple, list)) or any(f not in StepRecord.FIELDS for f in fields):
            raise ParameterError("output.fields", f"must be a list of {', '.join(map(repr, StepRecord.FIELDS))}, "
                                 f"got {fields!r}")
        for key, values in (("subsurface_depths", self.subsurface_depths), ("subsurface_times", self.subsurface_times)):
            for value in values or ():
                _check_number(f"output.{key}", value, " m" if key == "subsurface_depths" else " s", strict=False)
        check_subsurface_output(self.subsurface_depths, self.subsurface_times)


def check_subsurface_output(depths: Sequence[float], times: Sequence[float] | None) -> None:
    """Refuse (:class:`ParameterError`) an empty ``output.subsurface_times`` (it would select no
    step, and the subsurface output fail after the last step; None, the key left out, means the last
    recorded step) and more than :data:`MAX_SUBSURFACE_POINTS` depths or times (each depth at each
    time is a solve over the section: a million took minutes, after an estimate that saw none)."""
    if times is not None and len(times) == 0:
        raise ParameterError("output.subsurface_times", "must list at least one time [s], got []; leave the key out "
                             "for the last recorded step")
    for key, values in (("subsurface_depths", depths), ("subsurface_times", times or ())):
        if len(values) > MAX_SUBSURFACE_POINTS:
            raise ParameterError(f"output.{key}", f"lists {len(values)} entries, more than the "
                                 f"{MAX_SUBSURFACE_POINTS} a run computes: give fewer")


@dataclass(frozen=True)
class LayerSettings:
    """The viscoelastic material is a layer of ``thickness`` [m] on a base (the case's ``[layer]``).

    ``substrate``: the base, ``"rigid"`` or ``"elastic"`` (then ``substrate_shear_modulus`` [Pa] and
    ``substrate_poisson_ratio`` [-]); ``interface``: ``"bonded"`` or ``"frictionless"``. The field
    names are the case keys. The body is :class:`viscontact.bodies.layer.LayerOnBase`, its compliance
    that of :class:`viscontact.bodies.layer.Layer`.
    """

    thickness: float
    substrate: Literal["rigid", "elastic"] = "rigid"
    interface: Literal["bonded", "frictionless"] = "bonded"
    substrate_shear_modulus: float = float("inf")
    substrate_poisson_ratio: float = 0.3


def check_subsurface_body(depths, kind: Body | type) -> None:
    """Subsurface stresses (:mod:`viscontact.physics.subsurface`) are the elastic fields of the current
    tractions, true for the homogeneous half-space with constant nu only: raise
    :class:`~viscontact.errors.ParameterError` when ``depths`` are asked for of a body (``kind``, the
    body or its class: :func:`viscontact.bodies.registry.body_kind`) whose
    :attr:`~viscontact.bodies.base.Body.subsurface_stresses` is False."""
    if depths and not kind.subsurface_stresses:
        raise ParameterError("output.subsurface_depths", "needs a homogeneous half-space with material.poisson_ratio "
                             "(no [layer], no material.bulk_modulus): the stresses are the elastic fields of the "
                             "current tractions only there")


def check_line_contact_supported(problem: "Problem") -> None:
    """Refuse, in one line naming the key, what a line contact (``grid.dimension = 1``, plane strain)
    does not work with: an analytic shape other than the infinite cylinder and the strip punch
    (:meth:`~viscontact.problem.shapes.Shape.line_profile`; a gap without a shape, e.g. a ``surface``
    file of one row, is taken as it is). Periodic lines, layers, adhesion, rough profiles and
    subsurface stresses run on a line as on the square grid."""
    if problem.grid.dimension != 1:
        return
    if problem.shape is not None and not problem.shape.line_profile():
        raise ParameterError("indenter.shape", f"'{problem.shape.name}' is not a line contact's indenter "
                             "(grid.dimension = 1): use shape = 'cylinder' without a length (an infinite "
                             "cylinder, its gap x^2/(2R)) or 'flat_punch' (a strip)")


def check_adhesion_supported(problem: "Problem") -> None:
    """Refuse, in one line naming the key, what adhesion does not work with: a load history that pulls
    before it first presses (no equilibrium carries a tension without contact), and (not yet) rolling."""
    if problem.tangential.rolls:
        raise ParameterError("tangential.mode", "'rolling' is not supported with [adhesion] yet: an adhesive "
                             "rolling law is missing; roll without [adhesion], or slide (gross_sliding, partial_slip)")
    values = problem.normal.history.values
    pressed = next(i for i, v in enumerate(values) if v > 0)
    if problem.normal.control == "load" and min(values[:pressed + 1]) < 0:
        raise ParameterError("normal.history", f"a load history must press the indenter on (a load > 0 N) before it "
                             f"pulls: no equilibrium carries a tensile load before the first contact, got {values!r}")


@dataclass(frozen=True)
class Problem:
    """Everything the transient and steady solvers need.

    ``gap`` is the undeformed gap h0(x, y) [m] on the grid, in the frame of the indenter
    (origin under its centre). ``radius`` [m] is the sphere radius when the indenter is a sphere
    (used for Hertz normalisation and sub-cell shifts), else ``None``. ``shape`` is the analytic
    shape the gap was built from (:mod:`viscontact.problem.shapes`: its contact estimates, scales and
    resolution; None for a gap from a file or a generated surface): a sphere's mirrors ``radius``
    (given either way; ``radius = None`` makes the gap a plain gap), and ``radius`` is refused with
    any other shape.
    """

    material: Material
    grid: Grid
    gap: np.ndarray = field(repr=False)  # see frame_gap
    normal: NormalLoading
    tangential: TangentialLoading = TangentialLoading()
    time: TimeStepping = TimeStepping(t_end=0.0, dt=1.0)
    solver: SolverSettings = SolverSettings()
    output: OutputSettings = OutputSettings()
    radius: float | None = None
    title: str = ""
    #: elastic bulk modulus K [Pa]: nu(t) from G(t) and K (``material.poisson_ratio`` is then nu(0))
    bulk_modulus: float | None = None
    #: the material is a layer on a base (None: a half-space)
    layer: LayerSettings | None = None
    #: the gap was made by SurfaceTopography (a self-affine surface or roughness, a measured
    #: topography; set by :meth:`viscontact.io.case.Case.to_problem`): a run of it imports that package,
    #: which :func:`viscontact.running.resources.estimate` counts. It does not shape the solution.
    surface_topography: bool = False
    #: the surface's adhesive law (None: none, the seed's Kuhn-Tucker conditions; :mod:`viscontact.problem.adhesion`)
    adhesion: AdhesionSettings | None = None
    #: the compliant body (:class:`~viscontact.bodies.base.Body`): None builds it from ``material``,
    #: ``bulk_modulus`` and ``layer`` (:func:`viscontact.bodies.registry.body_of`, the one place);
    #: given, it sets ``bulk_modulus`` or ``layer`` when it is described by one, and takes ``material``
    body: Body | None = field(default=None, compare=False, repr=False)
    #: the analytic shape of the indenter (None: a gap from a file or a generated surface)
    shape: Shape | None = None

    def __post_init__(self) -> None:
        grid_shape = self.grid.shape
        self._mirror_sphere()
        if self.adhesion is None and self.normal.tensile and min(self.normal.history.values) < 0:
            raise ParameterError("normal.history", f"values must be >= 0 (N or m) without [adhesion], got "
                                 f"{self.normal.history.values!r}")
        if self.adhesion is not None:
            check_adhesion_supported(self)
        self._check_rough_rolling()
        if np.shape(self.gap) != grid_shape:
            raise ParameterError("gap", f"must be an array of the grid's shape {grid_shape}, got shape "
                                 f"{np.shape(self.gap)}")
        if not (np.isfinite(np.min(self.gap)) and np.isfinite(np.max(self.gap))):  # no n x n temporary
            raise ParameterError("gap", "must hold finite heights [m] only (NaN or Inf found)")
        if self.radius is not None:
            _check_number("indenter.radius", self.radius, " m")
        from viscontact.bodies.registry import body_of  # the solvers' modules: not for the command's parser

        body = body_of(self.material, self.body, bulk_modulus=self.bulk_modulus, layer=self.layer)
        object.__setattr__(self, "body", body)
        for key, value in body.description.items():  # a body given without its case key
            if key in ("bulk_modulus", "layer"):
                object.__setattr__(self, key, value)
        check_subsurface_body(self.output.subsurface_depths, body)
        check_line_contact_supported(self)

    def _check_rough_rolling(self) -> None:
        """Rolling on a rough surface (:meth:`rolling_gap`) needs a periodic grid and a held creepage;
        refused in one line otherwise."""
        if not self.rolls_rough:
            return
        missing = None
        if not self.grid.periodic:
            missing = ("needs grid.periodic = true: the roughness is carried through the contact as its "
                       "Fourier series (a convected roughness on a DC-FFT grid is missing)")
        elif self.tangential.creepage is None:
            missing = ("needs a held tangential.creepage: under a held tangential_force the roughness's "
                       "distance turned depends on each step's creepage (its accumulation is missing)")
        if missing:
            raise ParameterError("tangential.mode", f"'rolling' on a rough or measured surface {missing}; "
                                 "roll a smooth indenter, or slide (gross_sliding, partial_slip)")

    def _mirror_sphere(self) -> None:
        """Keep ``radius`` and a :class:`~viscontact.problem.shapes.Sphere` ``shape`` one description
        (``dataclasses.replace(problem, radius=None)`` turns a sphere's gap into a plain gap, as it
        always did); refuse a ``radius`` with another shape."""
        if self.shape is not None and not isinstance(self.shape, Shape):
            raise ParameterError("indenter.shape", f"must be a viscontact.problem.shapes.Shape, got {self.shape!r}")
        if self.shape is None or isinstance(self.shape, Sphere):
            sphere = None if self.radius is None else Sphere(self.radius)
            object.__setattr__(self, "shape", sphere)
        elif self.radius is not None:
            raise ParameterError("indenter.radius", f"is a sphere's radius; the indenter is a {self.shape.name} "
                                 f"({self.shape!r}): give radius = None")

    @cached_property
    def _gap_is_sphere(self) -> bool:
        """Whether the gap is the paraboloid of ``radius`` to round-off (built in any order: an exact
        comparison sent x^2/2R + y^2/2R to the interpolated shift)."""
        if self.radius is None:
            return False
        x, y = self.grid.mesh()
        sphere = (x**2 + y**2) / (2.0 * self.radius)
        return bool(np.allclose(self.gap, sphere, rtol=0.0, atol=1e-13 * sphere.max()))

    @property
    def sliding_dt(self) -> float | None:
        """The time step [s] that sliding ties ``time.dt`` to, (2 half_width / n) / sliding_speed /
        steps_per_cell (the frame moves by whole cells, one every ``steps_per_cell`` steps); None
        where the frame does not move (``time.dt`` is free) or the speed is not > 0."""
        tan = self.tangential
        if not (tan.frame_moves and tan.sliding_speed > 0):
            return None
        return self.grid.spacing / (tan.sliding_speed * tan.steps_per_cell)

    @cached_property
    def turning_steps(self) -> frozenset[int]:
        """The steps nearest the turning points of the run's histories (``normal.history``,
        ``tangential.displacement_history``: :meth:`PiecewiseLinear.turning_steps`), recorded whatever
        ``output.every`` (a fretting loop keeps its tips, a load pulse its peak)."""
        last = self.time.n_steps - 1
        histories = [self.normal.history, self.tangential.displacement_history]
        return frozenset(k for h in histories if h is not None for k, _ in h.turning_steps(self.time.dt, last))

    def recorded(self, step: int) -> bool:
        """Whether the result keeps step ``step``: every ``output.every``-th, the last and the
        :attr:`turning_steps`."""
        return step % self.output.every == 0 or step == self.time.n_steps - 1 or step in self.turning_steps

    @property
    def rolls_rough(self) -> bool:
        """Whether the indenter rolls on a rough or measured surface (``surface_topography``): its
        roughness is then carried through the contact (:meth:`rolling_gap`)."""
        return self.tangential.rolls and self.surface_topography

    @cached_property
    def _rolling_parts(self) -> tuple[np.ndarray, np.ndarray]:
        """The gap's smooth part (``shape``'s gap, fixed in the rolling frame; 0 without a shape) and
        its roughness, the rest [m]: gap = smooth + roughness."""
        smooth = np.zeros_like(self.gap) if self.shape is None else self.shape.gap(self.grid)
        return smooth, self.gap - smooth

    def rolling_gap(self, step: int) -> np.ndarray:
        """The undeformed gap [m] of rolling step ``step`` on a rough surface (:attr:`rolls_rough`).

        In the frame of the roller's axis (one cell dx = V dt per step) the roller's surface moves
        towards -x at its circumferential speed V (1 + xi) (``tangential.creepage`` xi), carrying its
        asperities through the contact, while its smooth shape stays in place: after k steps the gap
        is h_smooth(x) + r(x + k (1 + xi) dx), r the roughness (:attr:`_rolling_parts`), moved as its
        Fourier series along x (:func:`~viscontact.numerics.grid.shifted_periodic_x`; whole cells
        exactly). Step 0 (nothing rolled yet) and a problem that does not roll on a rough surface:
        ``gap`` itself.
        """
        if step == 0 or not self.rolls_rough:
            return self.gap
        smooth, roughness = self._rolling_parts
        return smooth + shifted_periodic_x(roughness, step * (1.0 + float(self.tangential.creepage)))

    def frame_gap(self, offset: float) -> np.ndarray:
        """Undeformed gap [m] on the grid with the indenter centre at x = ``offset`` [m], 0 <= offset < dx.

        The one place that moves the indenter within a cell (``tangential.steps_per_cell`` > 1):
        a sphere's paraboloid ((x - offset)^2 + y^2) / 2R is rebuilt exactly; on a periodic grid any
        other gap is translated exactly as its Fourier series along x (the phase exp(-i k_x offset);
        exact for a surface whose spectrum the grid holds, such as a generated self-affine one: a
        linear interpolation smoothed a rough surface, its approach 3-4 % high and its peak pressure
        10-14 % low at half a cell); on a DC-FFT grid it is interpolated linearly along x between
        neighbouring cells (error f (1 - f) dx^2 max|h''| / 2 at offset f dx), its first column
        extrapolated linearly (error f (1 + f) dx^2 max|h''| / 2). :meth:`frame_gaps` does the same
        on a device.
        """
        return self._host_frame_gaps.at(offset)

    def frame_gaps(self, to_device: Callable[[np.ndarray], Any] = lambda array: array) -> "FrameGaps":
        """What :meth:`frame_gap` builds the gap from, moved once by ``to_device`` (an
        :meth:`~viscontact.numerics.arrays.ArrayBackend.to_device`): its :meth:`FrameGaps.at` gives the gap at
        any offset on that device, equal to :meth:`frame_gap`'s, without copying a field there again."""
        sphere = periodic = None
        if self._gap_is_sphere:
            x, y = self.grid.mesh()
            sphere = (to_device(x[:1, :]), to_device(y[:, :1]), self.radius)  # broadcast: the same values
        elif self.grid.periodic:
            k_x = 2.0 * np.pi * np.fft.rfftfreq(self.grid.n, self.grid.spacing)
            periodic = (to_device(self._gap_rows_spectrum), to_device(k_x))
        return FrameGaps(to_device(self.gap), self.grid.spacing, sphere, periodic)

    @cached_property
    def _host_frame_gaps(self) -> "FrameGaps":
        return self.frame_gaps()

    @cached_property
    def _gap_rows_spectrum(self) -> np.ndarray:
        """The real FFT of the gap along x (periodic grids: :meth:`frame_gap`)."""
        return np.fft.rfft(self.gap, axis=1)


@dataclass(frozen=True)
class FrameGaps:
    """The undeformed gap at each frame offset (:meth:`Problem.frame_gap`) from arrays held by one
    array library (:meth:`Problem.frame_gaps`): each offset's gap is computed there by numpy's
    functions, which dispatch to the arrays' library, so a device needs no host field per step."""

    gap: Any
    spacing: float
    #: a sphere: x (1, n) and y (n, 1) [m], its radius [m]
    sphere: tuple[Any, Any, float] | None = None
    #: a periodic grid: the gap's real FFT along x, k_x [1/m]
    periodic: tuple[Any, Any] | None = None

    def at(self, offset: float) -> Any:
        """The gap [m] with the indenter centre at x = ``offset`` [m] (:meth:`Problem.frame_gap`)."""
        if offset == 0.0:
            return self.gap
        if self.sphere is not None:
            x, y, radius = self.sphere
            return ((x - offset) ** 2 + y**2) / (2.0 * radius)
        if self.periodic is not None:
            spectrum, k_x = self.periodic
            return np.fft.irfft(spectrum * np.exp(-1j * k_x * offset), self.gap.shape[1], axis=1)
        frac = offset / self.spacing
        behind = np.empty_like(self.gap)  # the gap one cell towards -x, h(x - dx)
        behind[:, 1:] = self.gap[:, :-1]
        behind[:, 0] = 2.0 * self.gap[:, 0] - self.gap[:, 1]
        return (1.0 - frac) * self.gap + frac * behind
