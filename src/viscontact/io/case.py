"""Case files: TOML text -> validated pydantic models -> :class:`~viscontact.problem.problem.Problem`.

Every key, with its unit, default and allowed range, is listed in the :ref:`case-key reference
<case-keys>` (generated from the models below). Every problem with the input -- not TOML, unknown
key, wrong type, value out of range, missing file -- is raised as one
:class:`~viscontact.errors.ParameterError` whose ``key`` is the dotted case-file key and whose
message gives the allowed range or values (and, for an unknown key, the closest valid one;
:mod:`viscontact.io.case_errors`).

Example (from the repository's root folder)
-------------------------------------------
>>> case = load_case("cases/creep_indentation.toml")
>>> small = case.with_overrides({"grid.n": 16, "time.t_end": 5e-4})
>>> problem = small.to_problem()
>>> problem.grid.n, problem.time.n_steps, problem.material.shear_modulus_instantaneous
(16, 3, 1930000.0)
>>> small.with_overrides({"grid.n": 4})
Traceback (most recent call last):
    ...
viscontact.errors.ParameterError: grid.n: must be >= 8, got 4
"""
from __future__ import annotations

import copy
import dataclasses
import json
import math
import re
from collections.abc import Mapping
from pathlib import Path
from typing import Annotated, Any, Callable, Literal

import numpy as np
import tomllib
from pydantic import BaseModel, ConfigDict, Field, PrivateAttr, ValidationError, model_validator
from pydantic.fields import FieldInfo

from viscontact.bodies.bulk_elastic import BulkElasticMaterial
from viscontact.bodies.registry import body_kind
from viscontact.errors import ParameterError, check_type, warn_caller
from viscontact.io.case_errors import closest, model_of, parameter_error
from viscontact.io.prony_table import parse_prony_table
from viscontact.io.safe_read import MAX_INPUT_BYTES, npy_layout, read_text_input, regular_input
from viscontact.numerics.grid import Grid
from viscontact.physics.materials import Material, shear_from_tensile, wlf_shift_factor
from viscontact.problem.adhesion import ADHESION_LAWS, AdhesionSettings
from viscontact.problem.problem import (
    LayerSettings,
    NormalLoading,
    OutputSettings,
    PiecewiseLinear,
    Problem,
    SolverSettings,
    TangentialLoading,
    TimeStepping,
    check_history,
    check_subsurface_body,
    check_subsurface_output,
)
from viscontact.problem.records import StepRecord
from viscontact.problem.shapes import SHAPES, Shape, shape_from_keys

__all__ = ["FILE_KEYS", "MATERIALS", "MAX_GRID_N", "MAX_INPUT_BYTES", "MIN_GRID_N", "Case", "case_keys", "closest",
           "load_case", "read_input_file", "required_first"]

#: the case keys that name a file the case reads (:meth:`Case.input_files`)
FILE_KEYS = ("material.file", "indenter.file")
#: smallest and largest grids accepted (cells per side); 16384^2 already needs ~100 GiB of kernels
MIN_GRID_N, MAX_GRID_N = 8, 16384
#: smallest and largest grid.half_width [m] accepted (1 nm to 1 km): beyond them the estimates drawn
#: from the grid (cells per contact radius, steps per cell of sliding) overflow
MIN_HALF_WIDTH, MAX_HALF_WIDTH = 1e-9, 1e3
_SLIDING_MODES = ("frictionless_sliding", "gross_sliding", "partial_slip", "rolling")
#: the keys of [normal] that give its values, one at a time
_NORMAL_FORMS = ("value", "history", "oscillation")


def _num(default: Any = ..., unit: str = "", **constraints: Any) -> Any:
    """A finite float field with a unit (shown in error messages)."""
    return Field(default, allow_inf_nan=False, json_schema_extra={"unit": unit}, **constraints)


def _int(default: Any = ..., **constraints: Any) -> Any:
    return Field(default, json_schema_extra={"unit": ""}, **constraints)


_POISSON = "Poisson ratio nu, constant in time"


class _Section(BaseModel):
    # strict: TOML is typed, so "0.3" (a string) is not a number; ints are accepted as floats.
    model_config = ConfigDict(extra="forbid", frozen=True, strict=True)


# --- [material] ---------------------------------------------------------------------------------
class _MaterialSection(_Section):
    """What every material type shares: exactly one of ``poisson_ratio`` (constant nu) and
    ``bulk_modulus`` (elastic K [Pa]; nu(t) follows from G(t) and K, :mod:`viscontact.bodies.bulk_elastic`)."""

    poisson_ratio: float | None = _num(None, unit="", ge=0, le=0.5,
                                       description=_POISSON + " [-], in [0, 0.5]; give this or bulk_modulus")
    bulk_modulus: float | None = _num(None, unit="Pa", gt=0,
                                      description="elastic bulk modulus K [Pa] (>= 2 G(0)/3) in place of "
                                                  "poisson_ratio: nu(t) = (3K - 2G(t)) / (2 (3K + G(t)))")

    @model_validator(mode="after")
    def _one_poisson(self) -> _MaterialSection:
        if (self.poisson_ratio is None) == (self.bulk_modulus is None):
            raise ParameterError("material.poisson_ratio", "give exactly one of material.poisson_ratio "
                                 "(in [0, 0.5]) and material.bulk_modulus (> 0 Pa)")
        return self

    def _build(self, poisson_ratio: float, base_dir: Path) -> Material:
        raise NotImplementedError

    def build(self, base_dir: Path = Path(".")) -> Material:
        """The material (files named in the section relative to ``base_dir``); with ``bulk_modulus``
        its ``poisson_ratio`` is nu(0) (K checked >= 2 G(0)/3)."""
        if self.bulk_modulus is None:
            return self._build(self.poisson_ratio, base_dir)
        bulk = self.bulk_elastic(base_dir)
        return dataclasses.replace(bulk.shear, poisson_ratio=bulk.poisson_ratio_instantaneous)

    def bulk_elastic(self, base_dir: Path = Path(".")) -> BulkElasticMaterial:
        """The shear relaxation with the elastic bulk modulus (needs ``bulk_modulus``)."""
        return BulkElasticMaterial(self._build(0.5, base_dir), float(self.bulk_modulus))


class _ViscoelasticSection(_MaterialSection):
    """Time-temperature superposition (WLF), shared by the viscoelastic materials: at
    ``temperature`` every relaxation time is multiplied by a_T (:func:`~viscontact.physics.materials.wlf_shift_factor`)
    of ``reference_temperature``, ``wlf_c1``, ``wlf_c2``. Without ``temperature`` the material is
    used at its reference temperature (a_T = 1)."""

    temperature: float | None = _num(None, unit="degC", gt=-273.15,
                                     description="temperature T; every relaxation time is shifted by a_T (WLF)")
    reference_temperature: float | None = _num(None, unit="degC", gt=-273.15,
                                               description="reference temperature T_ref of the moduli given")
    wlf_c1: float | None = _num(None, unit="", gt=0, description="WLF constant C1")
    wlf_c2: float | None = _num(None, unit="degC", gt=0, description="WLF constant C2")

    @model_validator(mode="after")
    def _wlf_complete(self) -> _ViscoelasticSection:
        if self.temperature is not None:
            for key in ("reference_temperature", "wlf_c1", "wlf_c2"):
                if getattr(self, key) is None:
                    raise ParameterError(f"material.{key}", "required with material.temperature (WLF shift: "
                                         "reference_temperature [degC], wlf_c1 > 0, wlf_c2 > 0 [degC])")
            self.shift_factor()  # T - T_ref <= -C2 is an error now, not at run time
        return self

    def shift_factor(self) -> float:
        """a_T [-] (1 without ``temperature``)."""
        if self.temperature is None:
            return 1.0
        return wlf_shift_factor(self.temperature, self.reference_temperature, self.wlf_c1, self.wlf_c2)

    def _build(self, poisson_ratio: float, base_dir: Path) -> Material:
        """The material at ``temperature``; files named in the section are relative to ``base_dir``."""
        return self._at_reference(base_dir, poisson_ratio).shifted(self.shift_factor())

    def _at_reference(self, base_dir: Path, poisson_ratio: float) -> Material:
        raise NotImplementedError


class ZenerMaterial(_ViscoelasticSection):
    """Standard linear solid: G(0), G(inf) [Pa] and the retardation (creep) time [s]."""

    type: Literal["zener"]
    shear_modulus_instantaneous: float = _num(unit="Pa", gt=0, description="instantaneous shear modulus G(0)")
    shear_modulus_long_term: float = _num(unit="Pa", gt=0,
                                          description="long-term shear modulus G(inf), at most G(0)")
    retardation_time: float = _num(unit="s", gt=0, description="retardation (creep) time; the relaxation time "
                                   "is retardation_time G(inf)/G(0)")

    @model_validator(mode="after")
    def _ordered(self) -> ZenerMaterial:
        if self.shear_modulus_long_term > self.shear_modulus_instantaneous:
            raise ParameterError("material.shear_modulus_long_term",
                                 f"must be <= shear_modulus_instantaneous = {self.shear_modulus_instantaneous:g} Pa, "
                                 f"got {self.shear_modulus_long_term:g} Pa")
        return self

    def _at_reference(self, base_dir: Path, poisson_ratio: float) -> Material:
        return Material.zener(self.shear_modulus_instantaneous, self.shear_modulus_long_term,
                              self.retardation_time, poisson_ratio)


class PronyMaterial(_ViscoelasticSection):
    """Generalized Maxwell: G(t) = g_inf + sum g_i exp(-t/tau_i) [Pa]; tau in s. The terms are typed
    (``g_inf``, ``g``, ``tau``) or read from ``file`` (:mod:`viscontact.io.prony_table`: the table
    pyvisco writes, or a plain CSV), relative to the case file's folder. ``modulus = "tensile"``
    says the moduli are tensile ones, E, converted to G = E / (2 (1 + poisson_ratio))."""

    type: Literal["prony"]
    g_inf: float | None = _num(None, unit="Pa", gt=0, description="long-term shear modulus G(inf) (or give file)")
    g: list[Annotated[float, Field(gt=0, allow_inf_nan=False)]] | None = Field(
        None, json_schema_extra={"unit": "Pa"}, description="Prony shear moduli g_i, one per relaxation time")
    tau: list[Annotated[float, Field(gt=0, allow_inf_nan=False)]] | None = Field(
        None, json_schema_extra={"unit": "s"}, description="relaxation times tau_i, as many as g")
    file: str | None = Field(None, description="Prony table file (pyvisco's, or a plain CSV tau, g), relative "
                             "to the case file, in place of g_inf, g and tau")
    modulus: Literal["shear", "tensile"] = Field("shear", description="the moduli given are shear ones (G) or "
                                                 "tensile ones (E, converted to G = E / (2 (1 + nu)))")

    @model_validator(mode="after")
    def _terms(self) -> PronyMaterial:
        typed = [k for k in ("g_inf", "g", "tau") if getattr(self, k) is not None]
        if self.modulus == "tensile" and self.bulk_modulus is not None:
            raise ParameterError("material.modulus", "'tensile' converts E to G with material.poisson_ratio; "
                                 "with material.bulk_modulus give shear moduli (modulus = 'shear')")
        if self.file is not None:
            if typed:
                raise ParameterError(f"material.{typed[0]}", "give either material.file or g_inf, g and tau, not both")
            return self
        for key in ("g_inf", "g", "tau"):
            if getattr(self, key) is None:
                raise ParameterError(f"material.{key}", "required with type = 'prony' (or give material.file, "
                                     "a Prony table)")
        if len(self.g) != len(self.tau):
            raise ParameterError("material.tau", f"must have as many entries as material.g ({len(self.g)}), "
                                 f"got {len(self.tau)}")
        return self

    def _at_reference(self, base_dir: Path, poisson_ratio: float) -> Material:
        if self.file is None:
            g_inf, g, tau, quantity = self.g_inf, self.g, self.tau, ""
        else:
            path = base_dir / self.file
            table = parse_prony_table(read_input_file(path, "material.file"), str(path))
            g_inf, g, tau, quantity = table.long_term, table.moduli, table.relaxation_times, table.quantity
            expected = {"shear": "G", "tensile": "E"}[self.modulus]
            if quantity and quantity != expected:
                raise ParameterError("material.modulus", f"{path} holds {quantity}_0/{quantity}_i columns "
                                     f"({'tensile' if quantity == 'E' else 'shear'} moduli); set modulus = "
                                     f"'{'tensile' if quantity == 'E' else 'shear'}', got {self.modulus!r}")
        if self.modulus == "tensile":
            g_inf = shear_from_tensile(g_inf, poisson_ratio)
            g = [shear_from_tensile(x, poisson_ratio) for x in g]
        return Material.prony(g_inf, g, tau, poisson_ratio)


class ElasticMaterial(_MaterialSection):
    """Elastic half-space: shear modulus G [Pa]."""

    type: Literal["elastic"]
    shear_modulus: float = _num(unit="Pa", gt=0, description="shear modulus G")

    def _build(self, poisson_ratio: float, base_dir: Path) -> Material:
        return Material.elastic(self.shear_modulus, poisson_ratio)


MATERIALS: dict[str, type[_Section]] = {"zener": ZenerMaterial, "prony": PronyMaterial,
                                          "elastic": ElasticMaterial}
MaterialSection = Annotated[ZenerMaterial | PronyMaterial | ElasticMaterial, Field(discriminator="type")]


# --- the other sections --------------------------------------------------------------------------
_SELF_AFFINE_KEYS = ("hurst", "rms_height", "rms_slope", "long_cutoff", "short_cutoff", "seed")
#: the keys of the analytic shapes besides radius (:mod:`viscontact.problem.shapes`)
_SHAPE_KEYS = ("length", "edge_radius", "radius_x", "radius_y", "half_angle")


class _SelfAffineKeys(_Section):
    """Keys of a self-affine surface (:func:`~viscontact.problem.topography.self_affine_heights`)."""

    hurst: float | None = _num(None, unit="", gt=0, le=1, description="Hurst exponent H of a self-affine surface")
    rms_height: float | None = _num(None, unit="m", gt=0, description="rms height (give rms_height or rms_slope)")
    rms_slope: float | None = _num(None, unit="", gt=0, description="rms gradient by forward differences on the grid "
                                   "(give rms_height or rms_slope)")
    long_cutoff: float | None = _num(None, unit="m", gt=0, description="roll-off wavelength (default: the period)")
    short_cutoff: float | None = _num(None, unit="m", gt=0, description="shortest wavelength (default: two cells)")
    seed: int | None = _int(None, ge=0, description="seed of the random phases and amplitudes (default 0); with "
                            "short_cutoff, the same surface at every grid.n")

    def _check_self_affine(self, table: str) -> None:
        if self.hurst is None:
            raise ParameterError(f"{table}.hurst", "required for a self-affine surface (0 < hurst <= 1)")
        if (self.rms_height is None) == (self.rms_slope is None):
            raise ParameterError(f"{table}.rms_height", "give exactly one of rms_height (m) or rms_slope (-)")

    def amplitude_key(self, table: str) -> str:
        """The key that sets the surface's amplitude (``rms_height`` or ``rms_slope``) in ``table``."""
        return f"{table}.rms_height" if self.rms_height is not None else f"{table}.rms_slope"

    def self_affine_heights(self, grid: Grid, table: str) -> np.ndarray:
        """Heights [m] of the self-affine surface these keys describe, on ``grid``."""
        from viscontact.problem.topography import self_affine_heights

        return self_affine_heights(grid, hurst=self.hurst, rms_height=self.rms_height, rms_slope=self.rms_slope,
                                   long_cutoff=self.long_cutoff, short_cutoff=self.short_cutoff,
                                   seed=self.seed or 0, key=table)


class RoughnessSection(_SelfAffineKeys):
    """``[indenter.roughness]``: self-affine roughness added to a sphere."""

    @model_validator(mode="after")
    def _complete(self) -> RoughnessSection:
        self._check_self_affine("indenter.roughness")
        return self


class IndenterSection(_SelfAffineKeys):
    """The rigid surface:

    * ``shape = "sphere"`` with ``radius`` [m] (and optionally ``[indenter.roughness]``);
    * the other analytic shapes (:mod:`viscontact.problem.shapes`, each with optional
      ``[indenter.roughness]``): ``"cylinder"`` (``radius``, ``length``, ``edge_radius`` [m]; its axis
      along y), ``"ellipsoid"`` (``radius_x``, ``radius_y`` [m]), ``"flat_punch"`` (``radius``,
      ``edge_radius`` [m]), ``"cone"`` (``half_angle`` [degrees]);
    * ``shape = "surface"`` with ``file``: a .npy of the undeformed gap h0 [m] on the grid (n x n, indexed
      [y, x]; its lowest point touches first: not heights z up, which ``topography`` takes);
    * ``shape = "self_affine"`` with ``hurst``, ``rms_height`` or ``rms_slope``, ``long_cutoff``,
      ``short_cutoff`` [m] and ``seed``: a periodic surface by Fourier synthesis;
    * ``shape = "topography"`` with ``file``: anything SurfaceTopography reads (x3p, opd, sur, di,
      NetCDF, plain text, ...), heights of the rigid surface z up, in the file's physical size and
      units (``physical_size_m`` [m] and ``unit`` for a file that gives none); ``resample = true``
      interpolates it onto the grid.

    Files are relative to the case file's folder.
    """

    shape: Literal[(*SHAPES, "surface", "self_affine", "topography")] = Field(
        "sphere", description="a sphere (paraboloid gap (x^2 + y^2)/(2 radius)); a cylinder (gap x^2/(2 radius), "
        "its axis along y, over length with rounded ends of edge_radius and end walls); an ellipsoid (gap "
        "x^2/(2 radius_x) + y^2/(2 radius_y)); a flat circular punch of radius (its rim sharp or rounded by "
        "edge_radius, a wall about it); a cone of semi-apex angle half_angle (gap r cot(half_angle)); a gap "
        "read from a .npy file; a generated self-affine surface; or a measured topography file")
    radius: float | None = _num(None, unit="m", gt=0, description="radius R of the sphere, of the cylinder "
                                "(its cross-section) or of the flat punch (its face); required with those shapes")
    length: float | None = _num(None, unit="m", gt=0, description="with shape = 'cylinder': its length L along y, "
                                "ends included (required on a 2-D grid)")
    edge_radius: float | None = _num(None, unit="m", ge=0, description="with shape = 'cylinder' or 'flat_punch': "
                                     "the radius of the rounded ends or rim (parabolic rounding "
                                     "(distance)^2/(2 edge_radius)); default 0, a sharp edge (a singular pressure)")
    radius_x: float | None = _num(None, unit="m", gt=0, description="with shape = 'ellipsoid': the radius of "
                                  "curvature in the x-z plane (gap x^2/(2 radius_x) + y^2/(2 radius_y))")
    radius_y: float | None = _num(None, unit="m", gt=0, description="with shape = 'ellipsoid': the radius of "
                                  "curvature in the y-z plane")
    half_angle: float | None = _num(None, unit="degrees", gt=0, lt=90, description="with shape = 'cone': the "
                                    "semi-apex angle alpha between the axis and the flank (gap r cot(alpha); "
                                    "a Berkovich tip's equivalent cone: 70.3)")
    file: str | None = Field(None, description="with shape = 'surface': .npy of the undeformed gap h0 [m], "
                             "(grid.n, grid.n), indexed [y, x], its lowest point touching first, h0[j, i] the gap "
                             "at the cell centre (x_i, y_j), x_i = y_i = -half_width + (i + 1/2) dx, dx = "
                             "2 half_width / n (numerics.grid.Grid.x); with shape = "
                             "'topography': any file SurfaceTopography reads that carries its physical size and "
                             "unit, heights z up (highest point touching first); relative to the case file's folder")
    resample: bool | None = Field(None, description="with shape = 'topography': interpolate the file onto the grid")
    physical_size_m: list[Annotated[float, Field(gt=0, allow_inf_nan=False)]] | None = Field(
        None, min_length=2, max_length=2, json_schema_extra={"unit": "m"},
        description="with shape = 'topography': [width, height] [m] of a file that does not give its size (a "
        ".npy, a text matrix without header); needs indenter.unit, the unit of the file's heights")
    physical_size: list[Annotated[float, Field(gt=0, allow_inf_nan=False)]] | None = Field(
        None, min_length=2, max_length=2, description="deprecated (warns): [width, height] in indenter.unit, "
        "not SI; use indenter.physical_size_m (metres)")
    unit: Literal["m", "mm", "um", "nm"] | None = Field(
        None, description="with shape = 'topography': the length unit of the heights of a file that does not "
        "give it (and of the deprecated physical_size)")
    roughness: RoughnessSection | None = Field(None, description="with shape = 'sphere': self-affine roughness "
                                               "([indenter.roughness], the self-affine keys)")

    @property
    def uses_surface_topography(self) -> bool:
        """Whether building this surface imports SurfaceTopography (a self-affine surface or roughness,
        a measured topography): :data:`viscontact.running.resources.TOPOGRAPHY_IMPORT_MEMORY` more."""
        return self.shape in ("self_affine", "topography") or self.roughness is not None

    @model_validator(mode="after")
    def _consistent(self) -> IndenterSection:
        shape = self.shape
        for key in _REQUIRED[shape]:
            if getattr(self, key) is None:
                what = {"file": "a file name", "half_angle": "in (0, 90) degrees"}.get(key, "> 0 m")
                raise ParameterError(f"indenter.{key}", f"required for shape = '{shape}' ({what})")
        for key in ("radius", *_SHAPE_KEYS, "file", "resample", "physical_size", "physical_size_m", "unit",
                    "roughness", *_SELF_AFFINE_KEYS):
            if getattr(self, key) is not None and key not in _ALLOWED[shape]:
                owners = " or ".join(repr(s) for s, keys in _ALLOWED.items() if key in keys)
                raise ParameterError(f"indenter.{key}", f"only with shape = {owners}")
        if shape == "self_affine":
            self._check_self_affine("indenter")
        self.analytic_shape()  # a shape's own checks (a roller's rounded ends within its length, a cone's angle)
        if self.physical_size_m is not None and self.physical_size is not None:
            raise ParameterError("indenter.physical_size", "give indenter.physical_size_m (metres) only: "
                                 "physical_size (in indenter.unit) is its deprecated form")
        if self.physical_size_m is not None and self.unit is None:
            raise ParameterError("indenter.unit", "required with indenter.physical_size_m: the length unit of the "
                                 "file's heights (\"m\", \"mm\", \"um\" or \"nm\")")
        return self

    def analytic_shape(self) -> Shape | None:
        """The analytic shape of :data:`~viscontact.problem.shapes.SHAPES` these keys describe, None for
        a surface, a self-affine surface or a topography."""
        if self.shape not in SHAPES:
            return None
        return shape_from_keys(self.shape, {key: getattr(self, key) for key in ("radius", *_SHAPE_KEYS)})

    def warn_deprecated(self) -> None:
        """Warn (:class:`~viscontact.errors.ViscontactWarning`) where the deprecated ``physical_size``
        (in ``unit``, not SI) is given, naming the ``physical_size_m`` [m] to write instead; called
        once the file it sizes has been read (:meth:`Case.gap`), so that a refused file is one line."""
        if self.physical_size is not None:
            scale = _LENGTH_UNITS[self.unit or "m"]
            warn_caller(f"indenter.physical_size is deprecated: it is in indenter.unit, not SI; use "
                        f"indenter.physical_size_m = {[x * scale for x in self.physical_size]!r} (metres)")

    def physical_sizes(self) -> tuple[float, float] | None:
        """[width, height] of the topography file in its unit ``indenter.unit`` (what SurfaceTopography
        takes), from ``physical_size_m`` [m] or the deprecated ``physical_size``; None when neither is given."""
        if self.physical_size_m is not None:
            scale = _LENGTH_UNITS[self.unit]
            return (self.physical_size_m[0] / scale, self.physical_size_m[1] / scale)
        return None if self.physical_size is None else tuple(self.physical_size)


#: metres per unit of indenter.unit
_LENGTH_UNITS = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "nm": 1e-9}


#: keys each indenter shape requires, and all the keys it accepts: an analytic shape's its class's
#: (:mod:`viscontact.problem.shapes`), with roughness added
_REQUIRED = {**{name: cls.required for name, cls in SHAPES.items()},
             "surface": ("file",), "self_affine": (), "topography": ("file",)}
_ALLOWED = {**{name: {*cls.required, *cls.optional, "roughness"} for name, cls in SHAPES.items()},
            "surface": {"file"}, "self_affine": set(_SELF_AFFINE_KEYS),
            "topography": {"file", "resample", "physical_size", "physical_size_m", "unit"}}


class GridSection(_Section):
    """n x n cells on [-half_width, half_width]^2 [m]; ``periodic``: one period of a repeated surface;
    ``dimension = 1``: a line contact (plane strain), n cells along x, forces per unit length."""

    n: int = _int(ge=MIN_GRID_N, le=MAX_GRID_N, description="cells per side")
    half_width: float = _num(unit="m", ge=MIN_HALF_WIDTH, le=MAX_HALF_WIDTH,
                             description="the domain is [-half_width, half_width]^2")
    periodic: bool = Field(False, description="the domain is one period of an infinitely repeated surface "
                           "(periodic kernels, the moving frame wrapping around)")
    dimension: Literal[1, 2] = Field(2, description="2: the n x n surface grid; 1: a line contact in plane strain "
                                     "(fields depend on x only, y has size 1 in results; normal.value and every "
                                     "force per unit length, N/m; contact_area per unit length, m; approaches "
                                     "relative to the surface at half_width from the load)")


class OscillationSection(_Section):
    """``[normal] oscillation = {mean, amplitude, frequency, cycles}``: a load or approach
    mean + amplitude sin(2 pi frequency t) from t = 0 for ``cycles`` cycles, then held at its last
    value (the mean after whole or half cycles; a DMA-like test), turned into the piecewise-linear ``normal.history`` through
    ``points_per_cycle`` points a cycle (a multiple of 4: every peak and trough is a point)."""

    mean: float = _num(unit="N or m", description="mean load or approach, reached at t = 0")
    amplitude: float = _num(unit="N or m", ge=0, description="amplitude of the sine about the mean")
    frequency: float = _num(unit="Hz", gt=0, description="frequency f of the sine")
    cycles: float = _num(unit="", gt=0, le=1e5, description="number of cycles (after them the last value is held)")
    points_per_cycle: int = _int(64, ge=4, le=4096, multiple_of=4, description="points of the piecewise-linear "
                                 "history per cycle, a multiple of 4 (peaks and troughs on points); its "
                                 "chord error is about amplitude (pi / points_per_cycle)^2 / 2")

    def history(self) -> list[list[float]]:
        """The [[t, value], ...] points [s, N or m] of the oscillation: phases k / points_per_cycle
        (cycles) up to ``cycles`` (and ``cycles`` itself), peaks, troughs and crossings of the mean exact."""
        steps = self.cycles * self.points_per_cycle
        phase = np.arange(int(math.floor(steps + 1e-9)) + 1) / self.points_per_cycle
        if steps - math.floor(steps + 1e-9) > 1e-9:
            phase = np.append(phase, self.cycles)
        quarters = phase * 4.0
        on_quarter = np.abs(quarters - np.round(quarters)) < 1e-9
        wave = np.where(on_quarter, np.array([0.0, 1.0, 0.0, -1.0])[np.round(quarters).astype(int) % 4],
                        np.sin(2.0 * np.pi * phase))
        return [[float(p / self.frequency), float(self.mean + self.amplitude * w)] for p, w in zip(phase, wave)]


class NormalSection(_Section):
    """Load W [N] or approach delta_z [m]: a held ``value``, a piecewise-linear ``history`` or an
    ``oscillation`` (a sine about a mean, made a history)."""

    control: Literal["load", "displacement"] = Field(description="prescribe the load W or the approach delta_z")
    value: float | None = _num(None, unit="N or m", gt=0, description="held from t = 0 (give value, history "
                               "or oscillation)")
    history: list[list[float]] | None = Field(None, json_schema_extra={"unit": "[s, N or m]"},
                                              description="[[t, value], ...], piecewise linear, times increasing "
                                              "from >= 0 (give value, history or oscillation)")
    oscillation: OscillationSection | None = Field(None, description="{mean, amplitude, frequency, cycles}: "
                                                   "mean + amplitude sin(2 pi frequency t) for cycles cycles, "
                                                   "then held (give value, history or oscillation)")

    @model_validator(mode="after")
    def _one_of(self) -> NormalSection:
        given = [k for k in ("value", "history", "oscillation") if getattr(self, k) is not None]
        if len(given) != 1:
            raise ParameterError(f"normal.{given[0]}" if given else "normal",
                                 "give exactly one of 'value' (held from t = 0) or 'history' "
                                 "([[t, value], ...], piecewise linear) or 'oscillation' ({mean, amplitude, "
                                 "frequency, cycles})")
        # the pairs (piecewise_linear), finite values, increasing times: NormalLoading; the sign (values
        # >= 0 without [adhesion]) is checked by the case, which knows whether the surface adheres
        self.build(tensile=True)
        return self

    def build(self, tensile: bool = False) -> NormalLoading:
        """The normal loading; ``tensile``: values below zero allowed (with ``[adhesion]``)."""
        if self.oscillation is not None:
            return NormalLoading(self.control, piecewise_linear(self.oscillation.history(), "normal.oscillation"),
                                 tensile)
        if self.history is None:
            return NormalLoading(self.control, PiecewiseLinear.constant(self.value), tensile)
        return NormalLoading(self.control, piecewise_linear(self.history, "normal.history"), tensile)


def piecewise_linear(points: list[list[float]], key: str) -> PiecewiseLinear:
    """The history through ``points`` ([[t, value], ...]) of the case key ``key``, checked: a non-empty
    list of pairs of finite numbers, times >= 0 s and strictly increasing (else
    :class:`~viscontact.errors.ParameterError` naming ``key``); the values are the caller's to check."""
    if not points or any(len(p) != 2 for p in points):
        raise ParameterError(key, "must be a non-empty list of [t, value] pairs")
    history = PiecewiseLinear(tuple(float(p[0]) for p in points), tuple(float(p[1]) for p in points))
    check_history(history, key)
    return history


class TangentialSection(_Section):
    """Tangential motion: ``mode`` and the friction coefficient, rates and speed [m/s]."""

    mode: Literal["none", "frictionless_sliding", "gross_sliding", "partial_slip", "rolling"] = Field(
        "none", description="indentation only, sliding without friction, Coulomb sliding from t = 0, partial "
        "slip at displacement_rate until the stick zone vanishes, then sliding (or following "
        "displacement_history, which does not slide), or rolling in +x at rolling_speed with a held creepage "
        "or a held tangential_force")
    friction_coefficient: float = _num(0.0, unit="", ge=0, description="Coulomb coefficient mu_f; > 0 for "
                                       "partial_slip")
    displacement_rate: float = _num(0.0, unit="m/s", ge=0, description="rate of the tangential displacement "
                                    "delta_x during partial slip; > 0 for partial_slip unless "
                                    "displacement_history is given")
    displacement_history: list[list[float]] | None = Field(
        None, json_schema_extra={"unit": "[s, m]"}, description="[[t, delta_x], ...]: partial slip's tangential "
        "displacement, piecewise linear, times increasing from >= 0, delta_x from 0 at t = 0 (held at the first "
        "value before the first time and at the last value after the last time), of either sign and reversing (fretting: Q-delta_x loops below gross slip), instead of displacement_rate; needs slip = "
        "'incremental' (its default here); no sliding: a step whose stick zone vanishes (an amplitude beyond "
        "gross slip) stops the run; sliding_speed is not needed and time.dt must be given")
    sliding_speed: float = _num(0.0, unit="m/s", ge=0, description="speed v once sliding; > 0 in every sliding mode "
                                "(but partial slip under displacement_history)")
    rolling_speed: float = _num(0.0, unit="m/s", ge=0, description="rolling: speed V of the indenter's centre in "
                                "+x (> 0; the frame moves one cell per step: dt = (2 half_width / n) / V)")
    creepage: float | None = _num(None, unit="", description="rolling: the held creepage (V_c - V) / V of the "
                                  "indenter's circumferential speed V_c (< 0: braking, the traction on the body "
                                  "in +x, friction_force > 0); give this or tangential_force")
    tangential_force: float | None = _num(None, unit="N", description="rolling: the held traction force "
                                          "friction_force = sum q_x dA (|F| < mu_f W), the creepage found at each "
                                          "step; give this or creepage")
    steps_per_cell: int = _int(1, ge=1, description="time steps per grid cell of sliding (the default dt is "
                               "one cell of travel divided by this)")
    slip: Literal["total", "incremental"] = Field(
        "total", description="partial slip's stick condition on the slip s_x = u_x - delta_x: total (the "
        "seed's Eqs. 9, 11: s_x = 0 at every stuck point at every step, without memory; exact under a held "
        "approach, too stiff where the contact grows: a rising load, creep under a held load) or incremental "
        "(Mindlin-Deresiewicz: a stuck point keeps its s_x, a point entering the contact sticks where it is, "
        "the slip condition acts on each step's change of s_x; the default, and the only one, under "
        "displacement_history); no effect outside partial_slip")

    @model_validator(mode="after")
    def _mode_needs(self) -> TangentialSection:
        self.build()  # what each mode needs is decided by TangentialLoading
        return self

    def build(self) -> TangentialLoading:
        history = (None if self.displacement_history is None else
                   piecewise_linear(self.displacement_history, "tangential.displacement_history"))
        # a displacement history needs the incremental slip: its default where slip is not given
        slip = "incremental" if history is not None and "slip" not in self.model_fields_set else self.slip
        if self.mode == "rolling" and "sliding_speed" in self.model_fields_set:
            raise ParameterError("tangential.sliding_speed", "give tangential.rolling_speed (the speed of the "
                                 "indenter's centre) with mode = 'rolling', not sliding_speed")
        return TangentialLoading(self.mode, self.friction_coefficient, self.displacement_rate,
                                 self.sliding_speed, self.steps_per_cell, slip, history, self.rolling_speed,
                                 self.creepage, self.tangential_force)


class TimeSection(_Section):
    """End time and step [s]; ``dt`` defaults to one cell of sliding per ``steps_per_cell`` steps.
    ``scheme``: ``"linear"`` (default, second order) or the seed's ``"constant"`` (first order)."""

    t_end: float = _num(unit="s", gt=0, description="end time")
    dt: float | None = _num(None, unit="s", gt=0, description="time step, <= t_end; required without sliding "
                            "(tangential.mode = 'none', or a tangential.displacement_history); when sliding, "
                            "leave it out: dt = (2 half_width / n) / sliding_speed / steps_per_cell (the frame "
                            "moves by whole cells), made smaller by tangential.steps_per_cell")
    scheme: Literal["constant", "linear"] = Field("linear", description="traction linear within a step (the "
                                                  "default: second order, stable for any dt) or constant "
                                                  "(the seed's, first order)")


_FIELD_NAMES = Literal["pressure", "shear_x", "stick", "displacement_z"]


class OutputSection(_Section):
    """Record every ``every``-th step (and the last and the histories' turning points) and these
    fields; optionally the subsurface stresses in the section y = 0 at ``subsurface_depths`` [m] and
    ``subsurface_times`` [s]."""

    every: int = _int(OutputSettings.every, ge=1,
                      description="record every k-th step (and the last, and the steps at the turning points of "
                                  "normal.history and tangential.displacement_history)")
    fields: list[_FIELD_NAMES] = Field(list(OutputSettings.fields), json_schema_extra={"unit": ""},
                                       description="fields on the grid kept at the recorded steps")
    subsurface_depths: list[Annotated[float, Field(ge=0, allow_inf_nan=False)]] = Field(
        [], json_schema_extra={"unit": "m"},
        description="depths z [m] (>= 0) of the stress output in the section y = 0 (von Mises, maximum shear); "
                    "homogeneous half-space with poisson_ratio only")
    subsurface_times: list[Annotated[float, Field(ge=0, allow_inf_nan=False)]] | None = Field(
        None, json_schema_extra={"unit": "s"},
        description="times [s] of the subsurface output (nearest recorded steps); default the last recorded step")


class LayerSection(_Section):
    """The material is a layer of ``thickness`` [m] on a rigid or elastic substrate."""

    thickness: float = _num(unit="m", gt=0, description="layer thickness h [m], > 0")
    substrate: Literal["rigid", "elastic"] = Field(
        "rigid", description="what the layer lies on: 'rigid' or 'elastic' (then substrate_shear_modulus, "
                             "substrate_poisson_ratio; a viscoelastic layer there has one kernel per shift node)")
    interface: Literal["bonded", "frictionless"] = Field(
        "bonded", description="layer/substrate interface: 'bonded' or 'frictionless' (normal contact only)")
    substrate_shear_modulus: float | None = _num(None, unit="Pa", gt=0,
                                                 description="shear modulus G_s [Pa] of an elastic substrate")
    substrate_poisson_ratio: float | None = _num(None, unit="", ge=0, le=0.5,
                                                 description="Poisson ratio nu_s [-] of an elastic substrate, in [0, 0.5]")

    @model_validator(mode="after")
    def _substrate_needs(self) -> LayerSection:
        for key in ("substrate_shear_modulus", "substrate_poisson_ratio"):
            given = getattr(self, key) is not None
            if self.substrate == "elastic" and not given:
                raise ParameterError(f"layer.{key}", "required with layer.substrate = 'elastic'")
            if self.substrate == "rigid" and given:
                raise ParameterError(f"layer.{key}", "only with layer.substrate = 'elastic'")
        return self

    def build(self) -> LayerSettings:
        if self.substrate == "rigid":
            return LayerSettings(self.thickness, "rigid", self.interface)
        return LayerSettings(self.thickness, "elastic", self.interface, self.substrate_shear_modulus,
                             self.substrate_poisson_ratio)


class AdhesionSection(_Section):
    """Adhesion of the surface (absent: none): a Maugis-Dugdale law, a tension ``cohesive_stress``
    wherever the gap is open but below w / cohesive_stress (Maugis 1992), or an exponential law, a
    tension (w / range) exp(-gap / range) across every open gap (Muser 2014). With it, a load
    history may be tensile and an approach history may go below zero (retraction to pull-off and
    beyond)."""

    work_of_adhesion: float = _num(unit="J/m^2", gt=0, description="Dupre work of adhesion w [J/m^2], > 0")
    law: Literal["maugis_dugdale", "exponential"] = Field(
        "maugis_dugdale", description="traction-separation law: 'maugis_dugdale' (a tension cohesive_stress "
        "wherever 0 < gap < work_of_adhesion / cohesive_stress) or 'exponential' (a tension "
        "(work_of_adhesion / range) exp(-gap / range) wherever gap > 0)")
    cohesive_stress: float | None = _num(None, unit="Pa", gt=0, description="sigma_0 [Pa] of the Maugis-Dugdale "
                                         "law, > 0 (required with law = 'maugis_dugdale')")
    range: float | None = _num(None, unit="m", gt=0, description="rho [m] of the exponential law, the gap over "
                               "which its tension falls by e, > 0 (required with law = 'exponential')")

    @model_validator(mode="after")
    def _law_needs(self) -> AdhesionSection:
        kind = ADHESION_LAWS[self.law]
        if getattr(self, kind.key) is None:
            raise ParameterError(f"adhesion.{kind.key}", f"required (> 0 {kind.unit}) with adhesion.law = {self.law!r}")
        for other in ADHESION_LAWS.values():
            if other is not kind and getattr(self, other.key) is not None:
                raise ParameterError(f"adhesion.{other.key}", f"not a key of adhesion.law = {self.law!r}")
        return self

    def build(self) -> AdhesionSettings:
        # the validator left only the law's own parameter set
        return AdhesionSettings(self.work_of_adhesion, self.cohesive_stress, self.law, self.range)


class SolverSection(_Section):
    """Tolerances (relative) and iteration caps of the constrained CG and the coupling loop, FFT
    workers and backend (``fft``: "scipy" or "pyfftw"), the history algorithm, ``coupling``
    (false: drop the (1 - 2 nu) normal/tangential cross terms) and ``mixed_precision`` (false: every
    product in double)."""

    tolerance: float = _num(SolverSettings.tolerance, unit="", gt=0, lt=1,
                            description="the constrained conjugate-gradient solves stop when the relative "
                            "change of their unknown in an iteration, sum|x - x_old| / sum|x|, falls below it")
    max_iterations: int = _int(SolverSettings.max_iterations, ge=1, description="iteration cap of one solve")
    coupling_tolerance: float = _num(SolverSettings.coupling_tolerance, unit="", gt=0, lt=1,
                                     description="relative change of the tractions that ends the normal/"
                                     "tangential coupling loop")
    max_coupling_iterations: int = _int(SolverSettings.max_coupling_iterations, ge=1,
                                        description="cap of the coupling loop")
    workers: int = _int(SolverSettings.workers, ge=-1, description="FFT threads; -1 for all cores on grids above "
                               "512^2 cells and one thread below, where a second one is slower (0 is refused)")
    history: Literal["recursive", "direct"] = Field(SolverSettings.history, description="hereditary sum: "
                                                    "recursive (one field per retardation time) or the direct "
                                                    "sum over all past steps (reference, slow)")
    coupling: bool = Field(SolverSettings.coupling, description="false: drop the (1 - 2 nu) normal/tangential "
                           "cross terms")
    fft: Literal["scipy", "pyfftw"] = Field(SolverSettings.fft, description="DC-FFT transforms: scipy (pocketfft) "
                                            "or pyfftw (FFTW plans; needs the optional package pyFFTW, extra fast)")
    mixed_precision: bool = Field(SolverSettings.mixed_precision, description="the CG's search directions and "
                                  "preconditioner in single precision (float32 transforms, about half their time; "
                                  "the solution and its residual stay double, so the results agree to the "
                                  "tolerance); false: every product in double")
    device: Literal["cpu", "gpu"] = Field(SolverSettings.device, description="array backend: cpu (numpy, "
                                          "scipy.fft) or gpu (CuPy and cuFFT on the first CUDA device; needs the "
                                          "optional extra gpu or gpu-cuda13)")

    @model_validator(mode="after")
    def _workers(self) -> SolverSection:
        if self.workers == 0:
            raise ParameterError("solver.workers", "must be -1 (all cores) or >= 1, got 0")
        return self


# --- the case -----------------------------------------------------------------------------------
class Case(_Section):
    """A validated case file. Build it with :func:`load_case` or :meth:`from_toml_text`.

    ``text`` is the TOML text it came from; ``base_dir`` the folder that relative paths in it
    (``indenter.file``) refer to.
    """

    title: str = Field("", description="shown on figures and stored in the result")
    material: MaterialSection
    indenter: IndenterSection
    grid: GridSection
    normal: NormalSection
    tangential: TangentialSection = TangentialSection()
    time: TimeSection
    output: OutputSection = OutputSection()
    solver: SolverSection = SolverSection()
    layer: LayerSection | None = None
    adhesion: AdhesionSection | None = None

    _text: str = PrivateAttr("")
    _base_dir: Path = PrivateAttr(default_factory=Path)
    _data: dict = PrivateAttr(default_factory=dict)

    @model_validator(mode="after")
    def _cross_checks(self) -> Case:
        if any(ord(c) < 32 and c not in "\t\n" for c in self.title):
            raise ParameterError("title", "must not contain control characters such as NUL (\\0): they cannot be "
                                 "stored in the result file")
        if self.time.dt is None and self.tangential.mode not in _SLIDING_MODES:
            raise ParameterError("time.dt", "required (> 0 s) when tangential.mode = 'none'")
        if self.time.dt is None and self.tangential.displacement_history is not None:
            raise ParameterError("time.dt", "required (> 0 s) with tangential.displacement_history (the indenter "
                                 "does not slide, so no sliding speed sets it)")
        TimeStepping(self.time.t_end, self.default_dt())  # at most MAX_STEPS steps
        if self.time.dt is not None and self.time.dt > self.time.t_end:
            raise ParameterError("time.dt", f"must be <= time.t_end = {self.time.t_end:g} s, got {self.time.dt:g} s")
        check_subsurface_output(self.output.subsurface_depths, self.output.subsurface_times)
        if self.output.subsurface_depths:
            check_subsurface_body(self.output.subsurface_depths, self._body_kind())
            needs = ["pressure"] + (["shear_x"] if self.tangential.mode in ("gross_sliding", "partial_slip") else [])
            missing = [f for f in needs if f not in self.output.fields]
            if missing:
                raise ParameterError("output.fields", f"must include {missing} for output.subsurface_depths")
        self._body_kind()  # one body: material.bulk_modulus and [layer] are refused together
        self.normal.build(tensile=self.adhesion is not None)  # a tensile history needs [adhesion]
        return self

    def _body_kind(self) -> type:
        """The class of the case's body (:func:`viscontact.bodies.registry.body_kind`) from the keys that
        describe it."""
        return body_kind({"bulk_modulus": self.material.bulk_modulus, "layer": self.layer})

    # --- construction -------------------------------------------------------------------------
    @classmethod
    def from_toml_text(cls, text: str, base_dir: str | Path = ".", *, source: str = "case file") -> Case:
        """Parse and validate TOML ``text``; relative paths in it are taken from ``base_dir``
        (:class:`TypeError` when ``text`` is not a str or ``base_dir`` not a path)."""
        check_type(text, str, "Case.from_toml_text's text", "the TOML text of a case (a str)")
        check_type(base_dir, (str, Path), "Case.from_toml_text's base_dir", "a folder (a str or Path)")
        try:
            data = tomllib.loads(text.removeprefix("\ufeff"))
        except tomllib.TOMLDecodeError as exc:
            raise ParameterError("case file", f"{source} is not valid TOML: {exc}") from None
        except RecursionError:
            raise ParameterError("case file", f"{source} nests arrays or tables too deeply to be a case file") from None
        return cls._from_data(data, text, Path(base_dir))

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], base_dir: str | Path = ".") -> Case:
        """A case from a dict of its tables, as a case file nests them (``{"grid": {"n": 64, ...},
        ...}``); relative paths in it are taken from ``base_dir``. Its :attr:`text` is the TOML that
        the dict spells (stored in the result like a case file's); numpy scalars and arrays are taken
        as the numbers and lists they hold.

        Raises
        ------
        TypeError
            ``data`` is not a mapping (of section names to tables).
        ParameterError
            A key or value the case refuses, as for a case file.
        """
        check_type(data, Mapping, "Case.from_dict's data", "a dict of case tables, e.g. {'grid': {'n': 64, ...}}")
        return cls.from_toml_text(toml_text(data), base_dir, source="the dict")

    @classmethod
    def _from_data(cls, data: dict, text: str, base_dir: Path) -> Case:
        try:
            case = cls.model_validate(data)
        except ValidationError as exc:
            raise parameter_error(exc, cls, MATERIALS) from None
        except RecursionError:
            raise ParameterError("case file", "nests arrays or tables too deeply to be a case file") from None
        case._text, case._base_dir, case._data = text, base_dir, data
        case.material.build(base_dir)  # a Prony table file is read (and checked) now
        return case

    @property
    def text(self) -> str:
        """The TOML text of the case (with applied overrides listed as comments at its end)."""
        return self._text

    @property
    def base_dir(self) -> Path:
        return self._base_dir

    def with_overrides(self, overrides: Mapping[str, Any]) -> Case:
        """A new case with dotted keys replaced, e.g. ``{"tangential.sliding_speed": 0.1}``.

        A value of ``None`` removes the key (its default applies). Setting one of ``normal.value``,
        ``normal.history`` and ``normal.oscillation`` drops the others. The new case is validated
        as a whole; its ``text`` is the original one followed by the overrides as comments. A numpy
        array or scalar is taken as the list or number it holds.

        Raises
        ------
        TypeError
            ``overrides`` is not a mapping of dotted keys (str) to values.
        ParameterError
            A key or value the case refuses.
        """
        check_type(overrides, Mapping, "with_overrides's overrides", "a dict of dotted case keys to values, e.g. "
                   "{'grid.n': 64}")
        data = copy.deepcopy(self._data)
        lines = []
        for key, value in overrides.items():
            check_type(key, str, "each key of with_overrides's overrides", "a dotted case key such as 'grid.n'")
            value = value.item() if isinstance(value, np.generic) else value
            value = value.tolist() if isinstance(value, np.ndarray) else value
            parts = key.split(".")
            node = data
            for i, part in enumerate(parts[:-1]):
                node = node.setdefault(part, {})
                if not isinstance(node, dict):
                    raise ParameterError(".".join(parts[:i + 1]), f"is not a table, cannot set {key}")
            if value is None:
                node.pop(parts[-1], None)
                lines.append(f"# {key} removed")
                continue
            node[parts[-1]] = value
            if parts[:-1] == ["normal"] and parts[-1] in _NORMAL_FORMS:
                for other in set(_NORMAL_FORMS) - {parts[-1]}:
                    node.pop(other, None)
            lines.append(f"# {key} = {value!r}")
        text = self._text.rstrip("\n") + "\n\n# overrides applied by viscontact:\n" + "\n".join(lines) + "\n"
        return self._from_data(data, text, self._base_dir)

    # --- to the core --------------------------------------------------------------------------
    def default_dt(self) -> float:
        """dt [s]: as given, else one grid cell of sliding per ``steps_per_cell`` steps."""
        if self.time.dt is not None:
            return self.time.dt
        tan = self.tangential
        speed = tan.rolling_speed if tan.mode == "rolling" else tan.sliding_speed
        return (2.0 * self.grid.half_width / self.grid.n) / speed / tan.steps_per_cell

    def input_files(self) -> dict[str, Path]:
        """Every file the case reads besides its own text, by the key naming it (:data:`FILE_KEYS`:
        ``material.file``, the Prony table; ``indenter.file``, the heights of a ``surface`` or
        ``topography``), relative paths taken from :attr:`base_dir`. A result depends on their
        content, and a run must never replace one of them."""
        files = {}
        for key in FILE_KEYS:
            section, name = key.split(".")
            value = getattr(getattr(self, section), name, None)  # material.file: type = "prony" only
            if value is not None:
                files[key] = self._base_dir / value
        return files

    def gap(self, grid: Grid) -> np.ndarray:
        """Undeformed gap h0(x, y) [m] on ``grid``: an analytic shape's (:meth:`~viscontact.problem.shapes.Shape.gap`:
        (x^2 + y^2)/(2R) for a smooth sphere), else the heights (z up; a shape's with roughness; on a
        line grid a profile: a self-affine one or a line scan)
        shifted so that the highest point touches first at delta_z = 0; a .npy ``surface`` file holds
        the gap itself, shifted so that its lowest point is 0."""
        from viscontact.problem.topography import check_surface, gap_from_heights, read_heights

        ind = self.indenter
        shape = ind.analytic_shape()
        if shape is not None:  # its heights are in m by construction: no slope check (walls: problem.shapes)
            if ind.roughness is None:
                return shape.gap(grid)
            rough = ind.roughness.self_affine_heights(grid, "indenter.roughness")
            check_surface(rough, grid, ind.roughness.amplitude_key("indenter.roughness"))
            return gap_from_heights(shape.heights(grid) + rough)
        if ind.shape == "self_affine":
            gap, key = gap_from_heights(ind.self_affine_heights(grid, "indenter")), ind.amplitude_key("indenter")
        elif ind.shape == "topography":
            check_topography_file(self._base_dir / ind.file, grid.n, "indenter.file")
            heights = read_heights(self._base_dir / ind.file, grid, resample=bool(ind.resample),
                                   physical_sizes=ind.physical_sizes(),
                                   unit={"um": "µm"}.get(ind.unit, ind.unit))
            ind.warn_deprecated()
            gap, key = gap_from_heights(heights), "indenter.file"
        else:
            h0 = read_height_file(self._base_dir / ind.file, grid.shape)
            gap, key = h0 - h0.min(), "indenter.file"
        check_surface(gap, grid, key)
        return gap

    def to_problem(self) -> Problem:
        """The :class:`~viscontact.problem.problem.Problem` the solvers consume."""
        return self._problem(lambda grid: self.gap(grid))

    def problem_outline(self) -> Problem:
        """:meth:`to_problem` without the gap: in its place a read-only zero-stride array of zeros of
        the grid's shape (no memory). Sizes, steps, modes and settings are the problem's: what the
        estimate of a run's memory, disk and time needs
        (:func:`viscontact.running.resources.check_resources`), before any n x n array is allocated (at
        n = 16384 the problem alone takes 8 GB)."""
        return self._problem(lambda grid: np.broadcast_to(np.float64(0.0), grid.shape))

    def _problem(self, gap: Callable[[Grid], np.ndarray]) -> Problem:
        grid = Grid(self.grid.n, self.grid.half_width, self.grid.periodic, self.grid.dimension)
        fields = tuple(f for f in StepRecord.FIELDS if f in self.output.fields)
        shape = self.indenter.analytic_shape()
        return Problem(
            material=self.material.build(self._base_dir),
            grid=grid,
            gap=gap(grid),
            normal=self.normal.build(tensile=self.adhesion is not None),
            tangential=self.tangential.build(),
            time=TimeStepping(self.time.t_end, self.default_dt(), self.time.scheme),
            solver=SolverSettings(**self.solver.model_dump()),
            output=OutputSettings(self.output.every, fields, tuple(self.output.subsurface_depths),
                                  None if self.output.subsurface_times is None else tuple(self.output.subsurface_times)),
            title=self.title,
            bulk_modulus=self.material.bulk_modulus,
            layer=None if self.layer is None else self.layer.build(),
            surface_topography=self.indenter.uses_surface_topography,
            adhesion=None if self.adhesion is None else self.adhesion.build(),
            radius=None if shape is None else shape.sphere_radius,
            shape=shape,
        )


def toml_text(data: Mapping[str, Any]) -> str:
    """The TOML text of a case's nested dict (:meth:`Case.from_dict`): its top-level keys, then one
    ``[table]`` per nested dict; numbers, booleans, strings and (nested) lists as values. Raises
    :class:`~viscontact.errors.ParameterError` (key: the dotted key) for a value TOML cannot hold."""
    scalars, tables = [], []
    for key, value in data.items():
        check_type(key, str, "each key of a case dict", "a section or key name (a str)")
        (tables if isinstance(value, Mapping) else scalars).append((key, value))
    lines = [f"{_toml_key(k)} = {_toml_value(v, k)}" for k, v in scalars]
    for name, table in tables:
        lines += ["", f"[{_toml_key(name)}]"]
        lines += [f"{_toml_key(k)} = {_toml_value(v, f'{name}.{k}')}" for k, v in table.items()
                  if not isinstance(v, Mapping)]
        nested = {k: v for k, v in table.items() if isinstance(v, Mapping)}
        for sub, inner in nested.items():  # [indenter.roughness]
            lines += ["", f"[{_toml_key(name)}.{_toml_key(sub)}]"]
            lines += [f"{_toml_key(k)} = {_toml_value(v, f'{name}.{sub}.{k}')}" for k, v in inner.items()]
    return "\n".join(lines) + "\n"


def _toml_key(name: str) -> str:
    """A TOML key: bare when it can be, else quoted."""
    return name if re.fullmatch(r"[A-Za-z0-9_-]+", name) else json.dumps(name)


def _toml_value(value: Any, key: str) -> str:
    """One TOML value (:func:`toml_text`)."""
    value = value.item() if isinstance(value, np.generic) else value
    value = value.tolist() if isinstance(value, np.ndarray) else value
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value) if np.isfinite(value) else {"inf": "inf", "-inf": "-inf"}.get(repr(value), "nan")
    if isinstance(value, str):
        return json.dumps(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v, key) for v in value) + "]"
    raise ParameterError(key, f"a case value must be a number, bool, str or list, got {type(value).__name__}")


def read_height_file(path: Path, shape: tuple[int, int]) -> np.ndarray:
    """Heights [m] of a .npy file of ``shape`` (real numbers, finite). The header is read first
    (:func:`~viscontact.io.safe_read.npy_layout`), so that a file that is not a regular file (a FIFO
    would block), is empty, has a malformed header, claims another shape or size, or holds complex or
    non-numeric data is refused (key ``indenter.file``) before any data is read."""
    key = "indenter.file"
    expected = f"it must be (grid.n, grid.n) = {shape}, real heights in m indexed [y, x]"
    found, dtype, _, _ = npy_layout(path, key)
    if tuple(found) != shape:
        raise ParameterError(key, f"{path} holds an array of shape {tuple(found)}; {expected}")
    if not (np.issubdtype(dtype, np.floating) or np.issubdtype(dtype, np.integer)):
        raise ParameterError(key, f"{path} holds {dtype} data; {expected}")
    try:
        h0 = np.load(path, allow_pickle=False)
    except (OSError, ValueError, EOFError) as exc:
        raise ParameterError(key, f"cannot read {path} as a .npy array: {str(exc) or type(exc).__name__}") from None
    if not np.all(np.isfinite(h0)):
        raise ParameterError(key, f"{path} must hold finite numbers (heights in m)")
    return np.asarray(h0, dtype=float)


#: largest topography file read [bytes per point of a grid whose side is RESAMPLE_RATIO (4) times the
#: grid's]: a text map takes about 25 bytes a point; SurfaceTopography reads a file whole
TOPOGRAPHY_BYTES_PER_POINT = 64


def check_topography_file(path: Path, n: int, key: str) -> None:
    """Refuse, before SurfaceTopography reads it whole, a topography file that is not a regular file
    (:func:`~viscontact.io.safe_read.regular_input`), is larger than a map for ``n`` x ``n`` cells can
    be (at most :data:`TOPOGRAPHY_BYTES_PER_POINT` bytes for each point of a 4n x 4n map, 16 MiB at
    least), or is a ``.npy`` file whose header is malformed or disagrees with its size."""
    limit = max(MAX_INPUT_BYTES, TOPOGRAPHY_BYTES_PER_POINT * (4 * n) ** 2)
    regular_input(path, key, max_bytes=limit, need="a topography file")
    try:
        with open(path, "rb") as fh:
            magic = fh.read(6)
    except OSError as exc:
        raise ParameterError(key, f"cannot read {path}: {exc.strerror}") from None
    if magic == b"\x93NUMPY":
        npy_layout(path, key)


def read_input_file(path: str | Path, what: str) -> str:
    """The UTF-8 text of an input file (a byte-order mark is skipped); :class:`ParameterError` (key
    ``what``, e.g. ``"case file"``) when it is missing, not a file, unreadable, or holds more than
    :data:`MAX_INPUT_BYTES` (read no further: ``/dev/zero`` or a result file named by mistake would
    otherwise fill the memory; a pipe with a writer, e.g. ``<(...)``, is read as a file, a FIFO with
    none refused): :func:`viscontact.io.safe_read.read_text_input`."""
    return read_text_input(path, what)


def load_case(path: str | Path) -> Case:
    """Read and validate a TOML case file. Raises :class:`ParameterError` (key ``"case file"``)
    when it is missing, unreadable or not TOML."""
    path = Path(path)
    return Case.from_toml_text(read_input_file(path, "case file"), path.parent, source=str(path))


def case_keys() -> dict[str, Any]:
    """Every settable dotted case key (``"grid.n"``) -> its pydantic FieldInfo; the keys of every
    material type together under ``material.`` (:func:`_material_keys`: ``material.type`` takes
    every type, and a key that only some types take says which at the end of its description). The
    unit is in ``json_schema_extra["unit"]``."""
    keys: dict[str, Any] = {}

    def walk(model: type[BaseModel], prefix: str) -> None:
        for name, info in required_first(model):
            if model is Case and name == "material":
                keys.update(_material_keys())
                continue
            sub = model_of(info.annotation)
            if sub is not None:
                walk(sub, f"{prefix}{name}.")
            else:
                keys.setdefault(f"{prefix}{name}", info)

    walk(Case, "")
    return keys


def required_first(model: type[BaseModel]) -> list[tuple[str, FieldInfo]]:
    """The fields of ``model`` as (name, FieldInfo): the required ones first (``material.type``
    before the optional keys a material inherits), each group in declaration order; the order of
    :func:`case_keys` and of the case-key reference."""
    fields = list(model.model_fields.items())
    return [f for f in fields if f[1].is_required()] + [f for f in fields if not f[1].is_required()]


def _material_keys() -> dict[str, Any]:
    """The ``material.`` keys of every type of :data:`MATERIALS` -> FieldInfo: ``material.type`` one
    of every type; a key that only some types take, a copy whose description ends with them
    (``(material.type = "zener" or "prony")``); the others as the types declare them."""
    takers: dict[str, list[str]] = {}
    fields: dict[str, Any] = {}
    for tag, model in MATERIALS.items():
        for name, info in required_first(model):
            takers.setdefault(name, []).append(tag)
            fields.setdefault(name, info)
    keys = {}
    for name, info in fields.items():
        if name == "type":
            info = FieldInfo(annotation=Literal[tuple(MATERIALS)], description="the material model; the keys "
                             "that only some models take name them")
        elif len(takers[name]) < len(MATERIALS):
            info = copy.copy(info)
            info.description = f"{info.description} (material.type = {' or '.join(map(_quoted, takers[name]))})"
        keys[f"material.{name}"] = info
    return keys


def _quoted(text: str) -> str:
    return f'"{text}"'
