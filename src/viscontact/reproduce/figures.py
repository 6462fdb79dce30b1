"""Which shipped cases make which seed figure, at which times, drawn by which function.

=======  ==============================================  ===========================================
figure   cases                                           panels
=======  ==============================================  ===========================================
fig4     seed_table1_v{0.4,0.8,1.2} (load, no friction)  p/p0 along y = 0 at t = 0, 0.5, 1, 2 tau per
                                                         speed; mu_app(t/tau)
fig6     seed_table2_ratio{3,5,10}_displacement          p/p0 at t = 0, 0.5, 1, 2, 4 tau per ratio;
                                                         G(t)/G(0)
fig7     seed_table2_ratio{3,5,10}_load                  p/p0 at t = 0, 0.5, 1, 2, 4 tau per ratio;
                                                         J(t) G(0)
fig8     both sets of Table 2                            mu_app(t/tau): relaxation | creep
fig9     seed_table3_case{1,2,3,4} (displacement)        per t = 0, 0.1, 0.5, 1, 1.5 tau: q_x of cases
                                                         3, 4 with mu_f p and stick zones | p of all
fig10    seed_fig10_case{1,2,3} (load)                   as fig9 at t = 0, 0.1, 0.2, 1, 4 tau (case 3)
=======  ==============================================  ===========================================

tau is the results' ``retardation_time`` (the shortest creep retardation time of the material;
the Zener retardation time of the seed's materials).
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from viscontact.plotting import FigureFiles
from viscontact.plotting import seed as draw

__all__ = ["FIGURES", "SHOWS", "FigureSpec"]

#: what each seed figure shows, in a line (``viscontact reproduce --help``)
SHOWS: dict[str, str] = {
    "fig4": "frictionless sliding at 0.4, 0.8, 1.2 a0/tau under a held load: p/p0 along y = 0 at t = 0, "
            "0.5, 1, 2 tau per speed, and mu_app(t)",
    "fig6": "frictionless sliding under a held approach (relaxation), G(0)/G(inf) = 3, 5, 10: p/p0 at "
            "t = 0 ... 4 tau per ratio, and G(t)/G(0)",
    "fig7": "the same under a held load (creep): p/p0 per ratio, and J(t) G(0)",
    "fig8": "mu_app(t) of the fig6 and fig7 runs: relaxation | creep",
    "fig9": "frictionless, gross sliding and partial slip at two rates under a held approach: q_x with "
            "mu_f p and the stick zones, and p, at t = 0 ... 1.5 tau; stick/slip maps",
    "fig10": "frictionless, gross sliding and partial slip under a held load of 0.15 N, at t = 0 ... "
             "4 tau; a stick/slip map",
}

Runs = Mapping[str, Any]  # case name -> its result Dataset
Render = Callable[[Runs, "FigureSpec", FigureFiles], list[Path]]


@dataclass(frozen=True)
class FigureSpec:
    """One seed figure: its cases, the times [tau] its fields are drawn at, its title and how it is
    drawn (``render(runs, spec, files)`` -> the files written by ``files``). ``record_times`` [tau] are the
    times the runs record fields at, when not ``times`` (fig8 shares the runs of fig6 and fig7)."""

    name: str
    cases: tuple[str, ...]
    times: tuple[float, ...]
    title: str
    render: Render = field(repr=False)
    record_times: tuple[float, ...] | None = None

    @property
    def times_recorded(self) -> tuple[float, ...]:
        return self.times if self.record_times is None else self.record_times


def _one(build: Callable[[Runs, FigureSpec], Any]) -> Render:
    """A figure drawn by ``build(runs, spec)`` as ``<name>.<format>``."""

    def render(runs: Runs, spec: FigureSpec, files: FigureFiles) -> list[Path]:
        return [files.save(build(runs, spec), spec.name)]

    return render


def _frictional(shear_cases: tuple[str, ...]) -> Render:
    """Figs. 9 and 10: the traction figure, then a stick/slip map per case of ``shear_cases``."""

    def render(runs: Runs, spec: FigureSpec, files: FigureFiles) -> list[Path]:
        paths = [files.save(draw.frictional_figure(runs, spec.times, spec.title, shear_cases), spec.name)]
        for name in shear_cases:
            title = f"{name.replace('seed_', '').replace('_', ' ')}: slip (orange), stick (blue)"
            paths.append(draw.stick_slip_map(runs[name], spec.times, files, f"{spec.name}_{name}_stick_map",
                                             title=title))
        return paths

    return render


_TABLE2 = tuple(f"seed_table2_ratio{r}_{c}" for c in ("displacement", "load") for r in (3, 5, 10))
_TABLE2_TIMES = (0.0, 0.5, 1.0, 2.0, 4.0)

FIGURES: dict[str, FigureSpec] = {spec.name: spec for spec in (
    FigureSpec("fig4", ("seed_table1_v0.4", "seed_table1_v0.8", "seed_table1_v1.2"), (0.0, 0.5, 1.0, 2.0),
               "Seed Fig. 4 / Table 1: frictionless sliding under W = 0.148 N",
               _one(lambda runs, s: draw.profiles_figure(runs, s.times, s.title))),
    FigureSpec("fig6", _TABLE2[:3], _TABLE2_TIMES,
               "Seed Fig. 6 / Table 2: frictionless sliding under a held approach (relaxation)",
               _one(lambda runs, s: draw.material_figure(runs, s.times, s.title, "relaxation"))),
    FigureSpec("fig7", _TABLE2[3:], _TABLE2_TIMES,
               "Seed Fig. 7 / Table 2: frictionless sliding under a held load (creep)",
               _one(lambda runs, s: draw.material_figure(runs, s.times, s.title, "creep"))),
    FigureSpec("fig8", _TABLE2, (), "Seed Fig. 8: apparent friction of the Table 2 materials",
               _one(lambda runs, s: draw.apparent_friction_figure(runs, s.title)),
               record_times=_TABLE2_TIMES),  # the runs of fig6/fig7: their saved results are reused
    FigureSpec("fig9", tuple(f"seed_table3_case{c}" for c in (1, 2, 3, 4)), (0.0, 0.1, 0.5, 1.0, 1.5),
               "Seed Fig. 9 / Table 3: frictional sliding under a held approach",
               _frictional(("seed_table3_case3", "seed_table3_case4"))),
    FigureSpec("fig10", tuple(f"seed_fig10_case{c}" for c in (1, 2, 3)), (0.0, 0.1, 0.2, 1.0, 4.0),
               "Seed Fig. 10: frictional sliding under a held load W = 0.15 N", _frictional(("seed_fig10_case3",))),
)}
