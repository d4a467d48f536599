"""``derive search`` beyond the answer itself: the states derived on processes or a Dask
cluster give the same document as in this process, the Pareto figure, and the refusals of
the options that say where and how to work (exit status 2, the option named)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from harness.helpers import run_main

DATA = Path(__file__).resolve().parent / "data"
STATES = DATA / "search_states.yaml"
PLANETARY = DATA / "search_planetary.yaml"
#: A two-state search (the low and high states of search_states.yaml) small enough to repeat.
ARGS = ["--target", "low=4.6", "high=1.28", "--tolerance", "0.01", "--teeth", "zs=17:50", "zr=50:130", "--planets", "3"]


def _candidates(*extra: str) -> list[dict]:
    result = run_main(["search", STATES, *ARGS, "--json", "--quiet", "--top", "1000", *extra], timeout=600)
    assert result.returncode == 0, result.describe()
    return json.loads(result.stdout)["candidates"]


def test_processes_give_what_this_process_gives() -> None:
    serial = _candidates()
    assert serial, "the space holds feasible designs"
    assert _candidates("--jobs", "2") == serial


@pytest.mark.slow
def test_a_dask_cluster_gives_what_this_process_gives() -> None:
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        on_cluster = _candidates("--scheduler", cluster.scheduler_address)
    assert on_cluster == _candidates()


@pytest.mark.slow
def test_an_unreachable_scheduler_is_named() -> None:
    pytest.importorskip("dask.distributed")
    result = run_main(["search", STATES, *ARGS, "--quiet", "--scheduler", "tcp://127.0.0.1:9"], timeout=120)
    assert result.returncode == 2, result.describe()
    assert "--scheduler" in result.stderr and "Traceback" not in result.stderr


@pytest.mark.slow
def test_the_pareto_figure_is_written(tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    figure = tmp_path / "front.png"
    result = run_main(["search", STATES, *ARGS, "--quiet", "--plot", "-o", figure, "--json"], timeout=600)
    assert result.returncode == 0, result.describe()
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    document = json.loads(result.stdout)
    front = document["pareto"]["ratio_error"]
    scores = [document["candidates"][k]["score"] for k in front if k < len(document["candidates"])]
    assert scores == sorted(scores, reverse=True), "the front runs from the best score down"


@pytest.mark.parametrize(
    ("extra", "option"),
    [
        (["--jobs", "0"], "--jobs"),
        (["--jobs", "many"], "--jobs"),
        (["--plot"], "--plot"),
        (["--plot", "-o", "front.txt"], "-o"),
        (["--top", "0"], "--top"),
        (["--min-teeth", "0"], "--min-teeth"),
        (["--tolerance", "abc"], "--tolerance"),
        (["--target", "low=4.6", "high=x"], "--target"),
    ],
)
def test_bad_options_are_refused(tmp_path: Path, extra: list[str], option: str) -> None:
    args = [a if a != "front.txt" else str(tmp_path / a) for a in extra]
    base = [a for a in ARGS]
    if "--target" in args:
        base = base[base.index("--tolerance") :]
    result = run_main(["search", STATES, *base, "--quiet", *args], timeout=120)
    assert result.returncode == 2, result.describe()
    assert option in result.stderr and "Traceback" not in result.stderr, result.describe()


def test_a_train_without_symbolic_teeth_is_refused() -> None:
    catalog = Path(__file__).resolve().parent.parent / "catalog" / "simple_pair.yaml"
    result = run_main(["search", catalog, "--target", "2.5", "--teeth", "z1=17:40", "--quiet"], timeout=120)
    assert result.returncode == 2, result.describe()
    assert "teeth" in result.stderr and "Traceback" not in result.stderr


@pytest.mark.slow
def test_a_tooth_geometry_efficiency_ranks_by_the_teeth_themselves() -> None:
    """With the sun mesh's efficiency from the tooth contact (Laus App. A, mu 0.06), designs
    of one ratio differ: zs/zr = 21/75 and 42/150 both give 32/7, and the larger teeth
    lose less (the sliding loss falls with 1/z1 + 1/z2, Laus eq. (134)).  Each candidate's
    efficiency is what ``derive --eval`` gives at its teeth (the planet's follows from them)."""
    path = DATA / "search_tooth_geometry.yaml"
    args = ["--target", "4.6", "--tolerance", "0.01", "--teeth", "zs=17:60", "zr=50:150", "--planets", "3"]
    result = run_main(["search", path, *args, "--json", "--quiet", "--top", "100"], timeout=600)
    assert result.returncode == 0, result.describe()
    candidates = json.loads(result.stdout)["candidates"]
    by_teeth = {(c["teeth"]["zs"], c["teeth"]["zr"]): c for c in candidates}
    small, large = by_teeth[(21, 75)], by_teeth[(42, 150)]
    assert small["speed_ratio_exact"] == large["speed_ratio_exact"] == "32/7"
    assert large["efficiency"] > small["efficiency"] + 1e-4
    assert [c["efficiency"] for c in candidates] == sorted((c["efficiency"] for c in candidates), reverse=True)
    for c in (candidates[0], small, candidates[-1]):
        teeth = c["teeth"]
        evaluated = run_main([path, "--quiet", "--eval", f"zs={teeth['zs']}", f"zr={teeth['zr']}"], timeout=600)
        assert evaluated.returncode == 0, evaluated.describe()
        assert float(evaluated.stdout.splitlines()[-1]) == pytest.approx(c["efficiency"], rel=1e-12)


def test_a_negative_fraction_is_a_target_not_an_option(tmp_path: Path) -> None:
    """`--target -22/25` reads as -0.88 does (argparse took it for an option).  An external
    pair driven at the 50-tooth gear B, output the z1-tooth gear A: speed ratio (B over A)
    -z1/50, which is -22/25 at z1 = 44 exactly."""
    path = tmp_path / "pair.yaml"
    path.write_text(
        "name: external pair\nlinks: [0, a, b]\nreference: 0\nindependent: [z1]\ngears:\n"
        "  G1: {link: a, teeth: z1, module: 2}\n  G2: {link: b, teeth: 50, module: 2}\ncouplings:\n"
        "  A: {type: revolute, links: [0, a]}\n  B: {type: revolute, links: [0, b]}\n"
        "  C: {type: mesh, gears: [G1, G2], efficiency: 0.98}\nports: {input: B, output: A}\n"
    )
    for target in ("-22/25", "-0.88"):
        result = run_main(["search", path, "--target", target, "--tolerance", "0", "--teeth", "z1=40:50", "--quiet"])
        assert result.returncode == 0, result.describe()
        assert re.findall(r"z1=(\d+)", result.stdout) == ["44"], result.stdout


def test_a_name_with_a_control_character_is_searched(tmp_path: Path) -> None:
    """A train's name is the in-memory module's file name too, where a NUL was refused by
    Python (ValueError: embedded null character); the search takes the name as derive does.
    The README's planetary at ratio 1 + zr/zs = 4: zp = zs."""
    path = tmp_path / "named.yaml"
    path.write_text(
        'name: "planetary \\x00 named"\nlinks: [0, s, p, c]\nreference: 0\nindependent: [zs, zp]\ngears:\n'
        "  S: {link: s, teeth: zs, module: 2}\n  P: {link: p, teeth: zp, module: 2}\n"
        "  R: {link: 0, teeth: zr, module: 2, internal: true}\ncouplings:\n"
        "  A: {type: revolute, links: [0, s]}\n  B: {type: revolute, links: [0, c]}\n"
        "  D: {type: revolute, links: [c, p]}\n"
        "  SP: {type: mesh, gears: [S, P], efficiency: 0.98}\n  PR: {type: mesh, gears: [P, R], efficiency: 0.99}\n"
        "ports: {input: A, output: B}\n"
    )
    result = run_main(["search", path, "--target", "4", "--tolerance", "0", "--teeth", "zs=20:22", "zp=18:24"])
    assert result.returncode == 0, result.describe()
    assert re.findall(r"zs=(\d+) zp=(\d+)", result.stdout) == [("20", "20"), ("21", "21"), ("22", "22")], result.stdout
