"""Generated Python module of a train's efficiency (``derive FILE --python OUT``).

The module depends on numpy alone and is meant for design code (sweeps, optimisers); its
functions take the arrays of any array API library (CuPy, JAX, ...) too:

- ``efficiency(input=..., errors=..., **params)`` on scalars or arrays (broadcast
  together) picks the variant element by element from the turning conditions, and gives
  NaN with a warning (or raises, ``errors='raise'``) where the design lies outside the
  admissible parameters or the train self-locks (efficiency outside (0, 1]);
- one function per variant named by its ports and condition signs, one per turning
  condition, ``speed_ratio`` and ``losses`` (power lost in each friction element over the
  input power, adding up to 1 - efficiency);
- ``PARAMETERS`` (name, meaning, unit, admissible range), ``RELATIONS`` (expressions
  positive on an admissible design), ``CONDITIONS`` and ``VARIANTS`` (conditions and
  formula as text and as LaTeX), ``EXCLUDED`` (the region codes, as ``VARIANTS`` gives
  them, that no admissible design reaches: a point there is not admissible), the source
  in the module docstring.

The module is built as a syntax tree: the hand-written part is
`davies_sym.emit.formula_runtime` (copied as it is), the train's tables are
literals and its formulas are the code printer's output split into short common
subexpressions (sympy ``cse``), laid out by `davies_sym.emit.code_layout`, which
checks that the text parses back to the same tree.  Names that become identifiers are
checked here; every other text the user wrote is a string literal.  The same train gives
the same bytes.
"""

from __future__ import annotations

import ast
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import sympy

from davies_sym.algebra.polynomials import RationalFunction
from davies_sym.efficiency.parameters import (
    admissible_relations,
    eliminated_symbols,
    given_forms,
    given_parameters,
    parameter_table,
)
from davies_sym.efficiency.power_losses import all_loss_fractions, lossy_couplings
from davies_sym.efficiency.variant_result import ExcludedVariant, Variant
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit import formula_code, formula_runtime
from davies_sym.emit.code_layout import docstring, keyword_function, literal
from davies_sym.emit.force_conditions import force_text
from davies_sym.emit.formula_code import (
    NOT_A_PARAMETER,
    FormulaTables,
    call,
    constant,
    module_text,
    name_node,
    refused_name,
    runtime_of,
    usable,
)
from davies_sym.emit.variant_report import condition_text, mesh_text, variant_forces
from davies_sym.network.motion_singularities import vanishing_denominators
from davies_sym.topology.symbol_display import latex as display_latex

#: The entry points' own arguments: a train's names may not take them.
_ENTRY_NAMES = frozenset(
    {"input", "errors", "values", "xp", "wrt", "efficiency", "losses", "sensitivity", "speed_ratio", "variant"}
)


def _runtime() -> formula_code.Runtime:
    return runtime_of(formula_runtime, _ENTRY_NAMES)


def _constant(name: str, value: ast.expr) -> ast.AnnAssign:
    return constant(_runtime(), name, value)


def _usable(name: str) -> bool:
    return usable(_runtime(), name)


@dataclass(frozen=True)
class _Arguments:
    """The arguments of a module's entry points: every parameter the file gives
    (``every``), those the formulas take (``formulas``) and the speed ratio's
    (``ratio``), the arguments of each dependent parameter's formula, and the input
    port a call without ``input`` has."""

    every: tuple[str, ...]
    formulas: tuple[str, ...]
    ratio: tuple[str, ...]
    dependent: Mapping[str, tuple[str, ...]]
    default_input: str


def _entry_point(
    name: str, doc: str, required: Sequence[str], returns: str, returned: ast.expr, arguments: _Arguments
) -> ast.FunctionDef:
    """``name(*, input, errors, required..., optional=None...)``: the required arguments
    as arrays, the given dependent parameters checked against their relations, the other
    optional ones accepted (held to their ranges where the train takes them); returns
    ``returned``."""
    checked = [d for d, args in arguments.dependent.items() if set(args) <= set(required)]
    optional = [a for a in arguments.every if a not in required]
    # A parameter of the train this entry does not need is still held to its range when given.
    ranged = [a for a in optional if a in arguments.formulas or a in arguments.ratio]
    params = [ast.arg("input", name_node("str")), ast.arg("errors", name_node("str"))]
    defaults: list[ast.expr | None] = [ast.Constant(arguments.default_input), ast.Constant("warn")]
    if any(isinstance(n, ast.Name) and n.id == "wrt" for n in ast.walk(returned)):
        params.insert(0, ast.arg("wrt", name_node("str")))  # what the derivative is taken in
        defaults.insert(0, None)
    params += [ast.arg(a, name_node("ArrayLike")) for a in required]
    defaults += [None] * len(required)
    maybe = ast.BinOp(name_node("ArrayLike"), ast.BitOr(), ast.Constant(None))
    params += [ast.arg(a, maybe) for a in optional]
    defaults += [ast.Constant(None) for _ in optional]
    # The library of the arrays given (numpy unless another's arrays are among them).
    xp = name_node("xp")
    namespace = call("_namespace", *(name_node(a) for a in [*required, *optional]))
    values = ast.Dict([ast.Constant(a) for a in required], [call("_array", name_node(a), xp) for a in required])
    body: list[ast.stmt] = [
        docstring(doc, "    "),
        ast.Assign([ast.Name("xp", ast.Store())], namespace),
        ast.AnnAssign(
            ast.Name("values", ast.Store()), ast.parse("dict[str, Array]", mode="eval").body, values, simple=1
        ),
    ]
    if checked:
        given = ast.Dict([ast.Constant(a) for a in checked], [name_node(a) for a in checked])
        body.append(ast.Expr(call("_consistent", given, name_node("values"), xp)))
    if ranged:
        # Given optional parameters join the values, so that the admissibility check sees them.
        given = ast.Dict([ast.Constant(a) for a in ranged], [name_node(a) for a in ranged])
        update = ast.Attribute(name_node("values"), "update", ast.Load())
        body.append(ast.Expr(ast.Call(update, [call("_given", given, xp)], [])))
    body.append(ast.Return(returned))
    return keyword_function(name, params, defaults, body, ast.parse(returns, mode="eval").body)


def _where(variants: VariantSet, variant: Variant) -> str:
    conditions = condition_text(variants, variant)
    return f"input {variant.input}, output {variant.output}" + (
        f", where {' and '.join(conditions)}" if conditions else ""
    )


def _region(variants: VariantSet, variant: Variant | ExcludedVariant) -> int:
    """Bit k set where condition k is negative (the code ``_region`` computes)."""
    return sum(1 << k for k, c in enumerate(variants.conditions) if variant.signs[c.name] < 0)


def _module_doc(variants: VariantSet, ignored: Sequence[str]) -> str:
    train = variants.train
    origin = os.path.basename(train.path) if train.path else "a topology file"
    parts = [
        f"Efficiency of {train.name}: every turning-condition variant.",
        "",
        f"Source: {train.source or 'not given'}.",
        f"Generated by davies_sym from {origin}; do not edit.",
        "",
    ]
    eliminated = eliminated_symbols(variants)
    if eliminated:
        given = ", ".join(f"{k} = {sympy.sstr(v)}" for k, v in sorted(eliminated.items(), key=lambda kv: str(kv[0])))
        parts += [f"The geometric constraints give {given}; the formulas use the other parameters.", ""]
    if ignored:
        parts += [
            f"This state does not use {', '.join(ignored)}: the functions accept them (as every state of the "
            "file does) and ignore them (IGNORED).",
            "",
        ]
    parts.append(
        "efficiency(**params) takes the parameters of PARAMETERS (scalars or numpy arrays, broadcast "
        "together), picks the variant element by element from the turning conditions, the input "
        "port and the signs of the loaded forces, and gives NaN with a DesignWarning (errors='raise': a "
        "DesignError) where the design is outside the admissible parameters, a port does not turn, no "
        "variant's power flow agrees with its own forces, or the train self-locks.  speed_ratio, losses "
        "and variant work the same way."
    )
    return "\n".join(parts)


def _tables(
    variants: VariantSet,
    lossy: Sequence[str],
    ignored: Sequence[str],
    relations: Sequence[sympy.Expr],
    sensitive: Sequence[str],
) -> list[ast.stmt]:
    """The public tables: ports, losses, parameters, relations, conditions, variants."""
    train = variants.train
    parameters = tuple(
        {"name": p.name, "meaning": p.meaning, "unit": p.unit, "low": p.low, "high": p.high, "closed_low": p.closed_low}
        for p in parameter_table(variants)
    )
    variant_rows = []
    for v in variants.variants:
        latex = tuple(
            f"{display_latex(c.simplified)} {'>' if v.signs[c.name] > 0 else '<'} 0" for c in variants.conditions
        )
        variant_rows.append(
            {
                "name": v.name,
                "number": v.number,
                "input": v.input,
                "output": v.output,
                "region": _region(variants, v),
                "conditions": tuple(condition_text(variants, v)),
                "conditions_latex": latex,
                "meshes": tuple(mesh_text(variants, v)),
                "formula": sympy.sstr(v.efficiency),
                "latex": display_latex(v.efficiency),
                "feasible": v.feasible,
                "reversed": tuple(sorted(v.reversed_forces)),
                "forces": tuple(force_text(variant_forces(variants, v))),
            }
        )
    data: dict[str, object] = {
        "PORTS": (train.ports.input, train.ports.output),
        "LOSSY": tuple(lossy),
        "SENSITIVE": tuple(sensitive),
        "PARAMETERS": parameters,
        "IGNORED": tuple(ignored),
        "RELATIONS": tuple(f"{sympy.sstr(r)} > 0" for r in relations),
        "DEPENDENT": {str(r.symbol): str(r) for r in train.dependent or ()},
        "CONDITIONS": {c.name: (sympy.sstr(c.simplified), display_latex(c.simplified)) for c in variants.conditions},
        "EXCLUDED": tuple(sorted({_region(variants, v) for v in variants.excluded})),
        "VARIANTS": tuple(variant_rows),
    }
    return [_constant(name, literal(value)) for name, value in data.items()]


def python_module(variants: VariantSet, accepted: Sequence[str] = (), scoring: bool = False) -> str:
    """Source text of the module.  ``accepted``: the parameters of the whole file (every
    state's module takes them all and ignores those its formulas do not use).
    ``scoring``: the module a search compiles in memory to score designs with, never
    written out: its ``efficiency``, ``speed_ratio`` and choice of variant are the full
    module's, line for line, but it has no gradient and no losses (the search reads
    neither, and they are most of the module's writing time)."""
    train = variants.train
    public = given_forms(variants)
    by_name = given_parameters(variants)
    symbols = list(by_name)
    dependent_of = {str(r.symbol): r for r in train.dependent or ()}
    for s in sorted({*symbols, *accepted, *dependent_of}):
        if not _usable(s) or s.startswith("_"):
            raise refused_name(train, "symbol", s, NOT_A_PARAMETER)
    lossy = lossy_couplings(variants)
    formulas = FormulaTables.named(
        "_CONDITIONS", "_RELATIONS", "_DEPENDENT", "_EFFICIENCY", "_LOSSES", "_GRADIENT", "_RATIO", "_MOTION", "_FORCES"
    )
    relations = admissible_relations(variants)
    _add_conditions(formulas, variants, relations)
    fractions = {} if scoring else all_loss_fractions(variants)
    for v in variants.variants:
        _add_variant(formulas, variants, v, by_name, lossy, {} if scoring else fractions[v.name], scoring)
    needs = {}
    for name, r in dependent_of.items():
        needs[name] = formulas.add(
            "_DEPENDENT",
            name,
            f"_dependent_{name}",
            f"{r} (the geometric constraint {r.constraint}).",
            [public(r.expression)],
        )
    ratio = public(variants.analysis.speed_ratio().to_expr())
    port = train.ports.input
    ratio_args = formulas.add("_RATIO", port, "_ratio_formula", f"Speed ratio with {port} as input.", [ratio])
    # Checked where the call gives their arguments (`_locked`), required by no entry point.
    motion_args: set[str] = set()
    for k, factor in enumerate(vanishing_denominators(variants.analysis), start=1):
        text = f"Denominator {sympy.sstr(factor)} of the motions (0: the train locks)."
        motion_args |= set(formulas.add("_MOTION", str(k), f"_motion_denominator_{k}", text, [public(factor)]))
    every = sorted({*symbols, *accepted, *dependent_of, *ratio_args, *motion_args})
    ignored = sorted(set(every) - {*symbols, *ratio_args, *dependent_of, *motion_args})
    given = _Arguments(tuple(every), tuple(symbols), ratio_args, needs, port)
    constants = _tables(variants, lossy, ignored, relations, symbols)
    entries = _entries(given, f"{sympy.sstr(ratio)} with {port} as input")
    return module_text(_runtime(), _module_doc(variants, ignored), constants, formulas, entries, train)


def _add_conditions(formulas: FormulaTables, variants: VariantSet, relations: Sequence[sympy.Expr]) -> None:
    """The turning conditions (Laus Tables 5 and 6) and the admissible relations."""
    public = given_forms(variants)
    for c in variants.conditions:
        formulas.add(
            "_CONDITIONS",
            c.name,
            f"condition_{c.name}",
            f"Turning condition {c.name}: {sympy.sstr(c.simplified)}.",
            [public(c.expression)],
        )
    for k, r in enumerate(relations, start=1):
        formulas.add_relation(
            "_RELATIONS", f"{sympy.sstr(r)} > 0", f"_relation_{k}", f"Whether {sympy.sstr(r)} > 0.", [r]
        )


def _add_variant(
    formulas: FormulaTables,
    variants: VariantSet,
    v: Variant,
    by_name: Mapping[str, sympy.Symbol],
    lossy: Sequence[str],
    fractions: Mapping[str, RationalFunction],
    scoring: bool = False,
) -> None:
    """A variant's efficiency, its gradient, its losses (``fractions`` of the input
    power, by coupling) and its loaded forces (``scoring``: the efficiency and the forces
    that pick the variant alone)."""
    public = given_forms(variants)
    doc = f"Variant ({v.number}): {_where(variants, v)}.  " + "; ".join(mesh_text(variants, v)) + "."
    eta = public(v.efficiency)
    formulas.add("_EFFICIENCY", v.name, v.name, doc, [eta])
    symbols = list(by_name)
    if symbols and not scoring:  # the exact partial derivatives in SENSITIVE's order, sharing their subexpressions
        formulas.add(
            "_GRADIENT",
            v.name,
            f"_gradient_{v.name}",
            f"Partial derivatives of variant ({v.number})'s efficiency in {', '.join(symbols)}.",
            [sympy.diff(eta, by_name[n]) for n in symbols],
            "tuple[Array, ...]" if len(symbols) > 1 else "Array",
        )
    if not scoring:
        formulas.add(
            "_LOSSES",
            v.name,
            f"_losses_{v.name}",
            f"Losses over the input power in variant ({v.number}).",
            [public(fractions[n].to_expr()) for n in lossy],
            "tuple[Array, ...]" if len(lossy) > 1 else "Array",
        )
    forces = [public(f.to_expr() * sign) for f, sign in v.loaded_forces.values()]
    if forces:
        formulas.add(
            "_FORCES",
            v.name,
            f"_forces_{v.name}",
            f"Loaded forces of {', '.join(v.loaded_forces)} in variant "
            f"({v.number}), each times the sign it needs: all >= 0 where the variant holds.",
            forces,
            "tuple[Array, ...]" if len(forces) > 1 else "Array",
        )


def _entries(given: _Arguments, ratio: str) -> list[ast.FunctionDef]:
    """The module's entry points (``ratio``: the speed ratio in words, for its docstring)."""
    arrays = (name_node("input"), name_node("errors"), name_node("values"), name_node("xp"))
    formulas = given.formulas
    return [
        _entry_point(
            "efficiency",
            "Overall efficiency -P_out/P_in with `input` as the input port, the variant chosen "
            "element by element; NaN where the design is not admissible or self-locks (errors: 'warn', 'raise', "
            "'ignore').",
            formulas,
            "Array",
            call("_efficiency", *arrays),
            given,
        ),
        _entry_point(
            "losses",
            "Power lost in each element of LOSSY over the input power (they add up to 1 - efficiency), "
            "the variant chosen element by element; NaN where efficiency is.",
            formulas,
            "dict[str, Array]",
            call("_losses", *arrays),
            given,
        ),
        _entry_point(
            "sensitivity",
            "Partial derivative of the efficiency in the parameter `wrt` (one of SENSITIVE), from the exact "
            "derivative of the variant that holds, element by element; NaN where efficiency is.",
            formulas,
            "Array",
            call("_sensitivity", name_node("wrt"), *arrays),
            given,
        ),
        _entry_point(
            "variant",
            "Number of the variant that holds with `input` as the input port (VARIANTS), element by "
            "element: its turning conditions hold and its loaded forces have their signs; 0 where none does or "
            "the design is not admissible.",
            formulas,
            "NDArray[np.int64]",
            call("_variant", *arrays),
            given,
        ),
        _entry_point(
            "speed_ratio",
            f"Input speed over output speed with `input` as the input port ({ratio}); NaN where the design is "
            "not admissible.",
            given.ratio,
            "Array",
            call("_speed_ratio", *arrays),
            given,
        ),
    ]
