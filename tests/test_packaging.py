"""What a user gets from ``pip install``: the wheel carries the catalog, the derivations,
the license and ``py.typed``; matplotlib is an optional extra; ``derive --version`` and
``derive --catalog``; figures in the format their suffix names; output files with the
usual permissions."""

from __future__ import annotations

import os
import shlex
import stat
import subprocess
import sys
import zipfile
from importlib import metadata
from pathlib import Path

import pytest
from hand.markdown import blocks as _blocks
from hand.markdown import commands as _commands
from harness.helpers import run_main

from davies_sym.emit.atomic import write_atomic
from davies_sym.topology.catalog_files import catalog_names

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def wheel(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps", "-q", "-w", str(out)],
        check=True,
        capture_output=True,
    )
    (found,) = out.glob("davies_sym-*.whl")
    return found


@pytest.mark.slow
def test_wheel_carries_the_catalog_license_and_types(wheel: Path) -> None:
    """Every catalog file and SR20 table, every derivation, py.typed and the license are in
    the wheel; the metadata has the SPDX license and matplotlib only as an extra."""
    names = set(zipfile.ZipFile(wheel).namelist())
    for stem in catalog_names():
        assert f"davies_sym/catalog/{stem}.yaml" in names
    assert {f"davies_sym/catalog/data/sr20_table{k}.csv" for k in range(1, 6)} <= names
    derived = {p.name for p in (ROOT / "derivations").iterdir()}
    assert {f"davies_sym/derivations/{n}" for n in derived if n.endswith((".py", ".tex"))} <= names
    assert "davies_sym/py.typed" in names
    assert any(n.endswith("licenses/LICENSE") for n in names)
    meta = zipfile.ZipFile(wheel).read(next(n for n in names if n.endswith("METADATA"))).decode()
    assert "License-Expression: MIT" in meta
    matplotlib = [line for line in meta.splitlines() if line.startswith("Requires-Dist: matplotlib")]
    assert matplotlib and all("extra ==" in line for line in matplotlib)


@pytest.mark.slow
def test_installed_wheel_runs_a_catalog_train_from_any_folder(wheel: Path, tmp_path: Path) -> None:
    """Installed from the wheel (not the checkout), run in an empty folder:
    ``derive --catalog buckingham_pair --eval mu=0.0272`` prints Laus's eq. (136) number
    0.9936745104 (App. A.4, Buckingham's pair)."""
    target = tmp_path / "site"
    subprocess.run(
        [sys.executable, "-m", "pip", "install", "--no-deps", "-q", "--target", str(target), str(wheel)],
        check=True,
        capture_output=True,
    )
    env = {**os.environ, "PYTHONPATH": str(target)}
    where = subprocess.run(
        [sys.executable, "-c", "import davies_sym; print(davies_sym.__file__)"],
        env=env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
        check=True,
    )
    assert where.stdout.startswith(str(target))
    result = subprocess.run(
        [sys.executable, "-m", "davies_sym.cli", "--catalog", "buckingham_pair", "--eval", "mu=0.0272", "--quiet"],
        env=env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0, result.stderr
    assert abs(float(result.stdout.splitlines()[-1]) - 0.9936745104) < 5e-11
    # The calibration of docs/calibration.md, its data from the wheel too (Mantriota and
    # Pennestri 2003: fitted on Table I, Tables II-V predicted to 0.0102 on average).
    fitted = subprocess.run(
        [sys.executable, "-m", "davies_sym.cli", "calibrate", "--catalog", "sr20_differential", "--quiet"],
        env=env,
        cwd=tmp_path,
        capture_output=True,
        text=True,
    )
    assert fitted.returncode == 0, fitted.stderr
    assert fitted.stdout.splitlines()[-1] == "mean absolute error against the measured eta: 0.0102"
    # Every command of the README's console blocks, in a folder holding only its planetary.yaml.
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    folder = tmp_path / "newcomer"
    folder.mkdir()
    (folder / "planetary.yaml").write_text(_blocks(readme, "yaml")[0], encoding="utf-8")
    for block in _blocks(readme, "console"):
        for command, shown in _commands(block):
            words = shlex.split(command)
            assert words[0] == "derive", command
            ran = subprocess.run(
                [sys.executable, "-m", "davies_sym.cli", *words[1:]],
                env=env,
                cwd=folder,
                capture_output=True,
                text=True,
            )
            assert ran.returncode == 0, (command, ran.stderr)
            assert ran.stdout.strip() == shown, command
    # The README's Python session, on the module the commands wrote, as a doctest.
    (folder / "session.txt").write_text("\n".join(_blocks(readme, "pycon")), encoding="utf-8")
    session = subprocess.run(
        [sys.executable, "-m", "doctest", "-o", "NORMALIZE_WHITESPACE", "session.txt"],
        env=env,
        cwd=folder,
        capture_output=True,
        text=True,
    )
    assert session.returncode == 0, session.stdout[-3000:]


def test_version_and_catalog_listing() -> None:
    """--version prints the installed version; --catalog lists every catalog train; an
    unknown name, a name and a file together, and no file at all are exit 2 with a message."""
    version = run_main(["--version"])
    assert version.returncode == 0 and version.stdout.strip() == f"derive (davies_sym) {metadata.version('davies_sym')}"
    listing = run_main(["--catalog"])
    assert listing.returncode == 0
    for stem in catalog_names():
        assert f"  {stem} " in listing.stdout
    assert set(catalog_names()) == {p.stem for p in (ROOT / "catalog").glob("*.yaml")}
    unknown = run_main(["--catalog", "nosuch"])
    assert unknown.returncode == 2 and "no catalog train 'nosuch'" in unknown.stderr and "tuplin" in unknown.stderr
    both = run_main(["--catalog", "tuplin", str(ROOT / "catalog" / "tuplin.yaml")])
    assert both.returncode == 2 and "not both" in both.stderr
    nothing = run_main([])
    assert nothing.returncode == 2 and "give a topology file" in nothing.stderr


def test_catalog_train_by_name_equals_its_file() -> None:
    """derive --catalog tuplin --eval gives the same answer as derive catalog/tuplin.yaml."""
    values = ["--eval", "r1=40", "r2=60", "r3=15", "eta_C=0.99", "eta_D=0.99", "--quiet"]
    by_name = run_main(["--catalog", "tuplin", *values])
    by_file = run_main([str(ROOT / "catalog" / "tuplin.yaml"), *values])
    assert by_name.returncode == 0 and by_name.stdout == by_file.stdout


@pytest.mark.parametrize(("suffix", "magic"), [(".png", b"\x89PNG"), (".svg", b"<?xml"), (".pdf", b"%PDF")])
def test_figure_format_follows_the_suffix(tmp_path: Path, suffix: str, magic: bytes) -> None:
    """-o fig.svg writes SVG, fig.pdf PDF, fig.png PNG, the same bytes on a second run."""
    figure = tmp_path / f"eta{suffix}"
    args = [
        "--catalog",
        "tuplin",
        "--plot",
        "r1=20:100",
        "--at",
        "r2=60",
        "r3=15",
        "eta_C=0.99",
        "eta_D=0.99",
        "-o",
        str(figure),
        "--quiet",
    ]
    assert run_main(args).returncode == 0
    first = figure.read_bytes()
    assert first.startswith(magic)
    assert run_main(args).returncode == 0 and figure.read_bytes() == first


def test_unknown_figure_suffix_is_refused(tmp_path: Path) -> None:
    result = run_main(
        [
            "--catalog",
            "tuplin",
            "--plot",
            "r1=20:100",
            "--at",
            "r2=60",
            "r3=15",
            "eta_C=0.99",
            "eta_D=0.99",
            "-o",
            str(tmp_path / "eta.jpg"),
            "--quiet",
        ]
    )
    assert result.returncode == 2 and "-o" in result.stderr and ".svg" in result.stderr
    assert not (tmp_path / "eta.jpg").exists()


def test_figures_without_matplotlib_say_which_extra_to_install(tmp_path: Path) -> None:
    """matplotlib is optional: without it --plot is exit 2 naming the extra, and the
    formulas still derive."""
    code = "import sys; sys.modules['matplotlib'] = None; from davies_sym.cli import main; sys.exit(main(sys.argv[1:]))"
    plot = subprocess.run(
        [
            sys.executable,
            "-c",
            code,
            "--catalog",
            "tuplin",
            "--plot",
            "r1=20:100",
            "--at",
            "r2=60",
            "r3=15",
            "eta_C=0.99",
            "eta_D=0.99",
            "-o",
            str(tmp_path / "eta.png"),
            "--quiet",
        ],
        capture_output=True,
        text=True,
    )
    assert plot.returncode == 2 and "davies_sym[plots]" in plot.stderr and "Traceback" not in plot.stderr
    derived = subprocess.run(
        [sys.executable, "-c", code, "--catalog", "tuplin", "--quiet"], capture_output=True, text=True
    )
    assert derived.returncode == 0 and "eta =" in derived.stdout


def test_output_files_get_the_usual_permissions(tmp_path: Path) -> None:
    """A new file is 0666 less the umask (0644 under umask 022), like any program's output;
    a replaced file keeps its mode."""
    previous = os.umask(0o022)
    try:
        new = tmp_path / "new.txt"
        write_atomic(str(new), "x")
        assert stat.S_IMODE(new.stat().st_mode) == 0o644
        kept = tmp_path / "kept.txt"
        kept.write_text("old")
        kept.chmod(0o640)
        write_atomic(str(kept), "new")
        assert stat.S_IMODE(kept.stat().st_mode) == 0o640 and kept.read_text() == "new"
    finally:
        os.umask(previous)
