"""The catalog of literature trains that comes with the package: its topology files by
name (``derive --catalog`` lists them, ``derive --catalog tuplin`` runs one)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from davies_sym.errors import InputError, Problem


def catalog_folder() -> Path:
    """The folder of the catalog's topology files (package data)."""
    return Path(str(resources.files("davies_sym") / "catalog"))


def catalog_names() -> list[str]:
    """The catalog trains' names: their files' stems, sorted."""
    return sorted(p.stem for p in catalog_folder().glob("*.yaml"))


def catalog_file(name: str) -> str:
    """The topology file of the catalog train ``name`` (``tuplin`` or ``tuplin.yaml``)."""
    stem = name[:-5] if name.endswith(".yaml") else name
    names = catalog_names()
    if stem not in names:
        raise InputError(
            [Problem("--catalog", f"no catalog train {stem!r}; the catalog has: {', '.join(names)}")], "derive"
        )
    return str(catalog_folder() / f"{stem}.yaml")
