"""What a derivation of the atlas of N links could share between its states, measured:

- relabellings within a file: states that an automorphism of the drawn train (links,
  gears with their internal flags, couplings, the housing fixed) maps onto another state
  of the same file, whose closed form is the other's with the names exchanged;
- rotation graphs recurring across displacement graphs: how many files and states share
  a rotation graph (their drawings differ: mesh kinds, coaxial conditions, layout);
- the share of a derivation spent in the exact null spaces (motions, lossless actions,
  actions with friction), the part a closed form in signed basic ratios could carry from
  one drawing of a rotation graph to another, against the turning-condition regions,
  variants and report, which depend on the drawing's signs (a profile of ``--sample K``
  files drawn at random).

    python benchmarks/atlas_recurrences.py [LINKS] [--jobs N] [--sample K] [--seed S]
"""

from __future__ import annotations

import argparse
import collections
import cProfile
import pstats
import random
import re

import networkx as nx
import yaml
from atlas_states import formed_file
from networkx.algorithms.isomorphism import DiGraphMatcher

from davies_sym.atlas.atlas_entries import places
from davies_sym.cli.many_files import Task, derive_task
from davies_sym.fan_out import Workers, fan_out

Node = tuple[str, str]


def train_graph(doc: dict) -> nx.DiGraph:
    """The drawn train as a labelled graph: links (the reference apart), gears (internal
    or not) on their links, couplings (kind; on the housing's axis; placed at a free
    distance) on their links or gears, a revolute's links in their order."""
    g = nx.DiGraph()
    for name in doc["links"]:
        g.add_node(("L", name), label="housing" if name == doc.get("reference") else "link")
    for name, gear in (doc.get("gears") or {}).items():
        g.add_node(("G", name), label="ring" if gear.get("internal") else "gear")
        g.add_edge(("G", name), ("L", gear["link"]), label="on")
    for name, c in doc["couplings"].items():
        g.add_node(("C", name), label=f"{c['type']} {'axis' in c} {'at' in c}")
        if c["type"] == "mesh":
            for gear in c["gears"]:
                g.add_edge(("C", name), ("G", gear), label="mesh")
        else:
            for k, link in enumerate(c["links"]):
                g.add_edge(("C", name), ("L", link), label=f"link {k}")
    return g


def state_images(doc: dict) -> int:
    """How many of the file's states are the image of an earlier state under an
    automorphism of the drawn train."""
    states = doc.get("states") or {}
    g = train_graph(doc)
    same = lambda a, b: a["label"] == b["label"]  # noqa: E731
    automorphisms = list(DiGraphMatcher(g, g, node_match=same, edge_match=same).isomorphisms_iter())
    seen: set[tuple[Node, ...]] = set()
    images = 0
    for s in states.values():
        key = (("L", (s.get("brake") or [doc["reference"]])[0]), ("C", s["input"]), ("C", s["output"]))
        if key in seen:
            images += 1
            continue
        seen.update(tuple(a[x] for x in key) for a in automorphisms)
    return images


def null_space_share(texts: list[tuple[str, str]]) -> tuple[float, float]:
    """Seconds of ``derive FILE --json`` over the files, and of them in the exact null spaces."""
    profile = cProfile.Profile()
    for name, text in texts:
        profile.enable()
        derive_task(Task(f"{name}.yaml", text.encode(), name, "json"))
        profile.disable()
    stats = pstats.Stats(profile).stats  # type: ignore[attr-defined]
    seconds = {fn: ct for (_, _, fn), (_, _, _, ct, _) in stats.items() if fn in ("derive_task", "null_space")}
    return seconds["derive_task"], seconds["null_space"]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("links", type=int, nargs="?", default=7)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--sample", type=int, default=60, help="files profiled, drawn at random")
    p.add_argument("--seed", type=int, default=1)
    args = p.parse_args()
    files = [(n, t) for n, t, _ in fan_out(formed_file, places(args.links), Workers(jobs=args.jobs)) if t is not None]
    docs = {name: yaml.safe_load(text) for name, text in files}
    count = {name: len(doc.get("states") or {}) or 1 for name, doc in docs.items()}
    states = sum(count.values())
    images = {name: state_images(doc) for name, doc in docs.items()}
    print(f"{args.links} links: {len(docs)} train files, {states} states")
    print(
        f"  relabellings within a file: {sum(images.values())} states are the image of another "
        f"({100 * sum(images.values()) / states:.1f} %), in {sum(1 for v in images.values() if v)} files"
    )
    rotation = collections.Counter(re.sub(r"_d\d+$", "", name) for name in docs)
    shared = [r for r, n in rotation.items() if n > 1]
    print(
        f"  rotation graphs: {len(rotation)} drawn; {len(shared)} recur across "
        f"{sum(rotation[r] for r in shared)} files (at most {max(rotation.values())} displacement graphs each)"
    )
    sample = random.Random(args.seed).sample(files, min(args.sample, len(files)))
    whole, solving = null_space_share(sample)
    print(
        f"  {len(sample)} files profiled: {whole:.1f} s, of it {solving:.1f} s in the exact null spaces "
        f"({100 * solving / whole:.0f} %); the rest forms the regions, variants and report"
    )


if __name__ == "__main__":
    main()
