"""Properties of ``derive`` on generated input (Hypothesis).

- Mutated catalog files: Hypothesis takes a catalog train, chooses an entry and a
  mutation (the key deleted, a value of the wrong type, an unknown name or key, a key
  given twice, a huge or negative number, a non-ASCII name, a name that shadows a Python
  or sympy name, an entry renamed everywhere) and runs ``derive FILE --quiet`` in this
  process.  Required: exit 0 with a result, or exit 2 with one line per distinct problem,
  each ``FILE:LINE: ENTRY: message``; never a traceback, never exit 1, the file untouched.
- Valid planar trains built from parts (the generator of tests/oracle/): Hypothesis
  chooses the family, the design (its seed), the spelling (gears of a mesh swapped,
  revolutes reversed, teeth and modules, numbers for symbols, a brake state) and, through
  a random generator it controls, the order of entries and the names.  Required: the
  train derives, and its speed ratio and efficiency in every state and both directions
  agree with the independent oracle (tests/oracle/balance.py).

Examples are drawn by the ``davies`` profile (tests/conftest.py: deterministic); the
functions marked slow draw others, and more (``davies-slow``: a fixed seed).  The last
section keeps the cases the properties found, as plain tests.
"""

from __future__ import annotations

import copy
import re
import tempfile
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest
import yaml
from harness.helpers import CATALOG, Result, assert_refused, rename_everywhere, run_main
from hypothesis import event, given, seed, settings
from hypothesis import strategies as st
from oracle.compare import LOCKING, OK, compare
from oracle.random_trains import generate, spelling

from conftest import SLOW_SEED, TRAIN_FILES

TRAINS = tuple(sorted(Path(p).stem for p in TRAIN_FILES))
#: Trains whose harmless mutations derive for seconds (Humpage 5 s, Ravigneaux 15 s; the worm
#: planetary and SR20 4-9 s for the fast run's few examples): only the slow run mutates them,
#: with this fraction of its examples.
COSTLY = {"humpage": 20, "simpson": 10, "ravigneaux": 50, "worm_planetary": 1, "sr20_differential": 1}
NAMED_TABLES = ("links", "gears", "couplings", "states")

#: Names that Python, sympy or the generated modules give a meaning to.
SHADOWING = (
    "lambda",
    "class",
    "None",
    "True",
    "E",
    "I",
    "pi",
    "N",
    "S",
    "oo",
    "zoo",
    "nan",
    "inf",
    "sqrt",
    "__import__",
    "np",
    "input",
)
NON_ASCII = ("Ωμέγα", "é", "名前", "r¹", "ζ")
#: Values a hand-edited file gets wrong: numbers out of range, text where a number belongs, ...
ODD_VALUES = (
    None,
    True,
    [1, 2],
    {"a": 1},
    7,
    0,
    -5,
    10**400,
    -(10**400),
    1e308,
    -1e-300,
    float("inf"),
    float("nan"),
    "",
    "xyz",
    "1e400",
    "-r1",
    "r1 - r1",
    "1/0",
    "sqrt(2)*r1",
    "-oo",
    "0.0",
)
#: Mutations with one cause, so one line when refused: an unknown key, a key given twice.
ONE_CAUSE = ("unknown_key", "duplicate_key")
#: Keys no entry has (one a near-miss of a real key).
UNKNOWN_KEYS = ("tolerence", "radus", "colour", "Links", "gear", "efficency")

#: ``FILE:LINE: ENTRY: message``, after an optional ``... error: `` prefix.
LINE_SHAPE = r"^(?:[A-Za-z ]+ error: )?{file}:(\d+): (\S.*?): \S"


# --- mutated catalog files ----------------------------------------------------------------------------------


def _paths(data: Any, prefix: tuple[Any, ...] = ()) -> Iterator[tuple[Any, ...]]:
    """The path of every mapping key and list item, depth first."""
    if isinstance(data, dict):
        for key, value in data.items():
            yield (*prefix, key)
            yield from _paths(value, (*prefix, key))
    elif isinstance(data, list):
        for index, value in enumerate(data):
            yield (*prefix, index)
            yield from _paths(value, (*prefix, index))


def _mappings(data: Any, prefix: tuple[Any, ...] = ()) -> Iterator[tuple[Any, ...]]:
    """The path of every mapping (the document itself included)."""
    if isinstance(data, dict):
        yield prefix
    children = data.items() if isinstance(data, dict) else enumerate(data) if isinstance(data, list) else ()
    for key, value in children:
        yield from _mappings(value, (*prefix, key))


def _dump(data: Any) -> str:
    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=100000)


@dataclass(frozen=True)
class Mutation:
    """One change to a train file: ``kind`` at ``path`` (a rename: ``(table, name)``) with ``value``."""

    kind: str
    path: tuple[Any, ...]
    value: Any = None

    def text(self, data: Any) -> str:
        """The YAML text of ``data`` with this change."""
        if self.kind == "duplicate_key":
            return _duplicated_line(_dump(data), self.value)
        out = copy.deepcopy(data)
        if self.kind == "rename":
            table, old = self.path
            return _dump(rename_everywhere(out, table, old, self.value))
        parent = out
        for part in self.path[:-1] if self.kind != "unknown_key" else self.path:
            parent = parent[part]
        if self.kind == "delete":
            del parent[self.path[-1]]
        elif self.kind == "unknown_key":
            parent[self.value] = 1
        else:
            parent[self.path[-1]] = copy.deepcopy(self.value)
        return _dump(out)


def _key_lines(text: str) -> list[int]:
    """Indices of the lines that hold a mapping key of their own (not a list item)."""
    return [i for i, line in enumerate(text.splitlines()) if re.match(r"^\s*[^\s#\-][^:]*:( |$)", line)]


def _duplicated_line(text: str, index: int) -> str:
    """``text`` with its key line ``index`` written twice (a key given twice)."""
    lines = text.splitlines(keepends=True)
    return "".join([*lines[: index + 1], lines[index], *lines[index + 1 :]])


def _scalars(data: Any) -> list[Any]:
    """Every name and number of the file: another link, gear, symbol or size where one belongs."""
    found = {str(p[-1]) for p in _paths(data)}
    found |= {str(v) for v in _leaves(data) if isinstance(v, (str, int)) and len(str(v)) < 20}
    return sorted(found)


def _leaves(data: Any) -> Iterator[Any]:
    children = data.values() if isinstance(data, dict) else data if isinstance(data, list) else None
    if children is None:
        yield data
        return
    for child in children:
        yield from _leaves(child)


def _values(data: Any) -> st.SearchStrategy[Any]:
    names = st.sampled_from(SHADOWING + NON_ASCII)
    numbers = st.one_of(
        st.integers(-100, 1000),
        st.integers(min_value=-(10**500), max_value=10**500),
        st.floats(),
        st.fractions(min_value=-10, max_value=100).map(str),
    )
    return st.one_of(
        st.sampled_from(ODD_VALUES),
        names,
        st.sampled_from(_scalars(data)),
        numbers,
        st.text(max_size=12),
        st.lists(st.integers(-3, 3), max_size=3),
    )


def _new_names() -> st.SearchStrategy[str]:
    return st.one_of(
        st.sampled_from(SHADOWING + NON_ASCII), st.text(alphabet="abcXYZ019_/.+- ", min_size=1, max_size=8)
    )


@st.composite
def mutations(draw: st.DrawFn, data: Any) -> Mutation:
    kind = draw(st.sampled_from(("set", "set", "delete", "unknown_key", "duplicate_key", "rename")))
    if kind == "rename":
        entries = [
            (t, n)
            for t in NAMED_TABLES
            if isinstance(data.get(t), (dict, list))
            for n in data[t]
            if not isinstance(n, (dict, list))
        ]
        return Mutation(kind, draw(st.sampled_from(entries)), draw(_new_names()))
    if kind == "unknown_key":
        return Mutation(kind, draw(st.sampled_from(list(_mappings(data)))), draw(st.sampled_from(UNKNOWN_KEYS)))
    if kind == "duplicate_key":
        return Mutation(kind, (), draw(st.sampled_from(_key_lines(_dump(data)))))
    path = draw(st.sampled_from(list(_paths(data))))
    return Mutation(kind, path, draw(_values(data)) if kind == "set" else None)


def _load(train: str) -> Any:
    with open(CATALOG / f"{train}.yaml", encoding="utf-8") as handle:
        return yaml.safe_load(handle)


def assert_answered_or_refused(result: Result, path: Path, text: str, single: bool = False) -> None:
    """Exit 0 with a result, or exit 2 with one located line per distinct problem (``single``:
    the change has one cause, so one line)."""
    why = f"{result.describe()}\n--- the file ---\n{text[:3000]}"
    assert not result.timed_out, f"no answer in time:\n{why}"
    assert "Traceback" not in result.stderr, f"a traceback:\n{why}"
    assert result.returncode in (0, 2), f"exit {result.returncode}:\n{why}"
    assert path.read_text(encoding="utf-8") == text, "the input file was changed"
    if result.returncode == 0:
        assert result.stdout.strip(), f"exit 0 without a result:\n{why}"
        # A warning says what the file leaves undone (a published check it cannot evaluate)
        # at its line; anything else on a successful run is a stray message.
        warning = re.compile(rf"derive: warning: {re.escape(str(path))}:\d+: ")
        stray = [line for line in result.stderr.splitlines() if line.strip() and not warning.match(line)]
        assert not stray, f"exit 0 with messages:\n{why}"
        return
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    assert lines, f"exit 2 without a message:\n{why}"
    assert len(lines) == len(set(lines)), f"a problem reported twice:\n{why}"
    assert not single or len(lines) == 1, f"{len(lines)} lines for one cause:\n{why}"
    assert len(result.stderr) < 2000, f"{len(result.stderr)} characters of messages:\n{why}"
    shape = re.compile(LINE_SHAPE.format(file=re.escape(str(path))))
    count = len(text.splitlines())
    for line in lines:
        found = shape.match(line)
        assert found, f"a line without FILE:LINE: ENTRY:\n{line}\n{why}"
        assert 1 <= int(found.group(1)) <= count, f"line {found.group(1)} is not a line of the file:\n{why}"


def _seeded(check: Callable[[], None], profile: settings) -> Callable[[], None]:
    """``check`` with the slow tests' fixed seed where ``profile`` is not derandomized: the
    same examples every run, others than the fast test of the same check draws."""
    return check if profile.derandomize else seed(SLOW_SEED)(check)


def _check_mutations(train: str, profile: settings) -> None:
    data = _load(train)
    examples = profile.max_examples // COSTLY.get(train, 1)

    @settings(profile, max_examples=max(examples, 2))
    @given(mutation=mutations(data))
    def check(mutation: Mutation) -> None:
        text = mutation.text(data)
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / f"{train}.yaml"
            path.write_text(text, encoding="utf-8")
            result = run_main([str(path), "--quiet"], timeout=120)
            event(f"{mutation.kind}: exit {result.returncode}")
            assert_answered_or_refused(result, path, text, single=mutation.kind in ONE_CAUSE)

    _seeded(check, profile)()


@pytest.mark.parametrize("train", [t for t in TRAINS if t not in COSTLY])
def test_mutated_catalog_file_is_answered_or_refused(train: str) -> None:
    _check_mutations(train, settings.get_profile("davies"))


@pytest.mark.slow
@pytest.mark.parametrize("train", TRAINS)
def test_mutated_catalog_file_is_answered_or_refused_many(train: str) -> None:
    _check_mutations(train, settings.get_profile("davies-slow"))


# --- valid trains against the oracle ------------------------------------------------------------------------

#: Families whose trains derive in about a second; the slow run adds the 2-D double-pinion set
#: and Simpson's four states (Ravigneaux, 30 s a train, is left to tests/test_seeded_trains_oracle.py).
FAST_FAMILIES = ("pair", "chain", "planetary", "stepped", "wolfrom", "tuplin")
SLOW_FAMILIES = (*FAST_FAMILIES, "double_pinion", "simpson")
#: Parts of a spelling (tests/oracle/random_trains.py): none of them changes the train.
PARTS = ("reversed", "flipped", "shuffled", "renamed", "teeth", "numeric", "minimal", "brake", "placement")


@st.composite
def planar_trains(draw: st.DrawFn, families: tuple[str, ...]) -> tuple[Any, Any]:
    family = draw(st.sampled_from(families))
    train = generate(family, draw(st.integers(min_value=0, max_value=10**6)))
    parts = draw(st.sets(st.sampled_from(PARTS)))
    name = "+".join(sorted(parts)) or "catalog"
    return train, spelling(train, name, draw(st.randoms(use_true_random=False)))


def _check_oracle(families: tuple[str, ...], profile: settings, examples: int) -> None:
    @settings(profile, max_examples=examples)
    @given(case=planar_trains(families))
    def check(case: tuple[Any, Any]) -> None:
        train, sp = case
        event(f"family {train.family}")
        bad = [
            f"{o.case}: {o.kind} {o.detail} engine {o.engine} oracle {o.oracle}"
            for o in compare(train, sp)
            if o.kind not in (OK, LOCKING)
        ]
        assert not bad, "\n".join(bad) + f"\n--- the file ---\n{sp.yaml}"
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / "train.yaml"
            path.write_text(sp.yaml, encoding="utf-8")
            result = run_main([str(path), "--quiet"], timeout=120)
        assert result.returncode == 0 and result.stdout.strip(), f"{result.describe()}\n--- the file ---\n{sp.yaml}"

    _seeded(check, profile)()


def test_planar_trains_derive_and_agree_with_the_oracle() -> None:
    profile = settings.get_profile("davies")
    _check_oracle(FAST_FAMILIES, profile, profile.max_examples)


@pytest.mark.slow
def test_planar_trains_derive_and_agree_with_the_oracle_many() -> None:
    profile = settings.get_profile("davies-slow")
    _check_oracle(SLOW_FAMILIES, profile, profile.max_examples)


# --- what the properties found ------------------------------------------------------------------------------

SIMPLE_PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")
MESH_FRICTION = "friction: {coulomb: zeta_C}"  # line 16 of simple_pair.yaml


def _run(tmp_path: Path, text: str) -> tuple[Result, Path]:
    path = tmp_path / "train.yaml"
    path.write_text(text, encoding="utf-8")
    return run_main([str(path), "--quiet"]), path


@pytest.mark.parametrize(
    ("friction", "entry"),
    [
        ("friction: {coulomb: 7}", "couplings.C.friction.coulomb"),
        ("friction: {coulomb: r1}", "couplings.C.friction.coulomb"),
        ("friction: none", "couplings.C.friction"),
        ("friction: {viscous: b}", "couplings.C.friction"),
    ],
    ids=["number", "a_radius", "none", "viscous_only"],
)
def test_mesh_friction_the_variants_cannot_use_is_refused_with_its_entry(
    tmp_path: Path, friction: str, entry: str
) -> None:
    """Each mesh's friction coefficient is solved from its ordinary efficiency: a number, a
    symbol used elsewhere or no load-dependent law was a traceback or a message without a line."""
    result, path = _run(tmp_path, SIMPLE_PAIR.replace(MESH_FRICTION, friction))
    assert_refused(result, path, (entry,))
    assert f"{path}:16: {entry}:" in result.stderr, result.describe()


def test_bearing_joining_the_wrong_links_is_refused_with_the_mesh(tmp_path: Path) -> None:
    """B on [1, 2] makes link 1 the carrier of gear 2 and holder of gear 1: the mesh has no
    carrier (it was ``derive: FILE: ...`` without line or entry)."""
    text = SIMPLE_PAIR.replace("B: {type: revolute, links: [0, 2]}", "B: {type: revolute, links: [1, 2]}")
    assert text != SIMPLE_PAIR
    result, path = _run(tmp_path, text)
    assert_refused(result, path, ("couplings.C",))


def test_large_numbers_in_a_design_derive(tmp_path: Path) -> None:
    """A radius of 31193315773297988 made python-flint's factor() overflow sorting its factors."""
    text = (CATALOG / "wolfrom.yaml").read_text(encoding="utf-8")
    data = yaml.safe_load(text)
    data["gears"]["R1"]["radius"] = 31193315773297988
    result, _ = _run(tmp_path, _dump(data))
    assert result.returncode == 0, result.describe()
    assert "31193315773297988" in result.stdout


def test_factor_survives_coefficients_beyond_a_c_long() -> None:
    from flint import fmpz_mpoly_ctx

    from davies_sym.algebra.polynomials import factor

    x, y = fmpz_mpoly_ctx.get(("x", "y"), "degrevlex").gens()
    content, factors = factor(-6 * (x + 2**70 * y) * (x + y + 3) ** 2)
    assert content == -6
    assert sorted((str(f), e) for f, e in factors) == sorted([(str(x + 2**70 * y), 1), (str(x + y + 3), 2)])


@pytest.mark.parametrize(
    ("old", "new", "entry"),
    [
        ("    tolerance: 1.0e-12", "    tolerence: 1.0e-12", "expected[0].tolerence"),
        ("    tolerance: 1.0e-12", "    tolerance: [1]", "expected[0].tolerance"),
        ("    value: 0.98", "    value: abc", "expected[0].value"),
        (
            "    values: {r1: 20, r2: 50, eta_C: 0.98}",
            "    values: {r1: \"__import__('os')\", r2: 50, eta_C: 0.98}",
            "expected[0].values.r1",
        ),
        (
            "    values: {r1: 20, r2: 50, eta_C: 0.98}",
            "    values: {r1: 20, r2: 50, eta_C: 1.5}",
            "expected[0].values.eta_C",
        ),
        ("    values: {r1: 20, r2: 50, eta_C: 0.98}", "    values: [20, 50]", "expected[0].values"),
        ("    tolerance: 1.0e-12", "    tolerance: 1.0e-12\n    published: maybe", "expected[0].published"),
        ("    tolerance: 1.0e-12", "    tolerance: 1.0e-12\n    differs: [1]", "expected[0].differs"),
    ],
    ids=[
        "typo",
        "tolerance_list",
        "value_text",
        "value_payload",
        "efficiency_above_one",
        "values_list",
        "published_not_boolean",
        "differs_not_text",
    ],
)
def test_published_check_is_read_against_the_schema(tmp_path: Path, old: str, new: str, entry: str) -> None:
    assert old in SIMPLE_PAIR
    result, path = _run(tmp_path, SIMPLE_PAIR.replace(old, new))
    assert_refused(result, path, (entry,))
