"""The engine against the independent oracle (tests/oracle/balance.py) on seeded random
planar trains, in several spellings of the topology language.

Each test is one family x spelling: every train of it (every state, both input
directions) must derive and give the oracle's speed ratio and efficiency to a relative
1e-9 (self-locking: the oracle's efficiency <= 0 and the engine's too).  Groups that fail
today would be marked ``xfail(strict=True)`` with the cause found (a fix turns them into
XPASS, which strict mode reports).  ``python3 tests/oracle/measure.py
N`` prints the per-case table.  No expected value here comes from the engine.
"""

from __future__ import annotations

import pytest
from oracle.compare import LOCKING, OK, compare
from oracle.random_trains import FAMILIES, SPELLINGS, generate, spelling

#: Default run: seed 0 of these groups (whole file well under a minute).
DEFAULT_SEEDS = (0,)
#: Slow run (CI runs it): these seeds of every group; `tests/oracle/measure.py N` runs many more.
SLOW_SEEDS = (1, 2)
#: The Ravigneaux set takes seconds per state: only some spellings by default.
DEFAULT_SPELLINGS = {"ravigneaux": ("numeric",), "simpson": ("catalog", "minimal", "reversed", "renamed")}

#: (family, spelling) -> cause, for groups that fail today (none: the layout is solved from
#: the topology, whatever the order of entries, gears or names).
KNOWN_DEFAULT: dict[tuple[str, str], str] = {}
#: The same for the slow seeds.
KNOWN_SLOW: dict[tuple[str, str], str] = {}


def failures(family: str, name: str, seeds: tuple[int, ...]) -> list[str]:
    """Every comparison of the group that is not correct, described."""
    out = []
    for seed in seeds:
        train = generate(family, seed)
        sp = spelling(train, name)
        for o in compare(train, sp):
            if o.kind not in (OK, LOCKING):
                values = (
                    ""
                    if o.engine is None
                    else f": engine {o.engine} ({float(o.engine):.10g}), "
                    f"oracle {o.oracle} ({float(o.oracle) if o.oracle is not None else None})"
                )
                out.append(f"{o.case}: {o.kind} {o.detail}{values}")
    return out


def applicable(family: str, name: str) -> bool:
    train = generate(family, 0)
    return not (name == "brake" and (train.held is None or train.states))


def groups(known: dict[tuple[str, str], str], default: bool) -> list[object]:
    out = []
    for family in FAMILIES:
        for name in SPELLINGS:
            if not applicable(family, name):
                continue
            if default and family in DEFAULT_SPELLINGS and name not in DEFAULT_SPELLINGS[family]:
                continue
            marks = [pytest.mark.xfail(strict=True, reason=known[(family, name)])] if (family, name) in known else []
            out.append(pytest.param(family, name, marks=marks, id=f"{family}-{name}"))
    return out


@pytest.mark.parametrize(("family", "name"), groups(KNOWN_DEFAULT, default=True))
def test_engine_matches_oracle(family: str, name: str) -> None:
    bad = failures(family, name, DEFAULT_SEEDS)
    assert not bad, "\n".join(bad)


@pytest.mark.slow
@pytest.mark.parametrize(("family", "name"), groups(KNOWN_SLOW, default=False))
def test_engine_matches_oracle_many(family: str, name: str) -> None:
    bad = failures(family, name, SLOW_SEEDS)
    assert not bad, f"{len(bad)} failures:\n" + "\n".join(bad[:40])


def test_published_tuplin_through_the_adapter() -> None:
    """The catalog's Tuplin train through the adapter against the published Laus values
    (section 3.4.1.6: 0.9462 with A as input, 0.9443 with B) - a check of the adapter."""
    from fractions import Fraction as F

    from oracle.engine_adapter import engine_efficiency

    from conftest import catalog_path, read_text

    values = {"r1": F(40), "r2": F(60), "r3": F(15), "r4": F(35), "eta_C": F(99, 100), "eta_D": F(99, 100)}
    text = read_text(catalog_path("tuplin"))
    assert round(float(engine_efficiency(text, values, "A")), 4) == 0.9462
    assert round(float(engine_efficiency(text, values, "B")), 4) == 0.9443
