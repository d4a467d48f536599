"""One name, one symbol: the polynomial ring refuses two symbols that share a name but
not their assumptions, and nothing that reaches an output depends on the hash order of
a set of symbols (a derivation gives the same document under any PYTHONHASHSEED)."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
import sympy

from davies_sym.algebra.polynomials import PolynomialRing
from davies_sym.algebra.symbol_order import sorted_symbols, symbol_key
from davies_sym.errors import DerivationError

from conftest import ROOT, catalog_path

R_POSITIVE = sympy.Symbol("r", positive=True)
R_REAL = sympy.Symbol("r", real=True)
Q = sympy.Symbol("q", positive=True)


def test_ring_refuses_one_name_with_two_sets_of_assumptions() -> None:
    for symbols in ([R_POSITIVE, R_REAL, Q], [R_REAL, Q, R_POSITIVE], {R_POSITIVE, R_REAL, Q}):
        with pytest.raises(DerivationError) as info:
            PolynomialRing(symbols)
        message = str(info.value)
        assert message.startswith("symbol r exists with two sets of assumptions")
        # Both sets, in the order of symbol_key whichever order the ring met them in.
        positive, real_only = message.split(": ", 1)[1].split(") and (")
        assert "positive" in positive
        assert "real" in real_only and "positive" not in real_only


def test_ring_is_the_same_for_any_order_of_its_symbols() -> None:
    orders = ([R_POSITIVE, Q], [Q, R_POSITIVE, Q], {Q, R_POSITIVE})
    assert {PolynomialRing(s).symbols for s in orders} == {(Q, R_POSITIVE)}


def test_sorted_by_name_then_assumptions() -> None:
    # Same name: the sorted facts decide ("extended_negative": False comes before "extended_real").
    assert symbol_key(R_POSITIVE) < symbol_key(R_REAL)
    assert sorted_symbols({R_REAL, Q, R_POSITIVE}) == sorted_symbols([R_REAL, R_POSITIVE, Q]) == [Q, R_POSITIVE, R_REAL]


_DOCUMENT = """
import json, sys
import davies_sym
from davies_sym.efficiency.variants import derive_variants
from davies_sym.emit.json_document import train_document
from davies_sym.emit.variant_report import variants_document
v = derive_variants(davies_sym.load(sys.argv[1]))
print(json.dumps([train_document(v.analysis), variants_document(v)], default=str))
"""


@pytest.mark.slow
@pytest.mark.parametrize("name", ["tuplin", "planetary_simple"])
def test_derivation_does_not_depend_on_the_hash_seed(name: str) -> None:
    outputs = set()
    for seed in ("1", "2", "3"):
        result = subprocess.run(
            [sys.executable, "-c", _DOCUMENT, catalog_path(name)],
            cwd=ROOT,
            check=True,
            capture_output=True,
            text=True,
            env={**os.environ, "PYTHONHASHSEED": seed},
        )
        outputs.add(result.stdout)
    assert len(outputs) == 1
