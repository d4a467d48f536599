"""The topology language's reference page (docs/topology.md) is the one
tools/topology_doc.py generates from the schema, so the page cannot go stale."""

from __future__ import annotations

import os

from topology_doc import render

from conftest import ROOT


def test_topology_reference_is_generated_and_current():
    """docs/topology.md is generated from the schema; regenerate with
    ``python3 tools/topology_doc.py``."""
    with open(os.path.join(ROOT, "docs", "topology.md"), encoding="utf-8") as handle:
        assert handle.read() == render()
