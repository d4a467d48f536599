"""Tooth numbers at which a train locks although its reduced speed ratio stays finite.

tests/data/three_sun_relay.yaml: three suns, relay planets on one axis and a compound
planet on another, sun_b held.  Its reduced speed ratio, -za (zb - zc) / (zc (za - zb)),
does not read the compound planet's teeth wa, but where wa = za the compound planet's
step copies sun_a and the train does not move from its input.  Whether a design locks is
decided independently by the numeric mobility check (the nullity of M_N with the numbers
written into the file, `davies_sym.network.mobility`); the API (``design_point``), the
generated Python module and the C program must refuse exactly those designs, with the
same reason, and accept the others alike.
"""

from __future__ import annotations

import ctypes
import inspect
import random
import re
import shutil
import subprocess
import warnings
from pathlib import Path

import numpy as np
import pytest
import sympy

from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.emit.derived_result import OneInputResult
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.languages import emit_code
from davies_sym.emit.python_module import python_module
from davies_sym.errors import InputError, NotCoveredError
from davies_sym.synthesis.best_design import best_design_text
from davies_sym.topology.loader import load, loads

FILE = Path(__file__).parent / "data" / "three_sun_relay.yaml"
STATE = "b_held"


def _teeth(za: int, zb: int, zc: int, ya: int, wa: int) -> dict[str, int]:
    """Every tooth number from the five free ones (the distances between the axes agree)."""
    yb, yc = ya + za - zb, ya + za - zc
    return {
        "za": za,
        "zb": zb,
        "zc": zc,
        "ya": ya,
        "wa": wa,
        "yb": yb,
        "yc": yc,
        "wb": wa - za + zb,
        "wc": wa - za + zc,
    }


def _designs(count: int, seed: int) -> list[dict[str, int]]:
    """Designs with every tooth number at least 12, a third of them with wa = za."""
    rng = random.Random(seed)
    out: list[dict[str, int]] = []
    while len(out) < count:
        za, zb, zc, ya = (rng.randint(14, 40) for _ in range(4))
        wa = za if len(out) % 3 == 0 else rng.randint(14, 40)
        teeth = _teeth(za, zb, zc, ya, wa)
        if min(teeth.values()) >= 12 and len({za, zb, zc}) == 3:
            out.append(teeth)
    return out


def _numeric_train_moves(teeth: dict[str, int]) -> bool:
    """The numeric route: the file with the numbers written in, loaded and its motions
    solved; False where the mobility check finds the input cannot move."""
    text = best_design_text(FILE.read_text(), teeth, "the three-sun relay with numbers")
    try:
        derive_variants(loads(text), state=STATE, inputs=["in_shaft"])
    except InputError as exc:
        assert "cannot move: the train is locked" in str(exc)
        # Sun and compound planet are on two axes: no ring written as external is hinted at.
        assert "internal: true" not in str(exc)
        return False
    return True


@pytest.fixture(scope="module")
def variants() -> VariantSet:
    return derive_variants(load(str(FILE)), state=STATE)


def _free(teeth: dict[str, int]) -> dict[str, int]:
    return {k: teeth[k] for k in ("za", "zb", "zc", "ya", "wa")}


def test_the_api_refuses_where_the_numeric_mobility_check_finds_the_train_locked(variants: VariantSet) -> None:
    """At 24 designs (8 with wa = za) the API refuses with "the train locks" exactly where
    the numbers written into the file give a train whose input cannot move."""
    seen = {True: 0, False: 0}
    for teeth in _designs(24, seed=3):
        moves = _numeric_train_moves(teeth)
        seen[moves] += 1
        try:
            variants.design_point(_free(teeth))
            refused = ""
        except NotCoveredError as exc:
            refused = str(exc)
        assert ("the train locks" in refused) == (not moves), (teeth, refused)
        assert (teeth["wa"] == teeth["za"]) == (not moves)
    assert seen[True] >= 8 and seen[False] >= 8


def test_the_python_module_gives_nan_with_the_reason_where_the_api_refuses(variants: VariantSet) -> None:
    """The generated module's efficiency is NaN, counted among the designs where a port
    does not turn, exactly where the API refuses for the locking; elsewhere it equals the
    API's efficiency or is NaN where the API refuses for another reason."""
    module = compiled_module(python_module(variants), "three_sun_relay")
    designs = _designs(30, seed=5)
    accepted = inspect.signature(module.efficiency).parameters
    arrays = {k: np.array([float(d[k]) for d in designs]) for k in _free(designs[0]) if k in accepted}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        eta = module.efficiency(**arrays)
    locked = [d["wa"] == d["za"] for d in designs]
    message = " ".join(str(w.message) for w in caught)
    assert re.search(
        rf"\b{sum(locked)} where a port does not turn \(speed ratio 0 or infinite, or the train locks", message
    )
    for design, value, lock in zip(designs, eta, locked, strict=True):
        try:
            exact = float(variants.design_point(_free(design)).efficiency)
        except NotCoveredError as exc:
            assert np.isnan(value) and (("the train locks" in str(exc)) == lock)
            continue
        assert not lock and value == pytest.approx(exact, rel=1e-12)


@pytest.mark.skipif(shutil.which("cc") is None, reason="no C compiler")
def test_the_c_program_says_a_port_does_not_turn_where_the_train_locks(variants: VariantSet, tmp_path: Path) -> None:
    """``reason_from_in_shaft`` of the compiled C program is 4 (a port does not turn, the
    train locks) exactly where the API refuses for the locking, and its efficiency NaN."""
    source = tmp_path / "relay.c"
    source.write_text(emit_code(OneInputResult(load(str(FILE)), ((STATE, variants),), STATE), "c"))
    library = tmp_path / "relay.so"
    built = subprocess.run(
        ["cc", "-std=c99", "-O1", "-shared", "-fPIC", "-o", str(library), str(source), "-lm"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert built.returncode == 0, built.stderr
    compiled = ctypes.CDLL(str(library))
    reason, efficiency = compiled.reason_from_in_shaft, compiled.efficiency_from_in_shaft
    names = ("wa", "za", "zb", "zc")
    for function in (reason, efficiency):
        function.argtypes, function.restype = [ctypes.c_double] * len(names), ctypes.c_double
    assert "reason_from_in_shaft(wa, za, zb, zc)" in source.read_text()
    for design in _designs(15, seed=7):
        values = [float(design[n]) for n in names]
        lock = design["wa"] == design["za"]
        assert (reason(*values) == 4) == lock, design
        if lock:
            assert np.isnan(efficiency(*values))


def test_the_reduced_ratio_cancels_the_locking_factor(variants: VariantSet) -> None:
    """Willis by hand, relative to the arm (sun_b held, so sun_b turns at -w_arm there):
    the twin turns at (za/wa) times sun_a, (zb/wb) times sun_b and (zc/wc) times sun_c, so
    w_sc / w_sa = za (zc wb - wc zb) / (zc (za wb - wa zb)); with wb = wa - za + zb and
    wc = wa - za + zc both brackets carry (wa - za), which cancels:
    -za (zb - zc) / (zc (za - zb)).  No check of the reduced ratio can see the locking."""
    ratio = variants.analysis.speed_ratio().to_expr()
    by_name = {str(s): s for s in ratio.free_symbols}
    assert set(by_name) == {"za", "zb", "zc"}
    za, zb, zc = (by_name[n] for n in ("za", "zb", "zc"))
    assert sympy.cancel(ratio + za * (zb - zc) / (zc * (za - zb))) == 0
