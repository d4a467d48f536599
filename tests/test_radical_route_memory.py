"""A state whose sibling's elimination modulo the square roots swelled skips that
attempt (`davies_sym.network.null_space.Swelling`): the derivation of a state must not
depend on which states were derived before it in the same file.

atlas7_r92_d23 is the 7-link train whose planet triangles swell the reduced elimination
of its actions in every state holding l2 (docs/atlas.md): its state h2_i1_o3 derived
alone (the reduced elimination tried, then the factored one) and derived after its
siblings (straight to the factored one) give the same document."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from harness.helpers import run_main_in

from davies_sym.atlas.atlas_entries import entry, places


@pytest.mark.slow
def test_a_state_derives_alike_alone_and_after_the_siblings_whose_matrices_swelled(tmp_path: Path) -> None:
    (place,) = [p for p in places(7) if p.name == "atlas7_r92_d23"]
    (tmp_path / "train.yaml").write_text(entry(place).train_text())
    whole = run_main_in(tmp_path, ["train.yaml", "--json"], timeout=600)
    alone = run_main_in(tmp_path, ["train.yaml", "--state", "h2_i1_o3", "--json"], timeout=600)
    assert whole.returncode == 0 and alone.returncode == 0, (whole.stderr, alone.stderr)
    states = json.loads(whole.stdout)["states"]
    assert list(states).index("h2_i1_o3") > list(states).index("h2_i0_o1")  # the siblings come first
    assert json.loads(alone.stdout)["states"] == {"h2_i1_o3": states["h2_i1_o3"]}
