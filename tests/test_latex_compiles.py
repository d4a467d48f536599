"""The LaTeX documents (``derive FILE --latex``) compile with pdflatex and fit the page.

Every catalog train (a train with states: its states document; a train driven on two
shafts: its several-input document) and two long hand-written trains are compiled with
``pdflatex -interaction=nonstopmode -halt-on-error``; the log may show no overfull box
wider than :data:`TOLERANCE_PT`, no overfull vertical box and no undefined control
sequence.  Every numbered formula, read back from the .tex by the independent reader of
tests/hand/latex.py, equals the derived one at random points, the long ones broken over
lines included.  The prose has no program syntax and the symbols their display names.
The pdflatex tests are skipped when pdflatex is not installed.
"""

from __future__ import annotations

import functools
import os
import random
import re
import shutil
import subprocess
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import pytest
import sympy
from hand.latex import (
    LatexError,
    align_rows,
    display_latex,
    document_equations,
    equal_at_random_points,
    force_conditions,
    read_latex,
    with_angle_symbols,
)

import davies_sym
from davies_sym.efficiency.operating_point import OPERATING_SYMBOLS
from davies_sym.efficiency.several_inputs import LOAD_TORQUE, SeveralInputs, derive_several_inputs
from davies_sym.efficiency.variants import VariantSet, derive_variants
from davies_sym.emit.latex import PREAMBLE, latex_document, latex_states_document, variants_table
from davies_sym.emit.latex_lines import LINE_WIDTH, estimate_width, expression_lines, numbered
from davies_sym.emit.several_inputs_latex import several_inputs_latex
from davies_sym.emit.several_inputs_report import region_forces
from davies_sym.emit.variant_report import variant_forces
from davies_sym.topology.model import Train
from davies_sym.topology.states import train_in_state

from conftest import ROOT, TRAIN_FILES, catalog_path

PDFLATEX = shutil.which("pdflatex")
needs_pdflatex = pytest.mark.skipif(PDFLATEX is None, reason="pdflatex is not installed")

#: Overfull boxes up to this width are rounding at the margin, not a formula past it.
TOLERANCE_PT = 3.0

STEMS = sorted(os.path.splitext(os.path.basename(p))[0] for p in TRAIN_FILES)

#: A Wolfrom train with long radius names and viscous bearings: the formulas depend on
#: the input torque and speed and run to a page, so every kind of line break is needed
#: (sums, products at \cdot, parentheses across lines, reciprocal denominators).
LONG_WOLFROM = """\
format: 1
name: Wolfrom train with viscous bearings (long formulas)
links:
  0: {description: "housing with the front ring"}
  s: {description: "sun shaft, input"}
  p: {description: "stepped planet"}
  c: {description: "carrier, free"}
  o: {description: "rear ring, output"}
reference: 0
gears:
  S: {link: s, radius: rsunwheelpitch}
  P1: {link: p, radius: rfrontplanetpitch}
  R1: {link: 0, radius: rfrontringpitch, internal: true}
  P2: {link: p, radius: rrearplanetpitch}
  R2: {link: o, radius: rrearringpitch, internal: true}
couplings:
  A: {type: revolute, links: [0, s], friction: {viscous: b_A}}
  B: {type: revolute, links: [0, o], friction: {viscous: b_B}}
  K: {type: revolute, links: [0, c], at: 0}
  C: {type: mesh, gears: [S, P1]}
  D: {type: mesh, gears: [R1, P1]}
  E: {type: mesh, gears: [R2, P2]}
  F: {type: revolute, links: [p, c]}
ports: {input: A, output: B}
"""


@dataclass(frozen=True)
class Document:
    """An emitted document with what it was written from."""

    text: str
    #: (symbols, variant set) of each section: the train's, or each state's.
    sections: tuple[tuple[list[sympy.Symbol], VariantSet], ...] = ()
    several: SeveralInputs | None = None


def _one_input(train: Train) -> Document:
    if not train.states:
        vs = derive_variants(train)
        return Document(latex_document(vs), ((_symbols(train), vs),))
    states = [train_in_state(train, st) for st in train.states]
    sets = [derive_variants(t) for t in states]
    return Document(latex_states_document(sets), tuple((_symbols(t), vs) for t, vs in zip(states, sets, strict=True)))


def _symbols(train: Train) -> list[sympy.Symbol]:
    return [*train.symbols.values(), *OPERATING_SYMBOLS]


def _document(train: Train) -> Document:
    if (train.degrees_of_freedom or 1) > 1:
        si = derive_several_inputs(train)
        return Document(several_inputs_latex(si), several=si)
    return _one_input(train)


@functools.cache
def catalog_document(stem: str) -> Document:
    """The document ``derive catalog/STEM.yaml --latex`` writes (derived once per run)."""
    return _document(davies_sym.load(catalog_path(stem)))


@functools.cache
def own_document() -> Document:
    return _document(davies_sym.loads(LONG_WOLFROM, "long_wolfrom.yaml"))


def compile_log(text: str, directory: Path) -> str:
    """pdflatex's log of ``text``; the run must succeed."""
    (directory / "doc.tex").write_text(text, encoding="utf-8")
    result = subprocess.run(
        [PDFLATEX or "pdflatex", "-interaction=nonstopmode", "-halt-on-error", "doc.tex"],
        cwd=directory,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    log = (directory / "doc.log").read_text(encoding="latin-1")
    assert result.returncode == 0, log[-3000:]
    return log


def layout_problems(log: str) -> list[str]:
    """Overfull boxes past the tolerance, overfull vertical boxes, undefined commands and
    errors in a pdflatex log."""
    problems = [
        m.group(0)
        for m in re.finditer(r"Overfull \\hbox \((\d+(?:\.\d+)?)pt too wide\)[^\n]*", log)
        if float(m.group(1)) > TOLERANCE_PT
    ]
    problems += re.findall(r"Overfull \\vbox[^\n]*", log)
    problems += re.findall(r"Undefined control sequence[^\n]*", log)
    problems += re.findall(r"^! [^\n]*", log, flags=re.MULTILINE)
    return problems


def prose_problems(text: str) -> list[str]:
    """Program syntax in a document: ``**``, ``<=``, ``>=`` anywhere, ``<`` or ``>``
    outside mathematics, ``*`` other than in starred commands, environments and
    ``\\eta^*``."""
    problems = [token for token in ("**", "<=", ">=") if token in text]
    body = text.split(r"\begin{document}", 1)[1]  # the preamble's column types use > and <
    prose = re.sub(r"\\begin\{(equation\*?|align\*)\}.*?\\end\{\1\}", " ", body, flags=re.DOTALL)
    prose = re.sub(r"\$[^$]*\$", " ", prose)
    problems += [f"{ch!r} outside mathematics" for ch in "<>" if ch in prose]
    starless = re.sub(r"\\[A-Za-z]+\*|\{(?:equation|align)\*\}|\\eta\^\*", "", body)
    problems += ["'*' outside a starred command"] if "*" in starless else []
    return problems


def sections(document: Document) -> list[str]:
    """The text of each state's section (the whole document without states)."""
    parts = document.text.split(r"\section*{")[1:]
    assert len(parts) == max(len(document.sections), 1)
    return parts


def check_read_back(document: Document) -> int:
    """Every numbered formula and every loaded-force condition, read back from the text,
    equals the derived one at random points; the number of formulas read."""
    read = 0
    if document.several is not None:
        si = document.several
        symbols = [*si.train.symbols.values(), *si.speeds, LOAD_TORQUE]
        equations = document_equations(document.text, "\\eta^*")
        assert sorted(equations) == [r.number for r in si.regions]
        for r in si.regions:
            assert equal_at_random_points(read_latex(equations[r.number], symbols), r.efficiency), r.number
            section = document.text.split(rf"\paragraph{{Region ({r.number})}}")[1].split(r"\paragraph")[0]
            _check_forces(
                force_conditions(section), region_forces(r) if any(x.reversed for x in si.regions) else [], symbols
            )
            read += 1
        return read
    for text, (symbols, vs) in zip(sections(document), document.sections, strict=True):
        equations = document_equations(text)
        assert sorted(equations) == [v.number for v in vs.variants]
        for v in vs.variants:
            shown = with_angle_symbols(read_latex(equations[v.number], symbols), vs.train)
            assert equal_at_random_points(shown, v.efficiency), v.name
            section = text.split(rf"\paragraph{{Variant ({v.number})}}")[1].split(r"\paragraph")[0]
            _check_forces(force_conditions(section), variant_forces(vs, v), symbols)
            read += 1
        for v in vs.excluded:  # proved empty: the reason, no formula
            section = text.split(rf"\paragraph{{Variant ({v.number})}}")[1].split(r"\paragraph")[0]
            assert "Never holds" in section and r"\tag" not in section and r"\eta" not in section
        _check_definitions(text, vs, symbols)
    return read


def _check_forces(
    shown: list[tuple[str, str]], expected: list[tuple[str, sympy.Expr, int]], symbols: list[sympy.Symbol]
) -> None:
    assert len(shown) == len(expected)
    for (body, relation), (_, force, sign) in zip(shown, expected, strict=True):
        assert relation == (">" if sign > 0 else "<")
        assert equal_at_random_points(read_latex(body, symbols), force), body


def _check_definitions(text: str, vs: VariantSet, symbols: list[sympy.Symbol]) -> None:
    """Each definition (``where X is the ...``), read back, equals its expression in
    floating point at random points (they may hold logarithms and sines)."""
    blocks = re.findall(
        r"where \$([^$]+)\$ is the [^\n]*:\n(\\begin\{equation\*\}\n.*?\n\\end\{equation\*\}|"
        r"\\begin\{align\*\}\n.*?\n\\end\{align\*\})",
        text,
        flags=re.DOTALL,
    )
    assert len(blocks) == len(vs.train.definitions)
    rng = random.Random(7)
    for (name, block), d in zip(blocks, vs.train.definitions, strict=True):
        body = block.split("\n", 1)[1].rsplit("\n", 1)[0]
        rows = align_rows(body) if block.startswith(r"\begin{align*}") else [tuple(body.split(" = ", 1))]
        assert len(rows) == 1 and rows[0][0] == name == display_latex(str(d.symbol))
        shown = read_latex(rows[0][1], symbols)
        for _ in range(3):
            point = {s: sympy.Rational(rng.randint(1, 97), 100) for s in d.expression.free_symbols}
            want = sympy.N(d.expression.xreplace(point), 30)
            assert abs(sympy.N(shown.xreplace(point), 30) - want) <= 1e-20 * (1 + abs(want)), (name, rows[0][1])


# --- the reader and the line breaker, without pdflatex -------------------------------------------------------


def test_reader_takes_display_names_and_broken_lines() -> None:
    """The reader's own display rule (rp1 -> r_{p1}, eta_C_1_2 -> \\eta_{C,1,2}), a
    formula broken over align* lines read as one, and a broken parenthesis that does not
    reopen on the next line refused."""
    rp1, rs, eta = sympy.symbols("rp1 rs eta_C", positive=True)
    assert [display_latex(n) for n in ("rp1", "N4", "eta_C", "eta_12", "eta_C_1_2", "mu", "r", "tau_in", "pin")] == [
        "r_{p1}",
        "N_{4}",
        r"\eta_{C}",
        r"\eta_{12}",
        r"\eta_{C,1,2}",
        r"\mu",
        "r",
        r"\tau_{in}",
        "p_{in}",
    ]
    symbols = [rp1, rs, eta]
    assert read_latex(r"\eta_{C} r_{p1} + r_{s}", symbols) == eta * rp1 + rs
    assert read_latex(r"\eta_{C} rp_{1} + rs", symbols) == eta * rp1 + rs  # sympy's spelling still read
    broken = r"\eta_{C} \left(r_{p1} \right. \\ &\quad \left. + r_{s}\right) \\ &\quad \cdot r_{s}"
    assert read_latex(broken, symbols) == eta * (rp1 + rs) * rs
    assert read_latex(r"\left(r_{p1} + r_{s}\right)^{-1} \log\left(r_{s}\right)", symbols) == sympy.log(rs) / (rp1 + rs)
    for wrong in (broken.replace(r"\left. ", ""), broken.replace(r"\right. ", ""), r"r_{p1} \right. r_{s}"):
        with pytest.raises(LatexError):
            read_latex(wrong, symbols)


def test_long_sums_break_into_balanced_lines_that_read_back() -> None:
    """A sum of products too wide for a line breaks between terms; a long sum inside a
    product breaks inside its parentheses with \\right. and \\left. on every line; each
    line's estimate fits its budget and the lines read back to the expression."""
    names = sympy.symbols("rsunwheelpitch rfrontplanetpitch rrearplanetpitch eta_C eta_D", positive=True)
    a, b, c, e, f = names
    long_sum = sympy.expand((a + b + c + e + f) ** 3)
    for expr in (long_sum, (a - b) * long_sum / (a + c), -long_sum / ((a + b) * long_sum.subs(a, c))):
        lines = expression_lines(expr)
        assert len(lines) > 1
        for level, text in lines:
            assert estimate_width(text) <= LINE_WIDTH - 11 * level + 1e-9, text
            assert text.count(r"\left") == text.count(r"\right") and text.count("{") == text.count("}")
        joined = " \\\\ &\\quad ".join(text for _, text in lines)
        assert equal_at_random_points(read_latex(joined, names), expr)


def test_numbered_formulas_short_long_and_without_denominator() -> None:
    """A short formula stays one tagged ``equation``; a long fraction becomes
    eta_{(n)} = N/D with N and D below; a long polynomial (and its negative) is broken
    after eta_{(n)} itself; each reads back by its tag."""
    names = sympy.symbols("rsunwheelpitch rfrontplanetpitch rrearplanetpitch eta_C eta_D", positive=True)
    a, b, c, e, f = names
    long_sum = sympy.expand((a + b + c + e + f) ** 3)
    cases = {1: a / (b + c), 2: long_sum / (a + b), 3: long_sum, 4: -long_sum, 5: -long_sum / (a * long_sum.subs(a, b))}
    text = "\n".join(line for number, expr in cases.items() for line in numbered(r"\eta", expr, number))
    assert text.count(r"\begin{equation}") == 1 and text.count(r"\begin{align*}") == 4
    assert r"N_{(2)} &= " in text and r"N_{(3)}" not in text and r"\eta_{(4)} &= - " in text
    equations = document_equations(text)
    assert sorted(equations) == sorted(cases)
    for number, expr in cases.items():
        assert equal_at_random_points(read_latex(equations[number], names), expr), number


def _display_names_only(document: Document) -> None:
    """Every symbol of the formulas is shown by its display name (``r_{r1}``), never by
    sympy's own spelling where that differs (``rr_{1}``)."""
    shown = set()
    for _, vs in document.sections:
        for v in vs.variants:
            shown |= v.efficiency.free_symbols
    assert shown
    math = " ".join(
        re.findall(r"\\begin\{(?:equation\*?|align\*)\}(.*?)\\end", document.text, flags=re.DOTALL)
        + re.findall(r"\$([^$]*)\$", document.text)
    )
    for s in shown:
        assert display_latex(s.name) in math, s
        if sympy.latex(s) != display_latex(s.name):
            assert not re.search(rf"(?<![A-Za-z\\]){re.escape(sympy.latex(s))}(?![A-Za-z_])", math), s


def test_simpson_shows_display_names_and_no_program_syntax() -> None:
    """simpson (states document): the radii as the references write them (r_{r1}, not
    rr_{1}), no ``**``, no ``<=``, no relation outside mathematics."""
    document = catalog_document("simpson")
    _display_names_only(document)
    assert not prose_problems(document.text), prose_problems(document.text)


def test_simpson_names_its_planet_radius_r_p1() -> None:
    """With the planet radii among the parameters (``independent: [rs, rp1, rp2]``),
    Simpson's formulas show Laus's r_{p1}, never sympy's rp_{1}, and read back."""
    text = re.sub(
        r"(?m)^independent: .*$",
        "independent: [rs, rp1, rp2]",
        Path(catalog_path("simpson")).read_text(encoding="utf-8"),
    )
    document = _document(davies_sym.loads(text, "simpson_planets.yaml"))
    assert "r_{p1}" in document.text and "rp_{1}" not in document.text
    _display_names_only(document)
    assert not prose_problems(document.text)
    assert check_read_back(document) > 0


# --- pdflatex -------------------------------------------------------------------------------------------------


@needs_pdflatex
def test_tuplin_compiles_and_fits(tmp_path: Path) -> None:
    """The quick case: Tuplin's document compiles without layout problems."""
    assert not layout_problems(compile_log(catalog_document("tuplin").text, tmp_path))


@pytest.mark.slow
@needs_pdflatex
@pytest.mark.parametrize("stem", STEMS)
def test_catalog_document_compiles_fits_and_reads_back(stem: str, tmp_path: Path) -> None:
    """Each catalog train's document: pdflatex succeeds, nothing runs past the margin,
    every formula reads back to the derived one, no program syntax in the prose."""
    document = catalog_document(stem)
    assert not layout_problems(compile_log(document.text, tmp_path)), stem
    assert not prose_problems(document.text), stem
    assert check_read_back(document) > 0


@pytest.mark.slow
@needs_pdflatex
def test_long_formulas_are_broken_to_fit_and_read_back(tmp_path: Path) -> None:
    """The hand-written Wolfrom train with viscous bearings: its efficiencies and
    loaded-force conditions run over many lines (N and D below the equation, products
    broken at \\cdot, parentheses across lines); the document fits the page and every
    formula reads back."""
    document = own_document()
    text = document.text
    assert r"\eta_{(1)} &= " in text and r"N_{(1)} &= " in text and r"\right. \\" in text
    assert re.search(r"^&\\quad \\cdot ", text, flags=re.MULTILINE)
    assert text.count(r"\tag{") == len(document.sections[0][1].variants)
    assert not layout_problems(compile_log(text, tmp_path))
    assert not prose_problems(text)
    assert check_read_back(document) == len(document.sections[0][1].variants)


@pytest.mark.slow
@needs_pdflatex
def test_lossy_two_input_document_fits(tmp_path: Path) -> None:
    """The SR20 with every kind of loss (tests/test_several_inputs_outputs.py): its long
    region efficiencies and torques are broken to fit, and read back."""
    from test_several_inputs_outputs import LOSSY

    document = _document(davies_sym.loads(LOSSY, "sr20_lossy.yaml"))
    assert r"\eta^*_{(" in document.text
    assert not layout_problems(compile_log(document.text, tmp_path))
    assert not prose_problems(document.text)
    assert check_read_back(document) > 0


@pytest.mark.slow
@needs_pdflatex
def test_out_dir_documents_compile(tmp_path: Path) -> None:
    """``derive FILE ... --out DIR`` (as derivations/ is written) gives .tex files that
    compile and fit."""
    from harness.helpers import run_main

    out = tmp_path / "out"
    out.mkdir()
    files = [catalog_path(stem) for stem in ("tuplin", "simpson", "sr20_differential", "buckingham_pair")]
    result = run_main([*files, "--out", str(out), "--quiet"])
    assert result.returncode == 0, result.stderr
    for tex in sorted(out.glob("*.tex")):
        work = tmp_path / tex.stem
        work.mkdir()
        assert not layout_problems(compile_log(tex.read_text(encoding="utf-8"), work)), tex.name


@needs_pdflatex
def test_wide_variants_table_fits(tmp_path: Path) -> None:
    """The widest variants table: four turning conditions, four meshes (one idle) with
    long gear names and a status on every row, in a table of its own; and the real
    tests/data/dependent_conditions.yaml train (two conditions, four meshes)."""
    conditions = [SimpleNamespace(name=f"c{k}") for k in range(1, 5)]
    roles = [
        SimpleNamespace(coupling=f"M{k}", idle=k == 4, flow=SimpleNamespace(gears=(f"Sun{k}", f"Planet{k}")))
        for k in range(1, 5)
    ]
    rows = []
    for n in range(16):
        signs = {c.name: 1 if n >> k & 1 else -1 for k, c in enumerate(conditions)}
        rows.append(
            SimpleNamespace(
                number=n + 1,
                input="A",
                output="B",
                signs=signs,
                feasible=n % 3 != 0,
                first_drives={r.coupling: n % 2 == 0 for r in roles},
                self_locking_point={} if n % 2 else None,
                reversed_forces=frozenset({"M1", "M2"}) if n % 4 == 0 else frozenset(),
            )
        )
    wide = SimpleNamespace(conditions=conditions, roles=roles, variants=rows, listed=rows)
    text = "\n".join([*PREAMBLE, *variants_table(wide), r"\end{document}", ""])  # type: ignore[arg-type]
    assert "Planet3" in text and "M4: idle" in text
    assert not layout_problems(compile_log(text, tmp_path))
    real = _document(davies_sym.load(os.path.join(ROOT, "tests", "data", "dependent_conditions.yaml")))
    (tmp_path / "real").mkdir()
    assert not layout_problems(compile_log(real.text, tmp_path / "real"))
    assert check_read_back(real) == 6  # of 8 combinations, two no design reaches
