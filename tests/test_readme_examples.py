"""The README and the documentation cannot go stale: every ``$ derive ...`` command shown
in a console block of README.md and docs/*.md runs and prints exactly what the block
shows (``...`` standing for what the page leaves out), the README's Python
session runs as a doctest, and its API example runs.  The commands run in an empty
folder holding only the README's ``planetary.yaml`` and the catalog, as a newcomer's
would."""

from __future__ import annotations

import doctest
import os
import re
import shlex
import sys
from pathlib import Path

import pytest
from hand.markdown import blocks as _blocks
from hand.markdown import commands as _commands
from harness.helpers import run_main

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def _cases():
    for page in PAGES:
        for block in _blocks(page.read_text(encoding="utf-8"), "console"):
            for command, shown in _commands(block):
                yield pytest.param(command, shown, id=f"{page.name}: {command[:60]}")


@pytest.fixture
def newcomer(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """An empty folder with the README's planetary.yaml, the catalog and the tests' data
    files (the docs' examples), as the cwd."""
    (tmp_path / "planetary.yaml").write_text(_blocks(README, "yaml")[0], encoding="utf-8")
    (tmp_path / "catalog").symlink_to(ROOT / "catalog")
    (tmp_path / "tests").symlink_to(ROOT / "tests")  # the docs' own example files
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_readme_is_short() -> None:
    assert len(README.splitlines()) <= 250


@pytest.mark.parametrize(("command", "shown"), list(_cases()))
def test_console_block_prints_what_it_shows(newcomer: Path, command: str, shown: str) -> None:
    words = shlex.split(command)
    assert words[0] == "derive", command
    result = run_main(words[1:])
    assert result.returncode == 0, result.describe()
    # "..." stands for what the page leaves out: lines, or the part of a line that varies.
    pattern = "\n".join(".*".join(map(re.escape, line.split("..."))) for line in shown.splitlines())
    assert re.fullmatch(pattern, result.stdout.strip(), flags=re.S), f"{command}\n--- prints ---\n{result.stdout}"


def test_readme_python_session_and_api_example(newcomer: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The module the README writes answers its session as shown; the API example runs."""
    assert run_main(["planetary.yaml", "--quiet", "--python", "planetary.py"]).returncode == 0
    monkeypatch.syspath_prepend(str(newcomer))
    sys.modules.pop("planetary", None)
    session = "\n".join(_blocks(README, "pycon"))
    test = doctest.DocTestParser().get_doctest(session, {}, "README", "README.md", 0)
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.failures == 0 and runner.tries >= 5
    api = next(b for b in _blocks(README, "python") if "davies_sym.derive" in b)
    scope: dict[str, object] = {}
    exec(compile(api, "README.md", "exec"), scope)  # the README's own example, as a user runs it
    assert str(scope["variants"].evaluate({"zs": 24, "zp": 30, "eta_SP": 0.98, "eta_PR": 0.99})) == "43957/45000"
    assert os.path.exists(newcomer / "planetary.py")
