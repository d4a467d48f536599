"""Markdown pages of the documentation site generated from the library: one page per
catalog train (coupling graph, speed ratio, turning conditions, every variant with its
formula, the published numbers beside the derived ones, figures), the command line
reference and the Python API reference (mkdocstrings directives).

Formulas are presentation MathML (sympy's printer, symbols as the references write
them), which browsers render natively: the site needs no script and no network.  Each
``<math>`` carries its LaTeX as an annotation, for copying into a paper."""

from __future__ import annotations

import argparse
import html
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import sympy

from davies_sym.efficiency.parameters import parameter_table
from davies_sym.efficiency.several_inputs import SeveralInputs
from davies_sym.efficiency.variants import VariantSet
from davies_sym.emit.several_inputs_report import drivers, region_forces
from davies_sym.emit.variant_report import mesh_text, variant_forces
from davies_sym.errors import MissingValuesError
from davies_sym.topology.model import Expected, Train
from davies_sym.topology.symbol_display import latex, mathml_body
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
        """``reproduced``, ``differs`` (with the file's explanation when it gives one),
        ``regression`` (a value of the file's own geometry) or ``not evaluated``."""
        if self.derived is None:
            return "not evaluated"
        close = abs(self.derived - self.expected.value) <= self.expected.tolerance
        if not self.expected.published:
            return "regression" if close else "differs"
        if close:
            return "reproduced"
        return "differs, explained below" if self.expected.differs else "differs"


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


def math(body: str, tex: str, display: bool = False) -> str:
    """A ``<math>`` element: presentation MathML ``body`` with its LaTeX as annotation.

    Characters that Markdown would read (``_``, ``*``, ``|`` in a table) are written as
    character references, so the element reaches the page as it was printed."""
    mode = ' display="block"' if display else ""
    annotation = html.escape(tex, quote=False)
    element = (
        f'<math xmlns="http://www.w3.org/1998/Math/MathML"{mode}><semantics><mrow>{body}</mrow>'
        f'<annotation encoding="application/x-tex">{annotation}</annotation></semantics></math>'
    )
    return element.replace("_", "&#95;").replace("*", "&#42;").replace("|", "&#124;")


def _math(expr: sympy.Basic) -> str:
    return math(mathml_body(expr), latex(expr))


def _sign_math(expr: sympy.Expr, sign: int) -> str:
    """``expr > 0`` or ``expr < 0`` as inline math."""
    op = "&gt;" if sign > 0 else "&lt;"
    return math(f"{mathml_body(expr)}<mo>{op}</mo><mn>0</mn>", f"{latex(expr)} {'>' if sign > 0 else '<'} 0")


def _equation(number: int, expr: sympy.Expr) -> str:
    """``eta_(number) = expr`` as display math (``\\eta_{(3)} = ...``)."""
    lhs = f"<msub><mi>&#951;</mi><mrow><mo>(</mo><mn>{number}</mn><mo>)</mo></mrow></msub><mo>=</mo>"
    return math(lhs + mathml_body(expr), f"\\eta_{{({number})}} = {latex(expr)}", display=True)


def _escape(text: str) -> str:
    return text.replace("|", "\\|").replace("*", "\\*").replace("_", "\\_")


def _ratio_math(train: Train, ratio: sympy.Expr) -> str:
    """The speed ratio ``omega_in / omega_out = ...`` as display math."""
    a, b = train.ports.input, train.ports.output
    lhs = (
        f"<mfrac><msub><mi>&#969;</mi><mi>{html.escape(a)}</mi></msub>"
        f"<msub><mi>&#969;</mi><mi>{html.escape(b)}</mi></msub></mfrac><mo>=</mo>"
    )
    return math(
        lhs + mathml_body(ratio), f"\\frac{{\\omega_{{{a}}}}}{{\\omega_{{{b}}}}} = {latex(ratio)}", display=True
    )


def _published_table(checks: Sequence[Check], heading: str, port: str) -> list[str]:
    """Published (and regression) numbers beside the derived ones; a published number the
    file does not reproduce is followed by the file's explanation."""
    lines = [
        "",
        f"{heading} Published numbers",
        "",
        "| values | input | expected | derived | variant | status | source |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for c in checks:
        values = ", ".join(f"{k} = {v}" for k, v in c.expected.values.items())
        derived = "—" if c.derived is None else f"{c.derived:.6g}"
        kind = "" if c.expected.published else " (regression, not published)"
        lines.append(
            f"| {_escape(values)} | {c.expected.input or port} | {c.expected.value:g} "
            f"(± {c.expected.tolerance:g}){kind} | {derived} | "
            f"{'—' if c.variant is None else f'({c.variant})'} | **{c.status}** | "
            f"{_escape(c.expected.source)} |"
        )
    for c in checks:
        if c.expected.differs:
            lines += [
                "",
                f'!!! note "Why the derived value differs from {c.expected.value:g}"',
                f"    {_escape(' '.join(c.expected.differs.split()))}",
            ]
    return lines


def state_section(variants: VariantSet, heading: str, figures: Sequence[Figure], state: str | None) -> list[str]:
    """Speed ratio, conditions, variants, formulas, checks and figures of one train or state."""
    train = variants.train
    ratio = variants.analysis.speed_ratio().to_expr()
    lines = [f"{heading} Speed ratio", "", _ratio_math(train, ratio), ""]
    lines += [f"{heading} Turning conditions", ""]
    if variants.conditions:
        lines += ["| condition | expression | decides the driving gear of |", "| --- | --- | --- |"]
        for c in variants.conditions:
            meshes = ", ".join(r.coupling for r in variants.roles if r.condition == c.name)
            lines.append(f"| {c.name} | {_math(c.simplified)} | mesh {meshes} |")
    else:
        lines.append("None: the driving gear of every mesh follows from the input port alone.")
    lines += [
        "",
        f"{heading} Variants",
        "",
        "| variant | input → output | where | driving gear in each mesh | checks |",
        "| --- | --- | --- | --- | --- |",
    ]
    for v in variants.variants:
        where = [_sign_math(c.simplified, v.signs[c.name]) for c in variants.conditions]
        where += [f"{_escape(what)}: {_sign_math(force, sign)}" for what, force, sign in variant_forces(variants, v)]
        meshes = "<br>".join(_escape(m) for m in mesh_text(variants, v))
        notes = "feasible" if v.feasible else "no admissible design"
        if v.self_locking_point is not None:
            notes += "; self-locks at some designs"
        if v.reversed_forces:
            notes += f"; the losses reverse {', '.join(sorted(v.reversed_forces))}"
        lines.append(
            f"| ({v.number}) | {v.input} → {v.output} | {'<br>'.join(where) or 'every design'} | {meshes} | {notes} |"
        )
    lines += ["", f"{heading} Formulas", ""]
    for v in variants.variants:
        lines += [f"Variant ({v.number}), input {v.input}:", "", _equation(v.number, v.efficiency), ""]
    lines += [f"{heading} Parameters", "", "| name | meaning | unit | range |", "| --- | --- | --- | --- |"]
    for p in parameter_table(variants):
        lines.append(f"| `{p.name}` | {_escape(p.meaning)} | {p.unit} | {p.range_text} |")
    checks = published_checks(variants, state)
    if checks:
        lines += _published_table(checks, heading, train.ports.input)
    if figures:
        lines += ["", f"{heading} Figures", ""]
        for f in figures:
            lines += [f"![{f.caption}](img/{f.file})", "", f"*{f.caption}*", ""]
    return [*lines, ""]


def several_inputs_section(si: SeveralInputs, heading: str) -> list[str]:
    """Speeds, speed conditions and every power-flow region of a train driven on several
    shafts, with its efficiency (Mantriota and Pennestri 2003, eq. (6))."""
    train = si.train
    lines = [f"{heading} Speeds", "", "| port | speed in the input speeds |", "| --- | --- |"]
    lines += [f"| {p} | {_math(v.to_expr())} |" for p, v in si.port_speeds.items()]
    lines += ["", f"{heading} Speed conditions", "", "| condition | expression | decides |", "| --- | --- | --- |"]
    lines += [f"| {c.name} | {_math(c.form)} | {_escape('; '.join(c.decides))} |" for c in si.conditions]
    lines += [
        "",
        f"{heading} Power-flow regions",
        "",
        "| region | power in → out | where | driving gear in each mesh |",
        "| --- | --- | --- | --- |",
    ]
    for r in si.regions:
        where = [_sign_math(c.form, r.signs[c.name]) for c in si.conditions]
        where += [f"{_escape(what)}: {_sign_math(force, sign)}" for what, force, sign in region_forces(r)]
        meshes = "<br>".join(f"{m}: gear {a} drives gear {b}" for m, a, b in drivers(si, r))
        lines.append(
            f"| ({r.number}) | {', '.join(r.inputs)} → {', '.join(r.outputs)} | {'<br>'.join(where)} | "
            f"{_escape(meshes)} |"
        )
    lines += [
        "",
        f"{heading} Formulas",
        "",
        f"The load torque is `tau_out` at {train.ports.output}; the input speeds are "
        f"{', '.join(f'`{s}`' for s in si.speeds)}.",
        "",
    ]
    for r in si.regions:
        lines += [f"Region ({r.number}):", "", _equation(r.number, r.efficiency), ""]
    return lines


def catalog_page(train: Train, stem: str, body: Sequence[str], notes: Sequence[str] = ()) -> str:
    """The page of one catalog file: source, files, coupling graph, links and couplings,
    then ``body`` (the derived sections)."""
    lines = [
        f"# {train.name}",
        "",
        f"Source: {_escape(train.source or 'not given')}.",
        "",
        f"Topology file: `catalog/{stem}.yaml`; generated formulas: `derivations/{stem}*.py` and "
        f"`derivations/{stem}.tex`.",
        "",
        f"![coupling graph of {stem}](img/{stem}_graph.png)",
        "",
        "| link | description |",
        "| --- | --- |",
    ]
    lines += [f"| {link.name} | {_escape(link.description)} |" for link in train.links]
    lines += ["", "| coupling | kind | between |", "| --- | --- | --- |"]
    for c in train.couplings:
        lines.append(f"| {c.name} | {type(c).__name__} | {' — '.join(c.links)} |")
    lines += ["", *notes, ""] if notes else [""]
    lines += body
    return "\n".join(lines).rstrip("\n") + "\n"


def states_body(train: Train, sections: Mapping[str | None, tuple[VariantSet, Sequence[Figure]]]) -> list[str]:
    """The derived sections of a train with one input: one per operating state, if it has states."""
    lines: list[str] = []
    for state, (variants, figures) in sections.items():
        if state is None:
            lines += state_section(variants, "##", figures, None)
        else:
            st = train.state(state)
            lines += [
                f"## State {state}" + (f": {st.description}" if st.description else ""),
                "",
                f"Input {st.input}, output {st.output}"
                + (f"; braked: {', '.join(st.brake)}" if st.brake else "")
                + (f"; clutched: {', '.join('+'.join(p) for p in st.clutch)}" if st.clutch else "")
                + (f"; free: {', '.join(st.free)}" if st.free else "")
                + ".",
                "",
            ]
            lines += state_section(variants, "###", figures, state)
    return lines


def cli_page(parser: argparse.ArgumentParser) -> str:
    """The command line reference: the help of ``derive`` and examples."""
    parser.prog = "derive"
    return "\n".join(
        [
            "# Command line",
            "",
            "```text",
            parser.format_help().rstrip(),
            "```",
            "",
            "## Examples",
            "",
            "```bash",
            "derive catalog/tuplin.yaml                       # summary: conditions and every variant",
            "derive catalog/tuplin.yaml --latex -o tuplin.tex # LaTeX: Table 5 form, one equation per variant",
            "derive catalog/tuplin.yaml --python tuplin_eff.py  # formula module for design code",
            "derive catalog/tuplin.yaml --eval r1=40 r2=60 r3=15 eta_C=0.99 eta_D=0.99",
            "derive catalog/litvin_face_drive.yaml --plot N4=60:99 -o litvin.png",
            "derive catalog/tuplin.yaml --plot r1=20:100 --vs r2=20:100 --at r3=15 -o regions.png",
            "derive catalog/simpson.yaml --state first --eval ...",
            "derive catalog/*.yaml --out derivations/        # every catalog train",
            "```",
            "",
            "Progress messages go to standard error (when it is a terminal); `--quiet` silences them. "
            "Errors name the file, the entry and what is wrong, and exit with status 2.",
            "",
        ]
    )


#: Modules of the public API, in reading order.
API_MODULES = (
    "davies_sym",
    "davies_sym.topology.loader",
    "davies_sym.topology.model",
    "davies_sym.network.analysis",
    "davies_sym.efficiency.variants",
    "davies_sym.efficiency.variant_result",
    "davies_sym.efficiency.turning_conditions",
    "davies_sym.efficiency.several_inputs",
    "davies_sym.efficiency.virtual_power",
    "davies_sym.efficiency.virtual_power_balance",
    "davies_sym.efficiency.power_losses",
    "davies_sym.efficiency.parameters",
    "davies_sym.emit.python_module",
    "davies_sym.emit.plots",
    "davies_sym.emit.graph_drawing",
    "davies_sym.emit.latex",
    "davies_sym.emit.languages",
    "davies_sym.emit.evaluation",
    "davies_sym.topology.symbol_display",
)


def api_page() -> str:
    """The Python API reference: one mkdocstrings directive per module of
    `API_MODULES` (signatures and docstrings are read from the source by griffe)."""
    lines = ["# Python API", "", "Generated from the docstrings of the package.", ""]
    for name in API_MODULES:
        lines += [f"::: {name}", ""]
    return "\n".join(lines).rstrip("\n") + "\n"
