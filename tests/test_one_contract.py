"""One contract for every entry point: the same designs accepted or refused, with the same reason.

For every catalog train with one input (every state of the multi-speed sets) the same
designs go through ``derive --eval`` (in-process), the Python API
(`VariantSet.design_point` and `VariantSet.evaluate`, with names and with symbols as keys),
Chen's virtual-power balance (`virtual_power_balance`, where it applies: parallel or
intersecting axes, ordinary efficiencies) and the generated formula module
(``derivations/``, ``errors="raise"``):

- the published design;
- the same design with every mesh efficiency low (self-locking for some trains and ports,
  working for others: the entry points must agree either way);
- a design exactly on each turning condition (the condition's first symbol solved for,
  the other values the published ones);
- a design exactly on the self-locking limit of each variant (its locking expression
  solved for a length, the efficiencies rational): the exact entry points refuse it as
  self-locking ("0 exactly"); the module, in floating point, gives NaN or a value within
  rounding of 0;
- inadmissible designs: a mesh efficiency of 3/2, a length of 0.

Agreement: an accepted design has one exact efficiency (CLI's exact value, API, balance)
and the module's float within 1e-12; a refused one is refused by every entry point, the
CLI's message is the API's message, the exit status is 2 for bad values and 3 for a design
the formulas do not cover, and the module gives NaN and raises its DesignError.  The
other languages are held to the module by tests/test_other_languages.py (NaN at the same
points).
"""

from __future__ import annotations

import importlib.util
import json
import warnings
from pathlib import Path
from types import ModuleType

import pytest
import sympy
from harness.helpers import run_main

import davies_sym
from davies_sym.efficiency.parameter_domain import ParameterDomain, efficiency_symbols
from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.efficiency.virtual_power_balance import virtual_power_balance
from davies_sym.errors import DaviesError, InputError, NotCoveredError
from davies_sym.losses.definitions import completed
from davies_sym.topology.checks import mesh_efficiency_symbols
from davies_sym.topology.states import train_in_state

from conftest import CATALOG, ROOT, TRAIN_FILES

#: Several inputs (its own contract: tests/test_several_inputs.py).
SEVERAL_INPUTS = {"sr20_differential"}
#: Chen's balance takes parallel or intersecting axes and ordinary efficiencies, of gear
#: pairs with bearings and lossless sliders (not a rack in its pressed guide).
NO_BALANCE = {"crossed_helical", "worm_drive", "worm_planetary", "buckingham_pair", "rack_pinion", "bicycle_hub"}


def _cases() -> list[tuple[str, str | None]]:
    out = []
    for path in TRAIN_FILES:
        stem = Path(path).stem
        if stem in SEVERAL_INPUTS:
            continue
        train = davies_sym.load(path)
        out += [(stem, s.name) for s in train.states] or [(stem, None)]
    return out


CASES = _cases()


def _module(stem: str) -> ModuleType:
    path = Path(ROOT) / "derivations" / f"{stem}.py"
    spec = importlib.util.spec_from_file_location(f"contract_{stem}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _exact(text: str) -> sympy.Expr:
    from davies_sym.topology.expressions import parse_expression

    return parse_expression(str(text))


def _drawn(vs: VariantSet) -> dict[sympy.Symbol, sympy.Expr]:
    """An admissible geometry drawn exactly (the same at every call: a fixed seed)."""
    return dict(next(iter(ParameterDomain.of(vs.train, vs.analysis.network.layout).samples(1, seed=3))))


def _designs(vs: VariantSet, train: davies_sym.Train, state: str | None) -> list[tuple[str, dict[str, sympy.Expr]]]:
    names = {str(s) for s in vs.parameters}
    published = {k: _exact(v) for k, v in train.published_design(state).items() if k in names}
    if not published:  # a file without a published design: an admissible one drawn exactly
        point = _drawn(vs)
        published = {str(k): v for k, v in point.items() if str(k) in names}
        published |= {str(e): sympy.Rational(97, 100) for e in efficiency_symbols(vs.train) if str(e) in names}
    assert set(published) == names, f"the design lacks {names - set(published)}"
    etas = sorted(str(e) for e in mesh_efficiency_symbols(vs.train.couplings) if str(e) in names)
    lengths = sorted(n for n in names if vs.train.symbols[n].is_positive and n not in etas)
    out = [("published", published)]
    if etas:
        out.append(("low efficiencies", {**published, **{e: sympy.Rational(3, 10) for e in etas}}))
        out.append(("efficiency above one", {**published, etas[0]: sympy.Rational(3, 2)}))
    if lengths:
        out.append(("a length of zero", {**published, lengths[0]: sympy.Integer(0)}))
    symbols = {str(s): s for s in vs.parameters}
    at = completed({symbols[k]: v for k, v in published.items()}, vs.train.definitions)
    for c in vs.conditions:
        for s in sorted(c.expression.free_symbols, key=str):
            roots = [
                r for r in sympy.solve(c.expression.subs({k: v for k, v in at.items() if k != s}), s) if r.is_positive
            ]
            if roots and roots[0].is_number:
                out.append((f"on condition {c.name}", {**published, str(s): roots[0]}))
                break
    for v in vs.variants:
        locking = v.locking_expression
        if locking is None or not locking.free_symbols:
            continue
        for s in sorted(locking.free_symbols, key=str):
            if str(s) not in lengths or sympy.degree(locking, s) != 1:
                continue
            root = sympy.solve(locking.subs({k: w for k, w in at.items() if k != s}), s)
            if root and root[0].is_number and root[0].is_positive:
                out.append(
                    (
                        f"on the self-locking limit of variant ({v.number}), input {v.input}",
                        {**published, str(s): root[0]},
                    )
                )
                break
    return out


def _same(a: sympy.Expr, b: sympy.Expr) -> bool:
    """One number, however written: exactly for rationals, to 45 digits for closed forms
    with logarithms (a tooth-geometry efficiency), which no finite procedure compares."""
    if a.is_Rational and b.is_Rational:
        return bool(a == b)
    return bool(abs(sympy.N(a - b, 60)) < sympy.Float(10) ** -45)


def _module_reason(refusal: DaviesError) -> str:
    """The words of a module's refusal that name the API's reason (its count is 1)."""
    text = str(refusal)
    if isinstance(refusal, InputError):
        return "1 design point(s) outside the admissible parameters"
    if "does not turn" in text:
        return "1 where a port does not turn"
    if "self-locks" in text:
        return "1 where the train self-locks"
    assert "no variant's power flow agrees with its own forces" in text, text
    return "1 where no variant's power flow agrees with its own forces"


def _cli(path: str, state: str | None, port: str, values: dict[str, sympy.Expr]) -> tuple[int, str, dict]:
    pairs = [f"{k}={sympy.sstr(v)}" for k, v in values.items()]
    args = [path, "--quiet", "--json", "--input", port, *(["--state", state] if state else []), "--eval", *pairs]
    result = run_main(args, timeout=600)
    assert result.returncode in (0, 2, 3), result.describe()
    assert "Traceback" not in result.stderr, result.describe()
    return result.returncode, result.stderr, json.loads(result.stdout) if result.stdout.strip() else {}


@pytest.mark.slow
@pytest.mark.parametrize(("stem", "state"), CASES, ids=[f"{s}[{t}]" if t else s for s, t in CASES])
def test_every_entry_point_accepts_and_refuses_the_same_designs(stem: str, state: str | None) -> None:
    path = str(Path(CATALOG) / f"{stem}.yaml")
    whole = davies_sym.load(path)
    train = train_in_state(whole, next(s for s in whole.states if s.name == state)) if state else whole
    vs = derive_variants(train)
    module = _module(f"{stem}_{state}" if state else stem)
    designs = _designs(vs, whole, state)
    # The balance's geometry may need a radius the formulas do not (a planet's): the published one.
    dependent = {str(r.symbol) for r in vs.train.dependent or ()}
    layout_values = {
        k: _exact(v) for k, v in whole.published_design(state).items() if k in vs.train.symbols and k not in dependent
    } or {str(k): v for k, v in _drawn(vs).items() if str(k) not in dependent}
    # An idle mesh of this state still has a row in the balance: its efficiency, any value.
    layout_values |= {str(e): sympy.Rational(97, 100) for e in mesh_efficiency_symbols(vs.train.couplings)}
    for label, values in designs:
        keyed = {vs.train.symbols[k]: v for k, v in values.items()}
        floats = {k: float(v) for k, v in values.items()}
        for port in (vs.train.ports.input, vs.train.ports.output):
            where = f"{stem} {state or ''} {label}, input {port}: {values}"
            status, stderr, document = _cli(path, state, port, values)
            try:
                point = vs.design_point(values, port)
            except DaviesError as exc:
                refusal: DaviesError | None = exc
            else:
                refusal = None
            # Names and symbols as keys: the same answer.
            try:
                same = vs.evaluate(keyed, port)
            except DaviesError as exc:
                assert refusal is not None and str(exc) == str(refusal), where
            else:
                assert refusal is None and _same(same, point.efficiency), where
            balance: object = None
            if stem not in NO_BALANCE:
                try:
                    given = {**{k: v for k, v in layout_values.items() if k not in values}, **values}
                    balance = virtual_power_balance(vs.train, given, port).efficiency
                except DaviesError as exc:
                    balance = exc
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                quiet = float(module.efficiency(input=port, errors="ignore", **floats))
            if refusal is None:
                assert status == 0, f"{where}: the CLI refuses ({stderr.strip()}) what the API accepts"
                assert _same(sympy.sympify(document["efficiency_exact"]), point.efficiency), where
                assert 0 < point.efficiency <= 1, where
                if balance is not None:
                    assert balance == point.efficiency, f"{where}: balance {balance}"
                assert quiet == pytest.approx(float(point.efficiency), rel=1e-12), where
                continue
            # Refused: by every entry point, with the same reason and the right status.
            expected_status = 2 if isinstance(refusal, InputError) else 3
            assert status == expected_status, f"{where}: CLI exit {status}, API {type(refusal).__name__}: {refusal}"
            said = stderr + str(document.get("reason", ""))  # --json puts a refusal's reason in the document
            assert str(refusal).split(": ")[-1] in said, f"{where}: CLI says {said!r}, API {refusal}"
            if balance is not None:
                assert isinstance(balance, DaviesError), f"{where}: balance gives {balance}, API refuses: {refusal}"
                if isinstance(refusal, NotCoveredError) and "self-locks" in str(refusal):
                    assert "self-locks" in str(balance), f"{where}: {balance}"
            if label.startswith("on the self-locking limit"):
                # Floats cannot sit on the limit: NaN, or a value within rounding of it.
                assert quiet != quiet or abs(quiet) < 1e-12, f"{where}: module gives {quiet}"
                continue
            assert quiet != quiet, f"{where}: the module gives {quiet} where the API refuses: {refusal}"
            with pytest.raises(module.DesignError) as raised:
                module.efficiency(input=port, errors="raise", **floats)
            said = str(raised.value)
            assert _module_reason(refusal) in said, f"{where}: module says {said}, API {refusal}"
