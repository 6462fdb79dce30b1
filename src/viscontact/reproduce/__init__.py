"""Reproduce the figures of the seed (Wang et al., Friction 2023, Figs. 4 and 6-10) from the shipped cases.

:mod:`.figures` defines each figure (its cases, times and drawing), :mod:`.runner` runs the cases,
saves and reuses their results and draws the figure with :mod:`viscontact.plotting.seed`.
``viscontact reproduce FIGURE --out DIR [--n N]`` on the command line.
"""
from viscontact.reproduce.figures import FIGURES, FigureSpec
from viscontact.reproduce.runner import (
           draw,
           find_cases_dir,
           load_seed_case,
           record_every,
           reproduce,
           run_seed_cases,
           time_scale,
)

__all__ = ["FIGURES", "FigureSpec", "draw", "find_cases_dir", "load_seed_case", "record_every", "reproduce",
           "run_seed_cases", "time_scale"]
