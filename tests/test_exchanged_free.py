"""A null space solved with another column free and read back in the wanted one
(`davies_sym.algebra.exchanged_free`), against the elimination that keeps the wanted
column free itself: exactly the same solution on random systems, with and without a
column of constants; and whole derivations whose every null space is forced onto the
other port's variable print the same document as the ordinary route."""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest
from test_factored_elimination import _system

import davies_sym
from davies_sym.algebra.exchanged_free import exchanged
from davies_sym.algebra.linalg import WorkExceeded, gauss_jordan
from davies_sym.cli.command import main
from davies_sym.network import null_space as null_space_module

CATALOG = Path(davies_sym.__file__).parent.parent / "catalog"


def _with_constants(seed: int):
    """A random system with one more column, the constants (free, as D_A's sources)."""
    ring, rows, n = _system(seed)
    rng = random.Random(1000 + seed)
    for row in rows:
        if rng.random() < 0.5:
            row[n] = ring.one * rng.choice([-2, 1, 3])
    return ring, rows, n + 1


@pytest.mark.parametrize("constants", [False, True])
@pytest.mark.parametrize("seed", range(40))
def test_the_exchanged_solution_is_the_direct_one(seed: int, constants: bool) -> None:
    ring, rows, n = _with_constants(seed) if constants else _system(seed)
    late = [n - 1] if constants else []
    direct = gauss_jordan([dict(r) for r in rows], n, prefer_free=[0, *late])
    if direct.free != (0, *late):
        pytest.skip("the system does not leave the wanted column free alone")
    taken = next((c for c in range(1, n - len(late)) if c not in direct.free), None)
    other = gauss_jordan([dict(r) for r in rows], n, prefer_free=[taken, *late])
    found = exchanged(other, ring, 0, taken, late)
    if found is None:
        # The taken column does not stand free with the constants alone, or the wanted
        # one does not move with it: nothing to exchange, as the direct route says.
        assert set(other.free) - {taken} != set(late) or direct.solution(ring)[taken].get(0) is None
        return
    assert found.free == direct.free
    assert set(found.pivots) == set(direct.pivots)
    expected, got = direct.solution(ring), found.solution(ring)
    for col in range(n):
        assert got[col] == expected[col], col


def _document(path: Path) -> dict[str, object]:
    from contextlib import redirect_stdout
    from io import StringIO

    out = StringIO()
    with redirect_stdout(out):
        assert main([str(path), "--json", "--quiet"]) == 0
    return json.loads(out.getvalue())


@pytest.mark.parametrize("name", ["ravigneaux", "wolfrom", "planetary_simple"])
def test_every_null_space_solved_with_the_other_port_free_derives_alike(name: str, monkeypatch) -> None:
    """The first route of every null space made to swell: each is solved with the output
    port's variable free and exchanged, and the whole document (speed ratios, variants,
    conditions) is the same as the ordinary route's, which keeps the input free."""
    path = CATALOG / f"{name}.yaml"
    ordinary = _document(path)
    real = null_space_module._null_space
    swelled: list[int] = []

    def first_route_swells(network, ring, matrix, prefer, columns, laws, bounded):
        if bounded and id(matrix) not in swelled:
            swelled.append(id(matrix))
            raise WorkExceeded("made to swell")
        return real(network, ring, matrix, prefer, columns, laws, bounded)

    monkeypatch.setattr(null_space_module, "_null_space", first_route_swells)
    assert _document(path) == ordinary
    assert swelled  # the exchange was taken


def _every_route_swells(monkeypatch) -> None:
    """Every elimination over square roots swells past its bound at its first step."""
    monkeypatch.setattr(null_space_module, "RADICAL_WORK", 0)
    monkeypatch.setattr(null_space_module, "ROUTE_WORK", 0)
    monkeypatch.setattr(null_space_module, "REDUCED_ROUTE_WORK", 0)


def test_a_state_whose_every_route_swells_is_refused_with_the_reason(monkeypatch, capsys) -> None:
    """Exit status 3 and a line naming the null space and the state, never a traceback
    nor minutes of work (the Ravigneaux set's 2-D drawing has square roots)."""
    _every_route_swells(monkeypatch)
    status = main([str(CATALOG / "ravigneaux.yaml"), "--quiet"])
    out, err = capsys.readouterr()
    # The states drawn without square roots derive; those with them say why, each.
    assert status == 3
    assert "swells past" in err and "with the input's variable free and with the output's" in err
    assert "(state " in err and "Traceback" not in out + err


def test_an_atlas_train_whose_motions_swell_is_listed_with_the_reason(monkeypatch) -> None:
    """The atlas keeps such a train, not drawn, with the reason in its JSON entry (not
    silently short of the choices whose motions could not be read)."""
    from davies_sym.atlas.atlas_entries import entry, places

    place = next(p for p in places(6) if (p.rotation, p.index) == (10, 6))  # drawn in 2-D
    assert entry(place).planar
    _every_route_swells(monkeypatch)
    found = entry(place)
    assert found.choices == () and found.not_drawable is not None
    assert "swells past" in found.not_drawable
    assert found.document()["not_drawable"] == found.not_drawable
