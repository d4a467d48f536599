"""Generated Python module of a train driven on several shafts (``derive FILE --python
OUT`` when the file lists several input ports).

The module depends on numpy only.  Its entry points take the input speeds
``omega_<port>`` (signed, rad/s), the load torque ``tau_out`` (the magnitude of the
torque resisting the output's motion) and the loss and geometry parameters, as scalars
or arrays broadcast together:

- ``efficiency(errors=..., **params)``: Mantriota and Pennestri's eq. (6), the region
  picked element by element from the signs of the speed conditions;
- ``torques(...)``: the torque the outside applies at every port, by name;
- ``speeds(...)``: the speed of every port; ``region(...)``: the number of the region
  that holds (0 where none does);
- ``PARAMETERS``, ``SPEEDS``, ``CONDITIONS`` and ``REGIONS`` (where each holds, which
  gears drive, where power goes in and out, formula as text and LaTeX).

Like `davies_sym.emit.python_module` it is built as a syntax tree around a
hand-written runtime (`davies_sym.emit.several_inputs_runtime`), and the same train
gives the same bytes.
"""

from __future__ import annotations

import ast
import os
from collections.abc import Sequence
from types import ModuleType

import sympy

from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.parameter_ranges import Parameter
from davies_sym.efficiency.parameters import given_forms
from davies_sym.efficiency.several_inputs import LOAD_TORQUE, Region, SeveralInputs
from davies_sym.emit import several_inputs_runtime
from davies_sym.emit.code_layout import docstring, keyword_function, literal
from davies_sym.emit.formula_code import (
    NOT_A_PARAMETER,
    FormulaTables,
    call,
    compiled_module,
    constant,
    module_text,
    name_node,
    refused_name,
    runtime_of,
    usable,
)
from davies_sym.emit.several_inputs_report import condition_text, mesh_text, region_force_text
from davies_sym.losses.definitions import parameters_of
from davies_sym.topology.symbol_display import latex as display_latex

#: The entry points' own names and arguments: a train's names may not take them.
_ENTRY_NAMES = frozenset({"errors", "values", "xp", "efficiency", "torques", "speeds", "region"})


def _entry(
    name: str, doc: str, required: Sequence[str], returns: str, returned: ast.expr, errors: bool = True
) -> ast.FunctionDef:
    """``name(*, [errors='warn',] required...)`` with the arguments as arrays in ``values``."""
    params = [ast.arg("errors", name_node("str"))] if errors else []
    defaults: list[ast.expr | None] = [ast.Constant("warn")] if errors else []
    params += [ast.arg(a, name_node("ArrayLike")) for a in required]
    defaults += [None] * len(required)
    # The library of the arrays given (numpy unless another's arrays are among them).
    xp = name_node("xp")
    values = ast.Dict([ast.Constant(a) for a in required], [call("_array", name_node(a), xp) for a in required])
    body: list[ast.stmt] = [
        docstring(doc, "    "),
        ast.Assign([ast.Name("xp", ast.Store())], call("_namespace", *(name_node(a) for a in required))),
        ast.AnnAssign(
            ast.Name("values", ast.Store()), ast.parse("dict[str, Array]", mode="eval").body, values, simple=1
        ),
        ast.Return(returned),
    ]
    return keyword_function(name, params, defaults, body, ast.parse(returns, mode="eval").body)


def _code(si: SeveralInputs, region: Region) -> int:
    """Bit k set where speed condition k is negative (what the runtime's ``_codes`` gives)."""
    return sum(1 << k for k, c in enumerate(si.conditions) if region.signs[c.name] < 0)


def several_inputs_module(si: SeveralInputs) -> str:
    """Source text of the module of ``si``."""
    train = si.train
    runtime = runtime_of(several_inputs_runtime, _ENTRY_NAMES)
    formulas = FormulaTables.named("_CONDITIONS", "_SPEEDS", "_EFFICIENCY", "_TORQUES", "_FORCES")
    speed_args, every = _add_formulas(formulas, si)
    condition_args = {a for _, _, args in formulas.tables["_CONDITIONS"] for a in args}
    required = [str(s) for s in sorted_symbols({sympy.Symbol(a) for a in every | condition_args | speed_args})]
    symbols = {
        str(s): s
        for s in (
            *si.speeds,
            LOAD_TORQUE,
            *train.symbols.values(),
            *parameters_of(set(train.symbols.values()), train.definitions),
        )
    }
    for a in required:
        if not usable(runtime, a) or a.startswith("_"):
            raise refused_name(train, "symbol", a, NOT_A_PARAMETER)
    data = _data(si, si.parameter_table([symbols[a] for a in required]))
    constants = [constant(runtime, n, literal(v)) for n, v in data.items()]
    entries = _entries(required, sorted(speed_args, key=required.index))
    return module_text(runtime, _module_doc(si), constants, formulas, entries, train)


def _add_formulas(formulas: FormulaTables, si: SeveralInputs) -> tuple[set[str], set[str]]:
    """The speed conditions, the port speeds and each region's efficiency, torques and
    loaded forces; the arguments of the speeds, and of the regions' formulas."""
    public, ports = given_forms(si), si.train.ports
    for c in si.conditions:
        formulas.add(
            "_CONDITIONS",
            c.name,
            f"condition_{c.name}",
            f"Speed condition {c.name}: {sympy.sstr(c.form)} ({'; '.join(c.decides)}).",
            [public(c.form)],
        )
    speed_args: set[str] = set()
    for p, v in si.port_speeds.items():
        speed_args |= set(formulas.add("_SPEEDS", p, f"_speed_{p}", f"Speed of port {p}.", [public(v.to_expr())]))
    every: set[str] = set()
    for r in si.regions:
        name = f"region_{r.number}"
        where = " and ".join(condition_text(si, r))
        doc = (
            f"Efficiency in region ({r.number}), where {where}: power in at {', '.join(r.inputs)}, out at "
            f"{', '.join(r.outputs)}; " + "; ".join(mesh_text(si, r)) + "."
        )
        every |= set(formulas.add("_EFFICIENCY", name, name, doc, [public(r.efficiency)]))
        every |= set(
            formulas.add(
                "_TORQUES",
                name,
                f"_torques_{r.number}",
                f"Torque at {', '.join(ports.every)} in region ({r.number}).",
                [public(r.torques[p].to_expr()) for p in ports.every],
                "tuple[Array, ...]",
            )
        )
        forces = [public(f.to_expr() * assumed) for f, assumed in r.loaded_forces.values()]
        if forces:
            every |= set(
                formulas.add(
                    "_FORCES",
                    name,
                    f"_forces_{r.number}",
                    f"Tooth forces and loaded reactions of {', '.join(r.loaded_forces)} in region "
                    f"({r.number}) times the sign it assumes: the region holds where all are positive.",
                    forces,
                    "tuple[Array, ...]" if len(forces) > 1 else "Array",
                )
            )
    return speed_args, every


def _data(si: SeveralInputs, parameters: Sequence[Parameter]) -> dict[str, object]:
    """The module's constants: ports, parameters, speeds, conditions and regions."""
    public, ports = given_forms(si), si.train.ports
    return {
        "INPUTS": tuple(ports.inputs),
        "OUTPUT": ports.output,
        "PORTS": tuple(ports.every),
        "PARAMETERS": tuple(
            {
                "name": p.name,
                "meaning": p.meaning,
                "unit": p.unit,
                "low": p.low,
                "high": p.high,
                "closed_low": p.closed_low,
            }
            for p in parameters
        ),
        "SPEEDS": {p: sympy.sstr(public(v.to_expr())) for p, v in si.port_speeds.items()},
        "CONDITIONS": {c.name: (sympy.sstr(c.form), display_latex(c.form)) for c in si.conditions},
        "REGIONS": tuple(
            {
                "name": f"region_{r.number}",
                "number": r.number,
                "code": _code(si, r),
                "conditions": tuple(condition_text(si, r)),
                "meshes": tuple(mesh_text(si, r)),
                "power_in": tuple(r.inputs),
                "power_out": tuple(r.outputs),
                "reversed": tuple(sorted(r.reversed)),
                "forces": tuple(region_force_text(r)),
                "formula": sympy.sstr(public(r.efficiency)),
                "latex": display_latex(public(r.efficiency)),
            }
            for r in si.regions
        ),
    }


def _entries(required: Sequence[str], speed_args: Sequence[str]) -> list[ast.FunctionDef]:
    """The module's entry points, taking the parameters ``required`` (``speeds``: only
    the input speeds ``speed_args`` it needs)."""
    values = (name_node("errors"), name_node("values"), name_node("xp"))
    return [
        _entry(
            "efficiency",
            "Mantriota and Pennestri's efficiency (eq. (6)): the output's power over the sum of "
            "the input shafts' powers, the region chosen element by element; NaN where the formulas do not hold "
            "(errors: 'warn', 'raise', 'ignore').",
            required,
            "Array",
            call("_efficiency", *values),
        ),
        _entry(
            "torques",
            "The torque the outside applies at each port (by name), the region chosen element by "
            "element; NaN where efficiency is.",
            required,
            "dict[str, Array]",
            call("_torques", *values),
        ),
        _entry(
            "speeds",
            "The speed of every port (by name) in the input speeds.",
            speed_args,
            "dict[str, Array]",
            call("_speeds", name_node("values"), name_node("xp")),
            errors=False,
        ),
        _entry(
            "region",
            "The number of the power-flow region (REGIONS) that holds at each point; 0 where none does "
            "(on a speed-condition line, or no region's loaded forces agree), -1 where several do.",
            required,
            "NDArray[np.int64]",
            call("_region_numbers", name_node("values"), name_node("xp")),
            errors=False,
        ),
    ]


def _module_doc(si: SeveralInputs) -> str:
    train, ports = si.train, si.train.ports
    origin = os.path.basename(train.path) if train.path else "a topology file"
    return "\n".join(
        [
            f"Efficiency of {train.name}, driven at {', '.join(ports.inputs)}: every power-flow region.",
            "",
            f"Source: {train.source or 'not given'}.",
            f"Generated by davies_sym from {origin}; do not edit.",
            "",
            f"Input speeds {', '.join(str(s) for s in si.speeds)} (signed, rad/s), load torque {LOAD_TORQUE} at "
            f"{ports.output} (magnitude, resisting its motion).  efficiency(**params) and torques(**params) take the "
            "parameters of PARAMETERS (scalars or numpy arrays, broadcast together), pick the region element by "
            "element from the speed conditions, and give NaN with a DesignWarning (errors='raise': a DesignError) "
            "where the formulas do not hold.",
        ]
    )


def several_inputs_formulas(si: SeveralInputs) -> ModuleType:
    """The generated module of ``si``, compiled in memory (figures and calibration use
    the numbers design code gets)."""
    return compiled_module(several_inputs_module(si), si.train.name)
