"""Markdown pages of the documentation site generated from the library: one page per
catalog train (coupling graph, speed ratio, turning conditions, every variant with its
formula rendered, the published numbers with their status, figures), the command line
reference and the Python API reference."""

from __future__ import annotations

import argparse
import importlib
import inspect
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import sympy

from davies_sym.efficiency.parameters import parameter_table
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.variant_report import condition_text, mesh_text
from davies_sym.errors import MissingValuesError
from davies_sym.topology.model import Expected, Train
from davies_sym.topology.symbols import exact_number


@dataclass(frozen=True)
class Figure:
    """A figure of a page: file name (beside the page, in ``img/``) and caption."""

    file: str
    caption: str


@dataclass(frozen=True)
class Check:
    """A published number and what the derivation gives."""

    expected: Expected
    derived: float | None
    variant: int | None

    @property
    def status(self) -> str:
        if self.derived is None:
            return "not evaluated"
        return "reproduced" if abs(self.derived - self.expected.value) <= self.expected.tolerance else "differs"


def published_checks(variants: VariantSet, state: str | None) -> list[Check]:
    """The file's ``expected`` entries for this state, evaluated exactly."""
    out = []
    train = variants.train
    for check in train.expected:
        if check.quantity != "efficiency" or check.state != state:
            continue
        values = {}
        for name, text in check.values.items():
            value = exact_number(text)
            if name in train.symbols and value is not None:
                values[train.symbols[name]] = value
        port = check.input or train.ports.input
        try:
            variant = variants.variant_for(values, port)
            derived = float(variants.evaluate(values, port))
        except MissingValuesError:
            # A published number whose design the paper gives only in part (a radius or an
            # efficiency not stated): the page lists it as "not evaluated".  Any other
            # error (a port that is not one, values that break a relation) is a fault of
            # the catalog file and stops the build.
            out.append(Check(check, None, None))
            continue
        out.append(Check(check, derived, variant.number))
    return out


def _math(expr: sympy.Expr) -> str:
    return f"${sympy.latex(expr)}$"


def _escape(text: str) -> str:
    return text.replace("|", "\\|").replace("*", "\\*").replace("_", "\\_")


def state_section(variants: VariantSet, heading: str, figures: Sequence[Figure], state: str | None) -> list[str]:
    """Speed ratio, conditions, variants, formulas, checks and figures of one train or state."""
    train = variants.train
    ratio = variants.analysis.speed_ratio().to_expr()
    lines = [f"{heading} Speed ratio", "",
             f"$$\\frac{{\\omega_{{{train.ports.input}}}}}{{\\omega_{{{train.ports.output}}}}} = "
             f"{sympy.latex(ratio)}$$", ""]
    lines += [f"{heading} Turning conditions", ""]
    if variants.conditions:
        lines += ["| condition | expression | decides the driving gear of |", "| --- | --- | --- |"]
        for c in variants.conditions:
            meshes = ", ".join(r.coupling for r in variants.roles if r.condition == c.name)
            lines.append(f"| {c.name} | {_math(c.simplified)} | mesh {meshes} |")
    else:
        lines.append("None: the driving gear of every mesh follows from the input port alone.")
    lines += ["", f"{heading} Variants", "",
              "| variant | input → output | where | meshes | checks |", "| --- | --- | --- | --- | --- |"]
    for v in variants.variants:
        where = ", ".join(f"${sympy.latex(c.simplified)} {'>' if v.signs[c.name] > 0 else '<'} 0$"
                          for c in variants.conditions) or "every design"
        meshes = "<br>".join(_escape(m) for m in mesh_text(variants, v))
        notes = "feasible" if v.feasible else "no admissible design"
        if v.self_locking_point is not None:
            notes += "; self-locks at some designs"
        lines.append(f"| ({v.number}) | {v.input} → {v.output} | {where} | {meshes} | {notes} |")
    lines += ["", f"{heading} Formulas", ""]
    for v in variants.variants:
        conditions = " and ".join(_escape(t) for t in condition_text(variants, v))
        lines += [f"Variant ({v.number}), input {v.input}" + (f", where {conditions}" if conditions else "") + ":", "",
                  f"$$\\eta_{{({v.number})}} = {sympy.latex(v.efficiency)}$$", ""]
    lines += [f"{heading} Parameters", "", "| name | meaning | unit | range |", "| --- | --- | --- | --- |"]
    for p in parameter_table(variants):
        lines.append(f"| `{p.name}` | {_escape(p.meaning)} | {p.unit} | {p.range_text} |")
    checks = published_checks(variants, state)
    if checks:
        lines += ["", f"{heading} Published numbers", "",
                  "| values | input | published | derived | variant | status | source |",
                  "| --- | --- | --- | --- | --- | --- | --- |"]
        for c in checks:
            values = ", ".join(f"{k} = {v}" for k, v in c.expected.values.items())
            derived = "—" if c.derived is None else f"{c.derived:.6g}"
            lines.append(f"| {_escape(values)} | {c.expected.input or train.ports.input} | {c.expected.value:g} "
                         f"(± {c.expected.tolerance:g}) | {derived} | "
                         f"{'—' if c.variant is None else f'({c.variant})'} | **{c.status}** | "
                         f"{_escape(c.expected.source)} |")
    if figures:
        lines += ["", f"{heading} Figures", ""]
        for f in figures:
            lines += [f"![{f.caption}](img/{f.file})", "", f"*{f.caption}*", ""]
    return [*lines, ""]


def catalog_page(train: Train, stem: str, sections: Mapping[str | None, tuple[VariantSet, Sequence[Figure]]],
                 notes: Sequence[str] = ()) -> str:
    """The page of one catalog file (one section per operating state, if it has states)."""
    lines = [f"# {train.name}", "", f"Source: {_escape(train.source or 'not given')}.", "",
             f"Topology file: `catalog/{stem}.yaml`; generated formulas: `derivations/{stem}*.py` and "
             f"`derivations/{stem}.tex`.", "", f"![coupling graph of {stem}](img/{stem}_graph.png)", "",
             "| link | description |", "| --- | --- |"]
    lines += [f"| {link.name} | {_escape(link.description)} |" for link in train.links]
    lines += ["", "| coupling | kind | between |", "| --- | --- | --- |"]
    for c in train.couplings:
        lines.append(f"| {c.name} | {type(c).__name__} | {' — '.join(c.links)} |")
    lines += ["", *notes, ""] if notes else [""]
    for state, (variants, figures) in sections.items():
        if state is None:
            lines += state_section(variants, "##", figures, None)
        else:
            st = train.state(state)
            lines += [f"## State {state}" + (f": {st.description}" if st.description else ""), "",
                      f"Input {st.input}, output {st.output}"
                      + (f"; braked: {', '.join(st.brake)}" if st.brake else "")
                      + (f"; clutched: {', '.join('+'.join(p) for p in st.clutch)}" if st.clutch else "")
                      + (f"; free: {', '.join(st.free)}" if st.free else "") + ".", ""]
            lines += state_section(variants, "###", figures, state)
    return "\n".join(lines).rstrip("\n") + "\n"


def cli_page(parser: argparse.ArgumentParser) -> str:
    """The command line reference: the help of ``derive`` and examples."""
    parser.prog = "derive"
    return "\n".join([
        "# Command line", "", "```text", parser.format_help().rstrip(), "```", "", "## Examples", "",
        "```bash",
        "derive catalog/tuplin.yaml                       # summary: conditions and every variant",
        "derive catalog/tuplin.yaml --latex -o tuplin.tex # LaTeX: Table 5 form, one equation per variant",
        "derive catalog/tuplin.yaml --python tuplin_eff.py  # formula module for design code",
        "derive catalog/tuplin.yaml --eval r1=40 r2=60 r3=15 eta_C=0.99 eta_D=0.99",
        "derive catalog/litvin_face_drive.yaml --plot N4=60:99 -o litvin.png",
        "derive catalog/tuplin.yaml --plot r1=20:100 --vs r2=20:100 --at r3=15 -o regions.png",
        "derive catalog/simpson.yaml --state first --eval ...",
        "derive catalog/*.yaml --out derivations/        # every catalog train",
        "```", "",
        "Progress messages go to standard error (when it is a terminal); `--quiet` silences them. "
        "Errors name the file, the entry and what is wrong, and exit with status 2.", ""])


#: Modules of the public API, in reading order.
API_MODULES = ("davies_sym", "davies_sym.topology.loader", "davies_sym.topology.model", "davies_sym.network.analysis",
               "davies_sym.efficiency.variants", "davies_sym.efficiency.turning_conditions",
               "davies_sym.efficiency.virtual_power", "davies_sym.efficiency.virtual_power_balance",
               "davies_sym.efficiency.power_losses", "davies_sym.efficiency.parameters",
               "davies_sym.emit.python_module", "davies_sym.emit.plots", "davies_sym.emit.graph_drawing",
               "davies_sym.emit.latex", "davies_sym.emit.evaluation")


def _doc(obj: object) -> str:
    return inspect.cleandoc(inspect.getdoc(obj) or "")


def _block(text: str) -> list[str]:
    """A docstring as an indented text block (no Markdown surprises)."""
    return ["```text", text, "```", ""] if text else []


def api_page() -> str:
    """Classes and functions of :data:`API_MODULES` with signatures and docstrings."""
    lines = ["# Python API", "", "Generated from the docstrings of the package.", ""]
    for name in API_MODULES:
        module = importlib.import_module(name)
        lines += [f"## `{name}`", "", *_block(_doc(module))]
        members = []
        for attr, obj in vars(module).items():
            if attr.startswith("_") or getattr(obj, "__module__", None) != name:
                continue
            if inspect.isclass(obj) or inspect.isfunction(obj):
                members.append((attr, obj))
        for attr, obj in members:
            try:
                signature = str(inspect.signature(obj))
            except (TypeError, ValueError):
                # inspect.signature's documented refusals: ValueError when an object has no
                # signature it can read (one implemented in C), TypeError when it cannot
                # take one; the page then writes the arguments as "(...)".
                signature = "(...)"
            kind = "class" if inspect.isclass(obj) else "def"
            lines += [f"### `{attr}`", "", "```python", f"{kind} {attr}{signature}", "```", "", *_block(_doc(obj))]
            if inspect.isclass(obj):
                for method_name, method in vars(obj).items():
                    if method_name.startswith("_") or not (inspect.isfunction(method) or isinstance(method, property)):
                        continue
                    target = method.fget if isinstance(method, property) else method
                    doc = _doc(target)
                    if doc:
                        lines += [f"- `{attr}.{method_name}`: {_escape(doc.splitlines()[0])}"]
                lines.append("")
    return "\n".join(lines).rstrip("\n") + "\n"

