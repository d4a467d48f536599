"""A refusal says what to write instead (docs/errors.md): the names the file defines for
an unknown one, `internal: true` for a ring written as an external gear, quotes for a
value cut at a comma, the bearing's own `axis:` entry where it puts two meshing links on
one axis, the free tooth numbers of a search without `independent:`.  Each train is the
README's planetary with one mistake, answered with exit 2 and one located line."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from harness.helpers import run_main

from conftest import ROOT


def _planetary() -> str:
    """The planetary of the README, as a newcomer copies it."""
    with open(f"{ROOT}/README.md", encoding="utf-8") as handle:
        found = re.search(r"```yaml\n(name: Planetary reduction.*?)```", handle.read(), re.S)
    assert found is not None
    return found.group(1)


MISTAKES = {
    "unknown link": (
        ("links: [c, p]}", "links: [c, q]}"),
        "couplings.D.links[1]: unknown link 'q' (the links are '0', 's', 'p', 'c')",
    ),
    "unknown gear": (
        ("gears: [S, P]", "gears: [S, Pl]"),
        "couplings.SP.gears: unknown gear 'Pl' (did you mean 'P'? the gears are 'S', 'P', 'R')",
    ),
    "ring written external": (
        (", internal: true", ""),
        "ports.input: the input coupling 'A' cannot move: the train is locked; gear 'P' meshes 'S' and 'R', both "
        "external: if one is a ring gear (an annulus), write `internal: true` on it",
    ),
    "comma in a value": (
        ("c: {description: carrier (output)}", "c: {description: front carrier, rear annulus}"),
        "links.c.rear annulus: unknown key 'rear annulus' (known: description); a comma ends a value inside "
        '{...}: quote it, description: "front carrier, rear annulus"',
    ),
    "axis on a third link": (
        ("D: {type: revolute, links: [c, p]}", "D: {type: revolute, links: [c, p], axis: s}"),
        "couplings.D.axis: `axis: s` puts links 's' and 'p' on one axis, so their mesh 'SP' cannot turn; `axis:` "
        "names the link whose axis the bearing is on: write `axis: p` for a planet on its pin, or leave `axis:` out",
    ),
}


@pytest.mark.parametrize("name", sorted(MISTAKES))
def test_a_mistake_is_answered_with_what_to_write(tmp_path: Path, name: str) -> None:
    (old, new), said = MISTAKES[name]
    text = _planetary()
    assert old in text
    path = tmp_path / "planetary.yaml"
    path.write_text(text.replace(old, new, 1))
    result = run_main([path, "--quiet"])
    assert result.returncode == 2, result.describe()
    (line,) = result.stderr.splitlines()
    assert re.match(rf"[a-z]+ error: {re.escape(str(path))}:\d+: ", line), line
    assert line.endswith(said), line


def test_a_search_without_independent_searches_the_free_tooth_numbers(tmp_path: Path) -> None:
    """Without `independent:` the geometry leaves zs and zp free (zr = zs + 2 zp), so the search
    takes ranges for them; ratio 1 + zr/zs = 4 holds exactly where zp = zs.  Symbolic mesh
    efficiencies are refused at the entry that writes them."""
    path = tmp_path / "planetary.yaml"
    path.write_text(_planetary())
    symbolic = run_main(["search", path, "--target", "4", "--teeth", "zs=18:24", "zp=18:24", "--quiet"])
    assert symbolic.returncode == 2, symbolic.describe()
    assert re.search(
        r"planetary.yaml:\d+: couplings\.\w+\.efficiency: the efficiency needs eta_PR, eta_SP", symbolic.stderr
    )
    path.write_text(
        _planetary().replace("efficiency: eta_SP", "efficiency: 0.98").replace("efficiency: eta_PR", "efficiency: 0.99")
    )
    result = run_main(
        ["search", path, "--target", "4", "--tolerance", "0", "--teeth", "zs=18:24", "zp=18:24", "--quiet"]
    )
    assert result.returncode == 0, result.describe()
    designs = re.findall(r"zs=(\d+) zp=(\d+) zr=(\d+)", result.stdout)
    assert designs and all(zs == zp and int(zr) == 3 * int(zs) for zs, zp, zr in designs), result.stdout
    assert "7 feasible design(s)" in result.stdout, result.stdout
