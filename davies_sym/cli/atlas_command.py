"""``derive atlas --links N [--json] [--out DIR] [--draw] [--jobs N]``: every
non-isomorphic one-degree-of-freedom planetary gear train of N links, counted against
the published complete set, with a train file for each that derives as written.

Bad input exits with status 2 and one message naming the option.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Iterator
from typing import Any

from davies_sym.emit.atomic import write_atomic
from davies_sym.fan_out import Counted, Workers, fan_out
from davies_sym.progress import Display, Progress


def folder_refused(command: str, folder: str | None) -> bool:
    """Say so when ``--out`` names a file that exists (a folder is wanted)."""
    if folder and os.path.exists(folder) and not os.path.isdir(folder):
        print(f"{command}: --out {folder}: a file of that name exists; name a folder", file=sys.stderr)
        return True
    return False


def _entries(links: int, workers: Workers, say: Progress) -> Iterator[Any]:
    """Every entry of the atlas, in the order of the codes, each as its worker reads its
    motions (so its files can be written at once)."""
    from davies_sym.atlas.atlas_entries import entry, places

    found = places(links)
    rotations = len({p.rotation for p in found})
    say(f"{rotations} rotation graphs, {len(found)} displacement graphs; reading their motions")
    return fan_out(entry, found, workers, Counted(say, "graph"))


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    """The ``derive atlas`` command, its arguments parsed by ``parser``; returns the
    exit status (0, or 2 for bad input)."""
    if args.draw and not args.out:
        print("derive atlas: --draw writes the drawings beside the train files: add --out DIR", file=sys.stderr)
        return 2
    if args.count and (args.out or args.draw):
        print("derive atlas: --count writes no train file: drop --out and --draw, or --count", file=sys.stderr)
        return 2
    if folder_refused("derive atlas", args.out):
        return 2

    say = Display("derive atlas", args.quiet)

    from davies_sym.atlas.atlas_entries import PUBLISHED, PUBLISHED_COUNTS
    from davies_sym.atlas.atlas_report import atlas_text, counts_text

    published = PUBLISHED_COUNTS.get(args.links)
    if args.count:
        from davies_sym.atlas.enumeration import atlas

        found = atlas(args.links)
        counts = (found.rotation_count, found.displacement_count)
        if args.json:
            sys.stdout.write(json.dumps(_counts(args.links, counts, published, PUBLISHED), indent=2) + "\n")
        else:
            sys.stdout.write(counts_text(args.links, counts, published))
        return 0
    entries: list[Any] = []
    try:
        for found in _entries(args.links, Workers(args.jobs), say):
            entries.append(found)
            if args.out:
                _write_files(found, args.out, args.draw)
        if args.out:
            say(f"{sum(not e.not_drawable for e in entries)} train files in {args.out}")
    except EditedFile as exc:
        print(
            f"derive atlas: --out: {exc.args[0]} is there with other contents; it is left as it is: "
            "move it or name another folder",
            file=sys.stderr,
        )
        return 2
    except OSError as exc:
        print(f"derive atlas: cannot write {exc.filename}: {exc.strerror}", file=sys.stderr)
        return 2
    rotation = len({e.rotation for e in entries})
    if args.json:
        document = _counts(args.links, (rotation, len(entries)), published, PUBLISHED)
        document["graphs"] = [e.document() for e in entries]
        sys.stdout.write(json.dumps(document, indent=2) + "\n")
    else:
        sys.stdout.write(atlas_text(args.links, entries, published))
    return 0


def _counts(links: int, counts: tuple[int, int], published: tuple[int, int] | None, source: str) -> dict[str, Any]:
    """The counts of ``derive atlas --json`` and the published ones (None where none are)."""
    return {
        "links": links,
        "rotation_graphs": counts[0],
        "displacement_graphs": counts[1],
        "published": {"rotation_graphs": published[0], "displacement_graphs": published[1], "source": source}
        if published
        else None,
    }


class EditedFile(Exception):
    """A file the atlas would write is there with other contents (someone edited it)."""


def _write_files(found: Any, folder: str, draw: bool) -> None:
    """The train file of a drawable entry (and its drawings), each written atomically as
    the entry is formed, so a run cut short keeps what it wrote; a file of the same name
    with other contents is never replaced (it may hold edits)."""
    if found.not_drawable:
        return
    outputs = [(os.path.join(folder, f"{found.name}.yaml"), found.train_text())]
    if draw:
        from davies_sym.atlas.drawing import graph_svg, layout_svg

        outputs.append((os.path.join(folder, f"{found.name}.graph.svg"), graph_svg(found)))
        outputs.append((os.path.join(folder, f"{found.name}.layout.svg"), layout_svg(found)))
    for path, text in outputs:
        if os.path.exists(path):
            with open(path, encoding="utf-8") as handle:
                if handle.read() != text:
                    raise EditedFile(path)
    os.makedirs(folder, exist_ok=True)
    for path, text in outputs:
        write_atomic(path, text)
