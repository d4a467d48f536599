"""Generate ``docs/topology.md`` from the schema tables (``python3 tools/topology_doc.py``)."""

from __future__ import annotations

import sys

from davies_sym.emit.atomic import write_atomic
from davies_sym.topology.coupling_kinds import KINDS
from davies_sym.topology.couplings import coupling_fields
from davies_sym.topology.schema import (
    BEARING,
    EXPECTED,
    FORMAT_VERSION,
    FRICTION,
    GEAR,
    LINK,
    PORTS,
    STATE,
    TOOTH_CONTACT,
    TOP_LEVEL,
    fields_table,
)

INTRO = f"""# Topology language, version {FORMAT_VERSION}

A train file is YAML. It describes the machine the way it is drawn: links (members),
gears on links, couplings between links (revolute pairs, gear meshes, prismatic
pairs, or explicit screws), the ports (input and output couplings), the reference
link and the friction of each coupling. Every entry is checked on load; all
problems are reported together, each with its file, line and entry path.
An entry that takes a list (`links`, `independent`, a state's `brake`, `free` and
`clutch`, `calibrate.fit`) takes one item written alone as the list of that item:
`brake: c2` is `brake: [c2]`.

This page is generated from `davies_sym/topology/schema.py` and the coupling kinds
registered in `davies_sym/topology/coupling_kinds.py` (`python3 tools/topology_doc.py`);
a test fails when it is out of date.

## Example: Laus Fig. 7 (Tuplin's two-annulus train)

```yaml
format: 1
name: Epicyclic gear train with two annuli (Tuplin)
links: [1, 2, 3/4, 5]
reference: 1
gears:
  1: {{link: 1, radius: r1, internal: true}}
  2: {{link: 2, radius: r2, internal: true}}
  3: {{link: 3/4, radius: r3}}
  4: {{link: 3/4, radius: r4}}
couplings:
  A: {{type: revolute, links: [1, 5]}}
  B: {{type: revolute, links: [1, 2]}}
  C: {{type: mesh, gears: [1, 3]}}          # Coulomb friction zeta_C by default
  D: {{type: mesh, gears: [2, 4]}}
  E: {{type: revolute, links: [3/4, 5]}}
ports: {{input: A, output: B}}
```

The engine places the axes from the meshes (planet bearing E at r1 - r3), states the
geometric constraint the loop implies (r1 - r3 = r2 - r4), builds the coupling graph
and the screws, and derives the efficiency.

## Layout of planar trains

All gear axes are parallel to z and lie in the plane x = 0 (Laus Figs. 5 and 7). Gears
on one link share its axis; a revolute between two geared links makes them coaxial, and
one whose `axis` names a third link turns its held link about that link's axis (an
output shaft coaxial with the input, each in a bearing of the housing).
The axis of the reference link is at y = 0, and a bearing's `at` puts its axis at that
y; when the reference carries no gear and no `at` places a geared axis, the axis of the
first geared link (by name) is at y = 0: the ports never move an axis. An external mesh
puts the centres r_g + r_h apart, an internal mesh R - r apart with the pinion on the
+y side of the annulus centre. The pitch point of a mesh is where its friction torque
acts and its tooth force (along x, pressure angle zero, Laus section 3.3.1) passes.
A mesh that closes a loop of meshes gives a geometric constraint, reported in the
output; with numeric radii that violate it, loading fails with a geometry error.

## Numbers and symbols

A quantity is a number (`40`, `0.99`, `"1/3"`, all taken exactly) or an expression
of symbols (`r1`, `r1 - r3`, `m*z/2`). Radii, friction and viscous coefficients are
positive symbols. A gear given by `teeth` and `module` gets radius module * teeth / 2.
Every value stays exact: square roots (`sqrt(2)`, `cos(pi/6)`) are accepted in
directions (`axis`, `placement`, `direction`, screw coordinates); sizes and
coefficients are rational expressions of the symbols. Numbers beyond 2^1024, values
that are not finite and sizes that can never be positive (`-r1`) are refused.

## Friction convention

Coulomb friction with a positive coefficient is the default for every gear mesh
(`zeta_<coupling>`); the friction torque acts about the relative-motion axis
(Laus Theorem 1) and opposes the relative motion. Its sign is fixed from the lossless
solution with positive input power; where the declared ports do not decide it (it
depends on the radii), the output keeps a symbol `sigma_<coupling>` = +1 or -1 and
states the expression whose sign it is. `friction: none` makes a coupling lossless.
"""


def render() -> str:
    parts = [
        INTRO,
        "## Top-level keys\n",
        fields_table(TOP_LEVEL),
        "\n## Links (mapping form)\n",
        fields_table(LINK),
        "\n## Gears\n",
        fields_table(GEAR),
        "\n## Ports\n",
        fields_table(PORTS),
        "\n## Couplings\n",
    ]
    for name, kind in KINDS.items():
        parts += [f"\n### `type: {name}`\n", kind.DOC + "\n", fields_table(coupling_fields(kind))]
    parts += ["\n## Friction\n", "`friction: none`, or a mapping of laws to coefficients:\n", fields_table(FRICTION)]
    parts += [
        "\n### Journal bearing\n",
        "`friction: {bearing: {...}}` on a revolute (Laus App. D): the Coulomb law "
        "whose friction-circle radius `zeta_<coupling>` the formulas keep, with its definition stated beside "
        "them.\n",
        fields_table(BEARING),
    ]
    parts += [
        "\n### Tooth contact\n",
        "`efficiency: {...}` on an external spur mesh: both ordinary efficiencies from "
        "the tooth geometry and the flank friction coefficient (Laus App. A, eqs. (134)-(136)); the formulas "
        "keep `eta_<coupling>_<driver>_<driven>` and state their definitions, `--eval`, the plots and the "
        "formula modules take the parameters (`derive catalog/buckingham_pair.yaml --eval mu=0.0272`).\n",
        fields_table(TOOTH_CONTACT),
    ]
    parts += [
        "\n## States\n",
        "Operating states of a multi-speed set (`states: {name: entry}`). "
        "`derive` derives every state; `--state NAME` picks one for `--eval`, `--latex` and "
        "`--python`.\n",
        fields_table(STATE),
    ]
    parts += [
        "\n## Published checks\n",
        "`expected:` lists published numbers the catalog tests reproduce, each "
        "checked on load like every other entry.\n",
        fields_table(EXPECTED),
    ]
    return "\n".join(parts) + "\n"


def main() -> int:
    target = sys.argv[1] if len(sys.argv) > 1 else "docs/topology.md"
    write_atomic(target, render())
    return 0


if __name__ == "__main__":
    sys.exit(main())
