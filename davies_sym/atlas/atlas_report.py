"""The atlas as text: the counts beside the published ones, then one line per
displacement graph (its levels, gear pairs and admissible choices)."""

from __future__ import annotations

from collections.abc import Sequence

from davies_sym.atlas.atlas_entries import PUBLISHED, Entry


def _entry_line(e: Entry) -> str:
    drawn = e.drawn
    named = sorted((drawn.axis_name(k), axis) for k, axis in enumerate(e.graph.axes))
    levels = " ".join(f"{name}={{{','.join(map(str, axis))}}}" for name, axis in named)
    gears = " ".join(f"{p.first}-{p.second}/{p.carrier}" for p in e.graph.gear_pairs)
    if e.not_drawable:
        tail = f"not drawn: {e.not_drawable}"
    elif e.drawn.frame is not None:
        tail = f"{len(e.choices)} choice(s) ({len(e.loaded)} loaded), frame {e.drawn.frame}"
    else:
        held = ",".join(map(str, sorted({c.held for c in e.choices})))
        tail = f"{len(e.choices)} choice(s) ({len(e.loaded)} loaded), held {held}"
    return f"  {e.name}  axes {levels}  gears {gears}  {tail}"


def counts_text(links: int, counts: tuple[int, int], published: tuple[int, int] | None) -> str:
    """The counts and, where published, whether they agree (``derive atlas --count``)."""
    lines = [f"{links} links: {counts[0]} rotation graphs, {counts[1]} displacement graphs"]
    if published is not None:
        agree = "agrees" if published == counts else "DIFFERS"
        lines.append(f"published ({PUBLISHED}): {published[0]} and {published[1]}: {agree}")
    return "\n".join(lines) + "\n"


def atlas_text(links: int, entries: Sequence[Entry], published: tuple[int, int] | None) -> str:
    """The ``derive atlas`` report."""
    rotation = len({e.rotation for e in entries})
    lines = counts_text(links, (rotation, len(entries)), published).splitlines()
    lines.append("gear pairs are written first-second/carrier; axis a is the main axis (housing or frame)")
    current = 0
    for e in entries:
        if e.rotation != current:
            current = e.rotation
            lines.append(f"rotation graph {current} ({e.rotation_code})")
        lines.append(_entry_line(e))
    return "\n".join(lines) + "\n"
