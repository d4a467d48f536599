"""One Python interpreter against the package installed in it.

Run by ``tools/check_pythons.sh`` in a fresh virtual environment of every supported
Python besides the default one.  It derives every catalog train with ``derive FILES --out
DIR`` and, for each generated formula module:

- its text is byte for byte the checkout's ``derivations/`` module (generation does not
  depend on the interpreter's version);
- it imports, and its ``efficiency`` at each published efficiency of the catalog file
  (``expected:`` entries with ``quantity: efficiency``) gives the published number within
  the file's tolerance, unless the file says its geometry does not reproduce it.

Usage: ``python tools/check_interpreter.py CHECKOUT OUT_DIR``; exit status 0 when every
module passes, 1 otherwise, with one line per problem.
"""

from __future__ import annotations

import importlib.util
import math
import subprocess
import sys
import warnings
from pathlib import Path

import davies_sym
from davies_sym.topology.model import Expected


def _module(path: Path) -> object:
    spec = importlib.util.spec_from_file_location(f"checked_{path.stem}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _published(check: Expected, module: object) -> str | None:
    """Why ``module`` does not give ``check``'s number (None when it does)."""
    names = {p["name"] for p in getattr(module, "PARAMETERS")}  # noqa: B009
    values = {k: float(eval_number(v)) for k, v in check.values.items() if k in names}
    if set(values) != names:
        return None  # the check gives values the module's parameters do not take (a loss model's)
    ports = getattr(module, "PORTS", None)
    keyword = {"input": check.input} if check.input is not None and ports is not None else {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        got = float(getattr(module, "efficiency")(**keyword, **values))  # noqa: B009
    if check.differs is not None:
        return None
    if not math.isfinite(got) or abs(got - check.value) > check.tolerance:
        return f"efficiency {got!r}, published {check.value} +- {check.tolerance} ({check.source})"
    return None


def eval_number(text: str) -> float:
    """A value of a catalog check (``0.99``, ``1/3``, ``20*pi/180``) as a float."""
    from davies_sym.topology.expressions import parse_expression

    return float(parse_expression(str(text)))


def main(checkout: Path, out: Path) -> int:
    # Gear trains only: a machine file (a ``machine:`` entry) writes no formula module.
    catalog = [
        p
        for p in sorted((checkout / "catalog").glob("*.yaml"))
        if not any(line.startswith("machine:") for line in p.read_text(encoding="utf-8").splitlines())
    ]
    derive = Path(sys.executable).with_name("derive")
    done = subprocess.run(
        [str(derive), *map(str, catalog), "--out", str(out), "--jobs", "auto", "--quiet"], check=False
    )
    problems = [] if done.returncode == 0 else [f"derive --out exited with {done.returncode}"]
    checked = 0
    for path in catalog:
        train = davies_sym.load(str(path))
        stems = [f"{path.stem}_{s.name}" for s in train.states] or [path.stem]
        for stem in stems:
            generated = out / f"{stem}.py"
            if not generated.exists():
                if (checkout / "derivations" / f"{stem}.py").exists():
                    problems.append(f"{stem}: no module written")
                continue
            if generated.read_bytes() != (checkout / "derivations" / f"{stem}.py").read_bytes():
                problems.append(f"{stem}: the module differs from derivations/{stem}.py")
            module = _module(generated)
            state = stem[len(path.stem) + 1 :] or None
            for check in train.expected:
                if check.quantity != "efficiency" or check.state not in (None, state):
                    continue
                why = _published(check, module)
                if why is not None:
                    problems.append(f"{stem}: {why}")
            checked += 1
    for line in problems:
        print(f"check_interpreter: {line}", file=sys.stderr)
    print(f"check_interpreter: Python {sys.version.split()[0]}: {checked} modules, {len(problems)} problems")
    return 1 if problems or not checked else 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), Path(sys.argv[2])))
