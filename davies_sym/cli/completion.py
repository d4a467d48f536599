"""``derive --completion bash|zsh|tcsh``: a shell completion script made from the
argument parser by ``shtab``, so it always knows the options ``derive`` has.  Topology
files complete to ``.yaml`` files (and folders), ``--catalog`` to the catalog's train
names, ``-o`` and ``--python`` to any file."""

from __future__ import annotations

import argparse

from davies_sym.errors import MissingDependencyError
from davies_sym.topology.catalog_files import catalog_names

SHELLS = ("bash", "zsh", "tcsh")

#: shtab's completion of a topology file in each shell (the bash function is in the preamble).
YAML_FILES = {"bash": "_shtab_derive_yaml_files", "zsh": "_files -g '*.(yaml|yml)'", "tcsh": "f:*.yaml"}
#: Any file (shtab's own ``FILE``, spelled out so the parser does not import shtab).
ANY_FILE = {"bash": "_shtab_compgen_files", "zsh": "_files", "tcsh": "f"}


def catalog_completion() -> dict[str, str]:
    """The catalog's train names as completions of ``--catalog``."""
    names = " ".join(catalog_names())
    return {"bash": "_shtab_derive_catalog_names", "zsh": f"({names})", "tcsh": f"({names})"}


def _preamble(shell: str) -> str:
    """The bash functions the completions name (the other shells need none)."""
    if shell != "bash":
        return ""
    names = " ".join(catalog_names())
    return "\n".join(
        [
            "# $1=COMP_WORDS[1]",
            "_shtab_derive_yaml_files() {",
            "  compgen -d -- $1  # into folders",
            "  compgen -f -X '!*.yaml' -- $1",
            "  compgen -f -X '!*.yml' -- $1",
            "}",
            "",
            "_shtab_derive_catalog_names() {",
            f'  compgen -W "{names}" -- $1',
            "}",
            "",
        ]
    )


def completion_script(parser: argparse.ArgumentParser, shell: str) -> str:
    """The completion script of ``parser`` for ``shell`` (one of `SHELLS`)."""
    try:
        import shtab
    except ImportError as exc:  # pragma: no cover - shtab is a dependency
        raise MissingDependencyError("--completion needs shtab (pip install 'shtab>=1.6')") from exc
    return str(shtab.complete(parser, shell=shell, preamble=_preamble(shell)))
