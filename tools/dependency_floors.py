"""Check that the dependency floors of ``pyproject.toml`` are versions that work.

``python3 tools/dependency_floors.py [VENV] [-- PYTEST ARGS]`` makes a fresh virtual
environment, installs every core dependency (and matplotlib of the ``plots`` extra) at
exactly its floor, binary wheels only, then runs the symbolic core of the tests against
the checkout.  A floor that is too old fails at import or in a test; raise it.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile

import tomllib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORE_TESTS = [
    "tests/test_tuplin.py",
    "tests/test_simple_pair.py",
    "tests/test_variants.py",
    "tests/test_api_values.py",
    "tests/test_several_inputs.py",
    "tests/test_losses_against_oracle.py",
]


def floors() -> list[str]:
    """``name==floor`` of every core dependency and of the plots extra."""
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as handle:
        project = tomllib.load(handle)["project"]
    specs = [*project["dependencies"], *project["optional-dependencies"]["plots"]]
    out = []
    for spec in specs:
        match = re.fullmatch(r"([A-Za-z0-9_.\-\[\]]+)>=([0-9.]+)", spec.split(";")[0].strip())
        if match is None:
            raise SystemExit(f"no floor in {spec!r}")
        out.append(f"{match.group(1)}=={match.group(2)}")
    return out


def main(argv: list[str]) -> int:
    rest = argv[argv.index("--") + 1 :] if "--" in argv else CORE_TESTS
    venv = argv[0] if argv and argv[0] != "--" else tempfile.mkdtemp(prefix="davies_sym_floors_")
    python = os.path.join(venv, "bin", "python")
    subprocess.run([sys.executable, "-m", "venv", venv], check=True)
    pins = floors()
    print("floors:", " ".join(pins), flush=True)
    subprocess.run(
        [
            python,
            "-m",
            "pip",
            "install",
            "-q",
            "--only-binary",
            ":all:",
            *pins,
            "pytest",
            "pytest-xdist",
            "hypothesis",
            "lark",
        ],
        check=True,
    )
    env = {**os.environ, "PYTHONPATH": ROOT}
    return subprocess.run(
        [python, "-m", "pytest", "-q", "-n", "auto", "-p", "no:cacheprovider", *rest], cwd=ROOT, env=env, check=False
    ).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
