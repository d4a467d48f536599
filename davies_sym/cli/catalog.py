"""``derive --catalog``: the catalog of literature trains and machines that comes with the package,
listed, or one of them chosen by name in place of a topology file."""

from __future__ import annotations

import argparse

from davies_sym.errors import DaviesError, InputError, Problem
from davies_sym.machines.machine_loader import build_machine, is_machine
from davies_sym.topology.catalog_files import catalog_file, catalog_folder, catalog_names
from davies_sym.topology.documents import read_document
from davies_sym.topology.loader import build_train


def catalog_listing() -> str:
    """One line per catalog train: the name to give ``--catalog``, its title and source."""
    folder = catalog_folder()
    lines = [f"catalog of literature trains ({folder}):"]
    names = catalog_names()
    width = max(map(len, names), default=0)
    for name in names:
        try:
            document = read_document(folder / f"{name}.yaml")
            entry = build_machine(document) if is_machine(document.data) else build_train(document)
            about = entry.name + (f" ({entry.source})" if entry.source else "")
        except DaviesError as exc:  # pragma: no cover - the catalog is tested to load
            about = f"does not load: {exc}"
        lines.append(f"  {name:<{width}}  {about}")
    lines.append("derive --catalog NAME [options] derives one, as derive FILE would.")
    return "\n".join(lines) + "\n"


def chosen_files(args: argparse.Namespace) -> list[str] | None:
    """The files to derive: the catalog train ``--catalog NAME`` names, or those given;
    None when ``--catalog`` alone asks for the listing."""
    if args.catalog is None:
        if not args.files:
            raise InputError(
                [
                    Problem(
                        "FILE",
                        "give a topology file (or --catalog NAME for a train of the catalog; "
                        "derive --catalog lists them)",
                    )
                ],
                "derive",
            )
        return list(args.files)
    if args.files:
        raise InputError(
            [Problem("--catalog", f"give a catalog name or files, not both (got {args.files[0]!r} as well)")], "derive"
        )
    if args.catalog == "":
        return None
    return [catalog_file(args.catalog)]
