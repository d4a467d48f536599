"""The power curves of a machine's task (Laus Figs. 22 and 24): the power each driving
port supplies, their total, and the power the loaded ports take, against time."""

from __future__ import annotations

from davies_sym.emit.plots import figure_bytes, new_figure
from davies_sym.machines.machine_model import Machine
from davies_sym.machines.task import TaskResult


def task_figure(machine: Machine, result: TaskResult, suffix: str) -> bytes:
    """The figure as bytes in the format of ``suffix`` (``.png``, ``.svg``, ``.pdf``)."""
    times = [s.time for s in result.steps]
    figure = new_figure()
    axes = figure.add_subplot()
    for port in result.drivers:
        axes.plot(times, [s.port_power[port] for s in result.steps], linewidth=1.0, label=f"{port}")
    axes.plot(
        times,
        [sum(s.port_power[p] for p in result.drivers) for s in result.steps],
        linewidth=2.0,
        color="black",
        label="supplied, total",
    )
    for port in result.loads:
        axes.plot(times, [-s.port_power[port] for s in result.steps], linestyle="--", label=f"{port} (taken, -P)")
    axes.axhline(0.0, color="grey", linewidth=0.5)
    axes.set_xlabel("time (s)")
    axes.set_ylabel("power (W)")
    summary = (
        f"efficiency {result.efficiency:.4f}"
        if result.delivered != 0
        else f"closed path, {sum(result.lost.values()):.0f} J lost"
    )
    axes.set_title(f"{machine.name}: task {result.task}, {summary}")
    axes.legend(loc="best", fontsize="small")
    return figure_bytes(figure, suffix)
