"""A process that reads and derives many train files (a worker of `derive FILES --jobs N`
or of a Dask cluster, thousands of atlas files) keeps nothing of a file once its result is
handed back: its YAML nodes, its trains and the layouts cached on them are released."""

from __future__ import annotations

import gc

import yaml
from harness.helpers import CATALOG

from davies_sym.cli.many_files import Task, derive_task
from davies_sym.topology.model import Train
from davies_sym.topology.yaml_source import parse_yaml


def _alive(kind: type) -> int:
    gc.collect()
    return sum(1 for o in gc.get_objects() if isinstance(o, kind))


def test_parsing_a_file_keeps_none_of_its_yaml_nodes() -> None:
    """Each scalar of a parsed document (values and keys) would stay reachable if the
    reader kept the nodes it built: 20 parses of the Wolfrom file leave no node alive."""
    text = (CATALOG / "wolfrom.yaml").read_text(encoding="utf-8")
    before = _alive(yaml.Node)
    for _ in range(20):
        parsed = parse_yaml(text, "wolfrom.yaml")
        assert parsed.data["name"]
    del parsed
    assert _alive(yaml.Node) == before


def test_deriving_files_in_one_process_keeps_no_train() -> None:
    """Three catalog files derived one after another, every state: no `Train` outlives
    its task (the caches keyed by train drop with it, `davies_sym.caches`)."""
    before = _alive(Train)
    for name in ("wolfrom", "simpson", "tuplin"):
        path = CATALOG / f"{name}.yaml"
        derived = derive_task(Task(str(path), path.read_bytes(), name, "json"))
        assert derived.status == 0, derived.messages
    assert _alive(Train) == before


def test_a_factorisation_is_remembered_by_the_polynomials_terms() -> None:
    """The memo of `factor` knows a polynomial by its terms (python-flint keeps the text
    of every polynomial it writes, so the memo never asks for it): one polynomial built
    two ways has one key and one factorisation, a polynomial one coefficient away
    another."""
    from flint import fmpz_mpoly_ctx

    from davies_sym.algebra.flint_conversion import factor, polynomial_key

    x, y, z = fmpz_mpoly_ctx.get(("x", "y", "z"), "degrevlex").gens()
    built = (x + 2 * y) * (y - z) ** 2
    expanded = x * y**2 - 2 * x * y * z + x * z**2 + 2 * y**3 - 4 * y**2 * z + 2 * y * z**2
    assert polynomial_key(built) == polynomial_key(expanded)
    assert polynomial_key(built + 1) != polynomial_key(built)
    assert factor(built) == factor(expanded) == (1, [(x + 2 * y, 1), (y - z, 2)])
