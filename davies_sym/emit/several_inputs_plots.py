"""Figures of a train driven on several shafts (``derive FILE --plot NAME=START:STOP
[--vs NAME2=...]`` when the file lists several input ports).

- Over two parameters, typically the two input speeds: the power-flow regions, the speed
  conditions (lines through the origin) and efficiency contours; blank where the
  formulas do not hold (on a condition line, or where the losses exceed the load).
- Against one parameter, e.g. one input speed with the other fixed: the efficiency with
  the regions shaded, and below it the torque at every port.

The numbers come from the train's generated formula module, compiled in memory, so a
figure shows what design code gets.
"""

from __future__ import annotations

from collections.abc import Mapping
from types import ModuleType
from typing import Any

import numpy as np

from davies_sym.efficiency.several_inputs import SeveralInputs
from davies_sym.emit.plots import (
    POINTS_1D,
    POINTS_2D,
    RegionMap,
    Sweep,
    condition_levels,
    efficiency_panel,
    fixed_text,
    label,
    map_regions,
    new_figure,
    require_drawn,
)
from davies_sym.emit.several_inputs_module import several_inputs_formulas


def _describe(module: ModuleType, number: int) -> str:
    region = next(r for r in module.REGIONS if r["number"] == number)
    text = f"({number}) in at {', '.join(region['power_in'])}, out at {', '.join(region['power_out'])}"
    return text + (f"; losses reverse {', '.join(region['reversed'])}" if region["reversed"] else "")


def _conditions_text(module: ModuleType) -> str:
    return "; ".join(f"{name} = {text}" for name, (text, _) in module.CONDITIONS.items())


def several_region_figure(
    si: SeveralInputs, x: Sweep, y: Sweep, values: Mapping[str, float], module: ModuleType | None = None
) -> Any:
    """Regions, speed conditions (red) and efficiency contours over two parameters."""
    module = module or several_inputs_formulas(si)
    gx, gy = np.meshgrid(x.values(POINTS_2D), y.values(POINTS_2D))
    kwargs: dict[str, Any] = {**values, x.name: gx, y.name: gy}
    required = [p["name"] for p in module.PARAMETERS]
    eta = np.broadcast_to(module.efficiency(errors="ignore", **{k: kwargs[k] for k in required}), gx.shape)
    require_drawn(eta, module.efficiency, {k: kwargs[k] for k in required}, f"{x.name} and {y.name}")
    numbers = np.broadcast_to(module.region(**{k: kwargs[k] for k in required}), gx.shape).astype(float)
    numbers[np.isnan(eta)] = np.nan
    levels = condition_levels(module, kwargs, gx.shape)
    figure = new_figure(7.5, 7.5)
    axis = figure.subplots()
    grid = RegionMap(gx, gy, numbers, eta, len(module.REGIONS), levels, lambda n: _describe(module, n))
    map_regions(axis, grid, "not covered: a condition line, or losses larger than the load", legend_below=True)
    axis.set_xlabel(label(module, x.name), fontsize=9)
    axis.set_ylabel(label(module, y.name), fontsize=9)
    axis.set_title(
        f"{si.train.name}\npower-flow regions, speed conditions (red: {_conditions_text(module)}), "
        f"efficiency [%]\n{fixed_text(values, [x.name, y.name])}",
        fontsize=9,
        wrap=True,
    )
    return figure


def several_efficiency_figure(
    si: SeveralInputs, sweep: Sweep, values: Mapping[str, float], module: ModuleType | None = None
) -> Any:
    """Efficiency (regions shaded) and every port's torque against one parameter."""
    module = module or several_inputs_formulas(si)
    xs = sweep.values(POINTS_1D)
    kwargs: dict[str, Any] = {**values, sweep.name: xs}
    required = {k: kwargs[k] for k in (p["name"] for p in module.PARAMETERS)}
    eta = np.broadcast_to(module.efficiency(errors="ignore", **required), xs.shape)
    require_drawn(eta, module.efficiency, required, sweep.name)
    torques = {k: np.broadcast_to(v, xs.shape) for k, v in module.torques(errors="ignore", **required).items()}
    numbers = np.broadcast_to(module.region(**required), xs.shape)
    figure = new_figure(7.5, 6.5)
    top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=[3, 2])
    efficiency_panel((top, bottom), xs, eta, numbers, lambda n: _describe(module, n))
    top.set_title(f"{si.train.name}\n{fixed_text(values, [sweep.name])}", fontsize=9)
    top.legend(fontsize=7, loc="lower center", bbox_to_anchor=(0.5, 1.12), ncols=2)
    for port, torque in torques.items():
        bottom.plot(xs, torque, label=f"torque at {port}")
    bottom.legend(fontsize=8, loc="best")
    bottom.set_ylabel("torque applied at the port")
    bottom.set_xlabel(label(module, sweep.name), fontsize=9)
    bottom.grid(True, alpha=0.3)
    return figure
