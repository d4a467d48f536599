"""``derive --completion bash|zsh|tcsh``: a shell completion script made from the
argument parsers by ``shtab``, so it always knows the options ``derive`` and its other
commands (``derive calibrate``, ``derive search``) have.  Topology files complete to
``.yaml`` files (and folders), ``--catalog`` to the catalog's train names, ``-o``,
``--python`` and data files to any file."""

from __future__ import annotations

import argparse
from collections.abc import Mapping

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


def _preamble(shell: str, commands: list[str]) -> str:
    """The bash functions the completions name (the other shells need none), and the
    other commands offered as the first word beside the topology files (bash completes a
    command word wherever it stands, but offers only the files in the first place)."""
    if shell != "bash":
        return ""
    names = " ".join(catalog_names())
    return "\n".join(
        [
            f"_shtab_derive_pos_0_choices=({' '.join(commands)})",
            "",
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


def completion_parser(
    main: argparse.ArgumentParser, commands: Mapping[str, argparse.ArgumentParser]
) -> argparse.ArgumentParser:
    """``main`` with the other commands as subcommands, for the completion only (``derive``
    dispatches them before parsing): each keeps its own options, a line of help, and its
    topology file completing to ``.yaml`` files."""
    full = argparse.ArgumentParser(prog=main.prog, parents=[main], add_help=False, description=main.description)
    sub = full.add_subparsers(dest="command", title="other commands")
    for name, command in commands.items():
        one = sub.add_parser(name, parents=[command], add_help=False, help=(command.description or "").split(". ")[0])
        for action in one._actions:
            if action.dest == "train":
                action.complete = YAML_FILES  # type: ignore[attr-defined]
            elif action.dest == "catalog":
                action.complete = catalog_completion()  # type: ignore[attr-defined]
            elif action.metavar and str(action.metavar).endswith((".csv", ".png", ".py")):
                action.complete = ANY_FILE  # type: ignore[attr-defined]
    return full


def completion_script(
    main: argparse.ArgumentParser, shell: str, commands: Mapping[str, argparse.ArgumentParser] | None = None
) -> str:
    """The completion script of ``main`` (and its other ``commands``) for ``shell`` (one of `SHELLS`)."""
    try:
        import shtab
    except ImportError as exc:  # pragma: no cover - shtab is a dependency
        raise MissingDependencyError("--completion needs shtab (pip install 'shtab>=1.6')") from exc
    full = completion_parser(main, commands) if commands else main
    return str(shtab.complete(full, shell=shell, preamble=_preamble(shell, list(commands or ()))))
