"""Pages of the documentation site generated from the library, at build time.

``mkdocs build --strict`` (or ``mkdocs serve``) in the checkout runs
``tools/docs_gen.py`` through the gen-files plugin, which calls `generate`: the
command line reference, the Python API reference (mkdocstrings) and one page per catalog
train with its coupling graph, conditions, variants, published checks and figures (among
them Chen Fig. 4.13 for Litvin's drive and Laus Fig. 11 for the Humpage train).  The
hand-written pages are ``docs/*.md``; ``mkdocs.yml`` holds the configuration.
"""

from __future__ import annotations

import glob
import os
from collections.abc import Callable
from types import ModuleType

from docs_pages import Figure, api_page, catalog_page, cli_page, several_inputs_section, states_body
from machine_pages import machine_page
from published_layouts import laus_humpage_layout

from davies_sym.cli import parser
from davies_sym.efficiency.parameter_domain import efficiency_symbols
from davies_sym.efficiency.parameters import formula_symbols
from davies_sym.efficiency.several_inputs import derive_several_inputs
from davies_sym.efficiency.turning_conditions import mesh_roles
from davies_sym.efficiency.variant_checks import NOMINAL_EFFICIENCY
from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.emit.graph_drawing import coupling_graph_figure
from davies_sym.emit.plots import (
    Sweep,
    efficiency_figure,
    figure_bytes,
    formula_module,
    region_figure,
    turning_surface_figure,
)
from davies_sym.machines.machine_loader import build_machine, is_machine
from davies_sym.network.analysis import Analysis
from davies_sym.network.analysis_options import AnalysisOptions
from davies_sym.topology.documents import read_document
from davies_sym.topology.loader import load
from davies_sym.topology.model import Train
from davies_sym.topology.states import train_in_state
from davies_sym.topology.symbols import exact_number

#: Writes a file of the site: path relative to the docs directory, bytes.
Write = Callable[[str, bytes], None]
Progress = Callable[[str], None]

#: Figures reproducing the literature, by catalog file: (kind, arguments, caption).
LITERATURE_FIGURES: dict[str, list[tuple[str, dict[str, object], str]]] = {
    "litvin_face_drive": [
        (
            "sweep",
            {"x": Sweep("N4", 60, 99)},
            "Efficiency against N4 with N1 = 100, N2 = N3 = 17, 98 % per mesh, as in Chen 2006 "
            "Fig. 4.13 (77.5 % at N4 = 88); below, the loss in each mesh.",
        )
    ],
    "humpage": [
        (
            "laus_surface",
            {},
            "Turning-condition surface of mesh C in the radii space (r1, r5, r2), Laus 2011 Fig. 11: Table 6's "
            "((r5 - 3 r1) r2^2 + r1 (r5 - r1)^2)(r5 - r1) = 0, derived by the engine on Laus's printed planet "
            "axis (eq. (80)). With the consistent cone geometry of the catalog file gear 1 always drives in "
            "mesh C, and the one turning condition is r2 r4 - r3 r5.",
        )
    ],
}


def _nominal(train: Train, state: str | None) -> dict[str, float]:
    """The train's (or state's) published design as floats."""
    out = {}
    for k, v in train.published_design(state).items():
        value = exact_number(v)
        if value is not None:
            out[k] = float(value)
    return out


def _automatic_figures(
    variants: VariantSet, module: ModuleType, stem: str, state: str | None, write: Write
) -> list[Figure]:
    """Efficiency against the first geometric parameter (or the first mesh efficiency)
    around the published design, and the variant map over the symbols of the first
    turning condition."""
    etas = {str(e) for e in efficiency_symbols(variants.train)}
    # Without a published design, the mesh efficiencies take Glover's 0.98.
    nominal = {**{e: float(NOMINAL_EFFICIENCY) for e in etas}, **_nominal(variants.train, state)}
    symbols = [str(s) for s in formula_symbols(variants)]
    if any(s not in nominal for s in symbols):
        return []
    port = variants.train.ports.input
    suffix = f"_{state}" if state else ""
    geometry = [s for s in symbols if s not in etas]
    out = []
    if geometry:
        name = geometry[0]
        sweep = Sweep(name, 0.5 * nominal[name], 1.5 * nominal[name])
    elif symbols:
        name = symbols[0]
        sweep = Sweep(name, 0.9, 1.0)
    else:
        return []
    values = {k: v for k, v in nominal.items() if k in symbols and k != sweep.name}
    file = f"{stem}{suffix}_{sweep.name}.png"
    write(f"catalog/img/{file}", figure_bytes(efficiency_figure(variants, sweep, values, port, module)))
    out.append(
        Figure(
            file,
            f"Efficiency and losses against {sweep.name} around the published design (mesh "
            f"efficiencies 0.98 where none is published), input {port}.",
        )
    )
    if variants.conditions:
        free = sorted(str(s) for s in variants.conditions[0].simplified.free_symbols)
        if len(free) >= 2:
            x, y = (Sweep(n, 0.5 * nominal[n], 1.5 * nominal[n]) for n in free[:2])
            values = {k: v for k, v in nominal.items() if k in symbols and k not in (x.name, y.name)}
            file = f"{stem}{suffix}_regions.png"
            write(f"catalog/img/{file}", figure_bytes(region_figure(variants, x, y, values, port, module)))
            out.append(Figure(file, f"Variant regions, turning conditions and efficiency over {x.name} and {y.name}."))
    return out


def _literature_figures(
    train: Train, variants: VariantSet, module: ModuleType, stem: str, write: Write
) -> list[Figure]:
    out = []
    for kind, arguments, caption in LITERATURE_FIGURES.get(stem, []):
        if kind == "sweep":
            sweep = arguments["x"]
            assert isinstance(sweep, Sweep)
            nominal = _nominal(train, None)
            values = {k: v for k, v in nominal.items() if k != sweep.name}
            figure = efficiency_figure(variants, sweep, values, train.ports.input, module)
            file = f"{stem}_literature_{sweep.name}.png"
        else:
            options = AnalysisOptions(
                coulomb_signs="mesh-linear",
                extra_symbols=efficiency_symbols(train),
                layout=laus_humpage_layout(train),
            )
            analysis = Analysis(train, options)
            roles, conditions = mesh_roles(analysis)
            name = next(r.condition for r in roles if r.coupling == "C")
            condition = next(c.simplified for c in conditions if c.name == name)
            figure = turning_surface_figure(
                condition,
                Sweep("r1", 1, 100),
                Sweep("r5", 1, 100),
                Sweep("r2", 0, 100),
                "Humpage, mesh C: turning-condition surface (Laus Fig. 11)",
            )
            file = f"{stem}_laus_fig11.png"
        write(f"catalog/img/{file}", figure_bytes(figure))
        out.append(Figure(file, caption))
    return out


def catalog_pages(root: str, write: Write, progress: Progress) -> list[str]:
    """``catalog/<stem>.md`` (and its images) for every catalog file, and the catalog
    index; the stems."""
    stems = []
    names = {}
    for path in sorted(glob.glob(os.path.join(root, "catalog", "*.yaml"))):
        stem = os.path.splitext(os.path.basename(path))[0]
        document = read_document(path)
        if is_machine(document.data):
            progress(f"catalog {stem}: machine")
            machine = build_machine(document)
            write(f"catalog/{stem}.md", machine_page(machine, stem, write).encode())
            stems.append(stem)
            names[stem] = machine.name
            continue
        train = load(path)
        names[stem] = train.name
        write(f"catalog/img/{stem}_graph.png", figure_bytes(coupling_graph_figure(train)))
        if (train.degrees_of_freedom or 1) > 1:
            progress(f"catalog {stem}: power-flow regions")
            body = several_inputs_section(derive_several_inputs(train), "##")
        else:
            sections: dict[str | None, tuple[VariantSet, list[Figure]]] = {}
            for state in [st.name for st in train.states] or [None]:
                progress(f"catalog {stem}" + (f", state {state}" if state else "") + ": variants and figures")
                one = train_in_state(train, train.state(state)) if state else train
                variants = derive_variants(one)
                module = formula_module(variants)  # compiled once for every figure of the state
                figures = _automatic_figures(variants, module, stem, state, write)
                if state is None:
                    figures = _literature_figures(train, variants, module, stem, write) + figures
                sections[state] = (variants, figures)
            body = states_body(train, sections)
        write(f"catalog/{stem}.md", catalog_page(train, stem, body).encode())
        stems.append(stem)
    index = [
        "# Catalog",
        "",
        "Literature trains and machines, each regression-checked against its published numbers.",
        "",
        "| train | file |",
        "| --- | --- |",
    ]
    for stem in stems:
        index.append(f"| [{names[stem]}]({stem}.md) | `catalog/{stem}.yaml` |")
    write("catalog/index.md", ("\n".join(index) + "\n").encode())
    return stems


def generate(root: str, write: Write, progress: Progress) -> list[str]:
    """Every generated page of the site (see the module docstring); the catalog stems."""
    progress("command line and API references")
    write("cli.md", cli_page(parser()).encode())
    write("api.md", api_page().encode())
    return catalog_pages(root, write, progress)
