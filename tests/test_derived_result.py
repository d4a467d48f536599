"""One result protocol (`DerivedResult`): a train driven at one port and one driven at
several give the command line every output through the same calls, so ``derive FILE``
prints what the result gives, byte for byte, for both kinds."""

from __future__ import annotations

from pathlib import Path

import pytest
from harness.helpers import run_main

from davies_sym.efficiency.several_inputs import derive_several_inputs
from davies_sym.efficiency.variants import derive_variants
from davies_sym.emit.derived_result import DerivedResult, OneInputResult, SeveralInputResult
from davies_sym.emit.languages import emit_code
from davies_sym.topology.loader import load

from conftest import ROOT as ROOT_TEXT

ROOT = Path(ROOT_TEXT)

# A planetary of my own spelling: ring on the frame, sun in, carrier out.
PLANETARY = """\
name: sun in, carrier out
links: [housing, s, p, k]
gears:
  sun: {link: s, radius: rs}
  planet: {link: p, radius: rp}
  ring: {link: housing, radius: rr, internal: true}
couplings:
  bs: {type: revolute, links: [housing, s]}
  bk: {type: revolute, links: [housing, k]}
  bp: {type: revolute, links: [k, p]}
  m1: {type: mesh, gears: [sun, planet], efficiency: e1}
  m2: {type: mesh, gears: [planet, ring], efficiency: e2}
ports: {input: bs, output: bk}
"""


def _one_input(tmp_path: Path) -> tuple[str, DerivedResult]:
    path = tmp_path / "planetary.yaml"
    path.write_text(PLANETARY, encoding="utf-8")
    train = load(str(path))
    return str(path), OneInputResult(train, (("", derive_variants(train)),))


def _several_inputs(tmp_path: Path) -> tuple[str, DerivedResult]:
    path = str(ROOT / "catalog" / "sr20_differential.yaml")
    return path, SeveralInputResult(derive_several_inputs(load(path)))


@pytest.mark.parametrize("make", [_one_input, _several_inputs], ids=["one input", "several inputs"])
def test_the_command_prints_what_the_result_gives(make, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    path, result = make(tmp_path)
    for options, expected in (
        ([], result.report(False)),
        (["--json"], result.report(True)),
        (["--latex"], result.latex()),
        (["--emit", "c"], emit_code(result, "c")),
    ):
        answer = run_main([path, "--quiet", *options])
        assert answer.returncode == 0 and answer.stdout == expected, (options, answer.stderr)
    module = tmp_path / "formulas.py"
    assert run_main([path, "--quiet", "--python", str(module)]).returncode == 0
    assert module.read_text(encoding="utf-8") == result.module()
    names = [name for name, _ in result.derivations("t")]
    assert names == ["t.tex", "t.py"]


def test_a_state_is_named_in_the_program_and_the_derivations_hold_every_state() -> None:
    from davies_sym.cli.one_input_outputs import derive_sets

    train = load(str(ROOT / "catalog" / "simpson.yaml"))
    sets = tuple(derive_sets(train, None, lambda _: None, []))
    every = OneInputResult(train, sets)
    assert [name for name, _ in every.derivations("simpson")] == ["simpson.tex"] + [
        f"simpson_{st.name}.py" for st in train.states
    ]
    chosen = OneInputResult(train, sets[1:2], sets[1][0])
    assert chosen.train.ports.input == train.states[1].input
    assert f"from simpson.yaml (state {sets[1][0]})" in emit_code(chosen, "c")
