"""Figures of a train's efficiency (``derive FILE --plot NAME=START:STOP [--vs NAME2=...]``).

- Against one parameter (like Chen Fig. 4.9 and 4.13): the efficiency, the regions of
  the variants with the turning conditions where the variant changes, and the power
  lost in each friction element stacked below, all in percent of the input power.
- Over two parameters: the variant regions, the turning-condition curves (condition =
  0), efficiency contours, and the self-locking or inadmissible area left blank.
- A turning-condition surface over three parameters (like Laus Fig. 11), solved for
  one of them.

The numbers come from the generated formula module of the train (compiled in memory),
so a figure shows what design code gets.  Figures are built on ``matplotlib.figure.Figure``
(no pyplot state) and written as PNG without a timestamp, so the bytes are reproducible.
"""

from __future__ import annotations

import io
import itertools
import os
import textwrap
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from functools import partial
from types import ModuleType
from typing import Any

import numpy as np
import sympy

from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.parameters import formula_symbols
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.python_module import python_module
from davies_sym.errors import MissingDependencyError, NotCoveredError

POINTS_1D = 400
POINTS_2D = 240


@dataclass(frozen=True)
class Sweep:
    """A parameter and the interval it runs over."""

    name: str
    start: float
    stop: float

    def values(self, count: int) -> np.ndarray:
        return np.linspace(self.start, self.stop, count)


def require_drawn(eta: np.ndarray, efficiency: Callable[..., Any], arguments: Mapping[str, Any], swept: str) -> None:
    """Refuse (`NotCoveredError`) a figure with nothing to draw: the efficiency is NaN at
    every point (self-locking or outside the variants' regions throughout).  The reason is
    the module's own, at the sweep's first point."""
    if np.isfinite(eta).any():
        return
    first = {k: np.ravel(v)[0] if isinstance(v, np.ndarray) else v for k, v in arguments.items()}
    try:
        efficiency(errors="raise", **first)
        reason = "the efficiency is not defined there"
    except Exception as exc:  # the module's DesignError: its message is the reason
        reason = str(exc)
    shown = ", ".join(f"{k}={float(v):g}" for k, v in sorted(first.items()))
    raise NotCoveredError(f"--plot: no point of the sweep of {swept} has an efficiency to draw; at {shown}: {reason}")


def formula_module(variants: VariantSet) -> ModuleType:
    """The generated module of ``variants``, compiled in memory."""
    return compiled_module(python_module(variants), variants.train.name)


def new_figure(width: float = 7.0, height: float = 5.0) -> Any:
    """A matplotlib figure with constrained layout (no pyplot state)."""
    try:
        from matplotlib.figure import Figure
    except ImportError as exc:
        raise MissingDependencyError(
            "figures need matplotlib, an optional dependency: pip install 'davies_sym[plots]'"
        ) from exc

    return Figure(figsize=(width, height), layout="constrained")


#: Figure formats by file suffix, each without the metadata that changes from run to run
#: (software version, creation time), so that the same figure gives the same bytes.
FIGURE_FORMATS = {
    ".png": ("png", {"Software": None}),
    ".svg": ("svg", {"Date": None, "Creator": None}),
    ".pdf": ("pdf", {"CreationDate": None, "Producer": None, "Creator": None}),
}


def figure_format(path: str) -> str | None:
    """The suffix of ``path`` when it names a figure format (``.png``, ``.svg``, ``.pdf``)."""
    suffix = os.path.splitext(path)[1].lower()
    return suffix if suffix in FIGURE_FORMATS else None


def figure_bytes(figure: Any, suffix: str = ".png") -> bytes:
    """The figure in the format of ``suffix`` (reproducible bytes)."""
    from matplotlib import rc_context

    form, metadata = FIGURE_FORMATS[suffix]
    buffer = io.BytesIO()
    # A fixed salt makes the SVG element ids the same from run to run.
    with rc_context({"svg.hashsalt": "davies_sym"}):
        figure.savefig(buffer, format=form, dpi=110, metadata=metadata)
    return buffer.getvalue()


def label(module: ModuleType, name: str) -> str:
    """An axis label: the parameter's name, meaning and unit (from ``PARAMETERS``)."""
    for p in module.PARAMETERS:
        if p["name"] == name:
            unit = "" if p["unit"] in ("", "1") else f" [{p['unit']}]"
            return f"{name}: {p['meaning']}{unit}"
    return name


def fixed_text(values: Mapping[str, float], skip: Sequence[str]) -> str:
    """The values held fixed in a figure, wrapped for its title."""
    text = ", ".join(f"{k} = {v:g}" for k, v in sorted(values.items()) if k not in skip)
    return "\n".join(textwrap.wrap(text, 90))


def _variant_numbers(module: ModuleType, kwargs: Mapping[str, Any], input: str, shape: tuple[int, ...]) -> np.ndarray:
    """Number of the variant that holds at each point (0 where none), as the module's own
    selection finds it (turning conditions, then the signs of the loaded forces)."""
    numbers = module.variant(input=input, errors="ignore", **kwargs)
    return np.array(np.broadcast_to(numbers, shape), dtype=np.int64)


def _describe(module: ModuleType, number: int) -> str:
    v = next(v for v in module.VARIANTS if v["number"] == number)
    parts = list(v["conditions"])
    if v["reversed"]:
        parts.append(f"losses reverse {', '.join(v['reversed'])}")
    return f"({number}) " + (", ".join(parts) or "every design")


def shade_regions(axes: Sequence[Any], xs: np.ndarray, numbers: np.ndarray, describe: Callable[[int], str]) -> None:
    """Each stretch of ``xs`` where region ``numbers`` holds shaded in the first of
    ``axes`` (labelled once by ``describe``), the changes marked in all (0: none holds)."""
    colours = ["#dbe9f6", "#fde9d9", "#e2f0d9", "#ede1f5", "#fff2cc", "#d9f2f2", "#f2dcdb", "#e4dfec"]
    edges = [0, *(int(i) + 1 for i in np.nonzero(np.diff(numbers))[0]), len(xs)]
    seen: set[int] = set()
    for a, b in itertools.pairwise(edges):
        n = int(numbers[a])
        if n == 0:
            continue
        axes[0].axvspan(
            xs[a], xs[b - 1], color=colours[(n - 1) % len(colours)], zorder=0, label=None if n in seen else describe(n)
        )
        seen.add(n)
        if a > 0:
            for axis in axes:
                axis.axvline(xs[a], color="grey", linestyle="--", linewidth=1)


@dataclass(frozen=True)
class RegionMap:
    """A grid of two swept parameters (``gx``, ``gy``) with the number of the variant or
    region that holds at each point (NaN: none; ``count`` in all, named by
    ``describe``), the efficiency there and each condition's value."""

    gx: np.ndarray
    gy: np.ndarray
    numbers: np.ndarray
    eta: np.ndarray
    count: int
    conditions: Mapping[str, np.ndarray]
    describe: Callable[[int], str]


def map_regions(axis: Any, grid: RegionMap, blank: str, legend_below: bool = False) -> None:
    """Regions coloured by number (NaN blank, labelled ``blank``), efficiency contours in
    percent, each condition's zero curve in red, and a legend of the regions present."""
    gx, gy, numbers, eta, count = grid.gx, grid.gy, grid.numbers, grid.eta, grid.count
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    palette = [
        "#9ecae1",
        "#fdae6b",
        "#a1d99b",
        "#bcbddc",
        "#f7b6d2",
        "#dbdb8d",
        "#c49c94",
        "#c7c7c7",
        "#6baed6",
        "#fd8d3c",
        "#74c476",
        "#9e9ac8",
        "#e377c2",
        "#bcbd22",
        "#8c6d31",
        "#17becf",
    ]
    colours = [palette[k % len(palette)] for k in range(max(count, 1))]
    axis.pcolormesh(
        gx,
        gy,
        np.ma.masked_invalid(numbers),
        cmap=ListedColormap(colours),
        vmin=0.5,
        vmax=max(count, 1) + 0.5,
        shading="auto",
    )
    finite = eta[np.isfinite(eta)]
    if finite.size and finite.max() > finite.min():
        levels = [
            v for v in (10, 20, 30, 40, 50, 60, 70, 80, 90, 95, 98, 99) if 100 * finite.min() < v < 100 * finite.max()
        ]
        contours = axis.contour(gx, gy, 100 * eta, levels=levels or 8, colors="black", linewidths=0.7)
        axis.clabel(contours, fmt="%.1f %%", fontsize=7)
    for name, level in grid.conditions.items():
        if np.nanmin(level) < 0 < np.nanmax(level):
            curve = axis.contour(gx, gy, level, levels=[0], colors="crimson", linewidths=2)
            axis.clabel(curve, fmt={0.0: f"{name} = 0"}, fontsize=8)
    present = sorted({int(n) for n in numbers[np.isfinite(numbers)]})
    handles = [Patch(color=colours[(n - 1) % len(colours)], label=grid.describe(n)) for n in present]
    handles.append(Patch(facecolor="white", edgecolor="grey", label=blank))
    if legend_below:
        axis.legend(handles=handles, fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncols=2)
    else:
        axis.legend(handles=handles, fontsize=8, loc="best")


def efficiency_panel(
    axes: tuple[Any, Any], xs: np.ndarray, eta: np.ndarray, numbers: np.ndarray, describe: Callable[[int], str]
) -> None:
    """The efficiency curve in percent on the upper of ``axes``, both shaded by the
    variant or region that holds (``numbers``, named by ``describe``)."""
    top, _ = axes
    top.plot(xs, 100 * eta, color="black", linewidth=2, label="efficiency")
    shade_regions(axes, xs, numbers, describe)
    top.set_ylabel("efficiency [%]")
    top.grid(True, alpha=0.3)


def condition_levels(module: ModuleType, kwargs: Mapping[str, Any], shape: tuple[int, ...]) -> dict[str, np.ndarray]:
    """Each turning (or speed) condition of ``module`` on a grid: its zero line bounds the
    variants (or regions)."""
    with np.errstate(all="ignore"):
        return {
            name: np.broadcast_to(function(**{a: kwargs[a] for a in args}), shape)
            for name, (function, args) in module._CONDITIONS.items()
        }


def efficiency_figure(
    variants: VariantSet, sweep: Sweep, values: Mapping[str, float], input: str, module: ModuleType | None = None
) -> Any:
    """Efficiency and stacked losses against one parameter, variant regions marked
    (``module``: the train's compiled `formula_module`, if already at hand)."""
    module = module or formula_module(variants)
    xs = sweep.values(POINTS_1D)
    kwargs: dict[str, Any] = {**values, sweep.name: xs}
    arguments = {k: v for k, v in kwargs.items() if k in {str(s) for s in formula_symbols(variants)}}
    eta = np.broadcast_to(module.efficiency(input=input, errors="ignore", **arguments), xs.shape)
    require_drawn(eta, partial(module.efficiency, input=input), arguments, sweep.name)
    losses = {
        k: np.broadcast_to(v, xs.shape) for k, v in module.losses(input=input, errors="ignore", **arguments).items()
    }
    numbers = _variant_numbers(module, arguments, input, xs.shape)
    figure = new_figure(7.0, 6.0)
    top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=[3, 2])
    efficiency_panel((top, bottom), xs, eta, numbers, lambda n: _describe(module, n))
    top.set_title(f"{variants.train.name}\ninput {input}; {fixed_text(values, [sweep.name])}", fontsize=9)
    top.legend(fontsize=8, loc="best")
    if losses:
        bottom.stackplot(xs, *[100 * v for v in losses.values()], labels=[f"loss in {k}" for k in losses], alpha=0.8)
        bottom.legend(fontsize=8, loc="upper left")
    bottom.set_ylabel("loss [% of input power]")
    bottom.set_xlabel(label(module, sweep.name), fontsize=9)
    bottom.grid(True, alpha=0.3)
    return figure


def region_figure(
    variants: VariantSet, x: Sweep, y: Sweep, values: Mapping[str, float], input: str, module: ModuleType | None = None
) -> Any:
    """Variant regions, turning-condition curves and efficiency contours over two parameters."""
    module = module or formula_module(variants)
    gx, gy = np.meshgrid(x.values(POINTS_2D), y.values(POINTS_2D))
    kwargs: dict[str, Any] = {**values, x.name: gx, y.name: gy}
    arguments = {k: v for k, v in kwargs.items() if k in {str(s) for s in formula_symbols(variants)}}
    eta = np.broadcast_to(module.efficiency(input=input, errors="ignore", **arguments), gx.shape)
    require_drawn(eta, partial(module.efficiency, input=input), arguments, f"{x.name} and {y.name}")
    numbers = _variant_numbers(module, arguments, input, gx.shape).astype(float)
    numbers[np.isnan(eta)] = np.nan
    levels = condition_levels(module, kwargs, gx.shape)
    figure = new_figure(7.0, 5.5)
    axis = figure.subplots()
    grid = RegionMap(gx, gy, numbers, eta, len(module.VARIANTS), levels, lambda n: _describe(module, n))
    map_regions(axis, grid, "self-locking or not admissible")
    axis.set_xlabel(label(module, x.name), fontsize=9)
    axis.set_ylabel(label(module, y.name), fontsize=9)
    axis.set_title(
        f"{variants.train.name}: variants, turning conditions (red), efficiency [%]\n"
        f"input {input}; {fixed_text(values, [x.name, y.name])}",
        fontsize=9,
    )
    return figure


def turning_surface_figure(condition: sympy.Expr, x: Sweep, y: Sweep, z: Sweep, title: str) -> Any:
    """The surface condition = 0 over (x, y), solved for z (every real root in z's
    interval), like Laus Fig. 11."""
    symbols = {str(s): s for s in sorted_symbols(condition.free_symbols)}
    zs = symbols[z.name]
    roots = sympy.solve(condition, zs)
    if not roots:
        raise ValueError(f"the condition {condition} does not depend on {z.name}")
    gx, gy = np.meshgrid(x.values(150), y.values(150))
    figure = new_figure(6.5, 5.5)
    axis = figure.add_subplot(projection="3d")
    for root in roots:
        function = sympy.lambdify([symbols[x.name], symbols[y.name]], root, "numpy")
        with np.errstate(all="ignore"):
            value = np.asarray(function(gx.astype(complex), gy.astype(complex)) * np.ones_like(gx), dtype=complex)
        real = np.where(np.abs(value.imag) < 1e-9, value.real, np.nan)
        real[(real < z.start) | (real > z.stop)] = np.nan
        if np.isfinite(real).any():
            axis.plot_surface(gx, gy, real, cmap="viridis", alpha=0.85, linewidth=0)
    axis.set_xlabel(x.name)
    axis.set_ylabel(y.name)
    axis.set_zlabel(z.name)
    axis.set_zlim(z.start, z.stop)
    axis.set_title(title, fontsize=9)
    return figure
