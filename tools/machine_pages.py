"""The documentation page of a catalog machine (Laus ch. 4): its couplings, the closed
forms per friction mode with their regions and the cycle efficiencies, or its tasks'
energies and power curves."""

from __future__ import annotations

from collections.abc import Callable

from docs_pages import math

from davies_sym.emit.machine_plots import task_figure
from davies_sym.errors import NotCoveredError
from davies_sym.machines.closed_form import derive_closed_forms
from davies_sym.machines.cycle import cycle_efficiency
from davies_sym.machines.machine_model import Machine
from davies_sym.machines.task import run_task
from davies_sym.topology.symbol_display import latex, mathml_body

Write = Callable[[str, bytes], None]


def _escape(text: str) -> str:
    return text.replace("|", "\\|").replace("*", "\\*").replace("_", "\\_")


def _eta(expr, label: str) -> str:  # type: ignore[no-untyped-def]
    lhs = "<mi>&#951;</mi><mo>=</mo>"
    return math(lhs + mathml_body(expr), f"\\eta = {latex(expr)}", display=True) + f"\n\n{label}\n"


def machine_page(machine: Machine, stem: str, write: Write) -> str:
    lines = [
        f"# {machine.name}",
        "",
        f"Source: {_escape(machine.source or 'not given')}.",
        "",
        f"Machine file: `catalog/{stem}.yaml`; derivation: `derivations/{stem}.txt` (`derive catalog/{stem}.yaml`).",
        "",
        "| coupling | kind | between | friction |",
        "| --- | --- | --- | --- |",
    ]
    for c in machine.couplings:
        friction = "" if c.friction is None else f"Coulomb, load by {c.friction.load}"
        lines.append(f"| {c.name} | {c.kind.replace('_', ' ')} | {' — '.join(c.links)} | {friction} |")
    lines.append("")
    try:
        forms = derive_closed_forms(machine)
    except NotCoveredError as exc:
        forms = None
        lines += [f"No closed form: {_escape(str(exc))}.", ""]
    if forms is not None:
        sample = machine.sample()
        for direction in forms.directions:
            lines += [f"## Input {direction.input}, output {direction.output}", ""]
            for variant in direction.variants:
                signs = ", ".join(f"{s} = {v:+d}" for s, v in variant.signs)
                where = " and ".join(
                    math(f"{mathml_body(c)}<mo>&gt;</mo><mn>0</mn>", f"{latex(c)} > 0") for c in variant.conditions
                )
                lines.append(_eta(variant.efficiency, f"Friction mode {_escape(signs)}, where {where}."))
            if machine.cycle is not None:
                cycle = cycle_efficiency(direction, machine.cycle, sample)
                if cycle.closed is not None:
                    eq = "Laus eq. (120)" if cycle.steady_is_input else "Laus eq. (123)"
                    lines.append(_eta(cycle.closed, f"Over one cycle, the power of {cycle.steady} constant ({eq})."))
    if machine.tasks:
        lines += ["## Tasks", "", "| task | supplied (J) | delivered (J) | lost (J) | task efficiency |"]
        lines.append("| --- | --- | --- | --- | --- |")
        figures = []
        for name in machine.tasks:
            result = run_task(machine, name)
            lost = sum(result.lost.values())
            lines.append(
                f"| {name} | {result.supplied:.2f} | {result.delivered:.2f} | {lost:.2f} | {result.efficiency:.4f} |"
            )
            write(f"catalog/img/{stem}_{name}.png", task_figure(machine, result, ".png"))
            figures.append(f"![{stem}: powers of task {name}](img/{stem}_{name}.png)")
        lines += ["", *(f"{f}\n" for f in figures)]
    for check in machine.expected:
        lines.append(f"Published: {check.quantity} {check.value} ({_escape(check.source)}).\n")
    return "\n".join(lines).rstrip("\n") + "\n"
