"""The documentation site, built as a user builds it (``mkdocs build --strict`` with the
checkout's ``mkdocs.yml``): every catalog page shows every variant, its formula read back
from the MathML the browser renders; published numbers beside derived ones, with the
explanation where they differ; and the site opened from disk in headless Chromium loads
every page without a single request leaving the machine, renders math as math and has
no dead navigation link."""

from __future__ import annotations

import ast
import fcntl
import glob
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import sympy
import yaml
from hand.latex import equal_at_random_points, read_latex, with_angle_symbols
from hand.mathml import annotation, math_elements, read_mathml

import davies_sym
from davies_sym.efficiency.several_inputs import LOAD_TORQUE, derive_several_inputs
from davies_sym.efficiency.variants import derive_variants
from davies_sym.topology.states import train_in_state

from conftest import CATALOG, ROOT, TRAIN_FILES

pytestmark = pytest.mark.slow

#: Neither MkDocs' nor the theme's banner about MkDocs 2 is a build warning.
BUILD_ENVIRONMENT = {**os.environ, "NO_MKDOCS_2_WARNING": "1", "DISABLE_MKDOCS_2_WARNING": "true"}


@pytest.fixture(scope="session")
def site(tmp_path_factory) -> Path:
    """The site, built once for every test worker (the workers share the folder; a lock
    makes the others wait for the first)."""
    base = tmp_path_factory.getbasetemp()
    # Under xdist each worker's folder lies in the session's folder, which they share.
    shared = base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base
    out = shared / "docs_site"
    with open(shared / "docs_site.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not (out / "ok").exists():
            result = subprocess.run(
                [
                    sys.executable,
                    "-m",
                    "mkdocs",
                    "build",
                    "--strict",
                    "-f",
                    os.path.join(ROOT, "mkdocs.yml"),
                    "-d",
                    str(out / "site"),
                ],
                capture_output=True,
                text=True,
                check=False,
                env=BUILD_ENVIRONMENT,
                cwd=ROOT,
            )
            (out / "log").parent.mkdir(parents=True, exist_ok=True)
            (out / "log").write_text(result.stdout + result.stderr)
            if result.returncode == 0:
                (out / "ok").write_text("")
    log = (out / "log").read_text()
    assert (out / "ok").exists(), log
    return out / "site"


def test_site_builds_in_strict_mode_without_warnings(site):
    """mkdocs build --strict from the checkout's mkdocs.yml: a broken link or a missing
    image fails; nothing of the log is a warning."""
    log = (site.parent / "log").read_text()
    assert not [line for line in log.splitlines() if "WARNING" in line], log
    assert (site / "catalog" / "humpage.html").exists()
    assert (site / "api.html").exists() and (site / "cli.html").exists()


def test_navigation_lists_every_catalog_train():
    with open(os.path.join(ROOT, "mkdocs.yml"), encoding="utf-8") as handle:
        config = yaml.safe_load(handle)
    catalog = next(entry["Catalog"] for entry in config["nav"] if isinstance(entry, dict) and "Catalog" in entry)
    stems = sorted(os.path.splitext(os.path.basename(p))[0] for p in glob.glob(os.path.join(CATALOG, "*.yaml")))
    assert catalog == ["catalog/index.md", *(f"catalog/{s}.md" for s in stems)]


def _display_equations(page: str) -> list:
    return [m for m in math_elements(page) if m.attrs.get("display") == "block"]


def _state_sections(page: str) -> dict[str, str]:
    """The page's "State NAME" sections by state name."""
    parts = re.split(r'<h2 id="[^"]*">State ([^:<]+)', page)
    return dict(zip(parts[1::2], parts[2::2], strict=True))


def test_every_catalog_page_shows_every_variant_as_math(site):
    """Each variant's formula is read back twice from the page: from the presentation
    MathML (what the browser draws) and from its LaTeX annotation; both equal the
    variant's efficiency at random points."""
    for path in TRAIN_FILES:
        stem = os.path.splitext(os.path.basename(path))[0]
        page = (site / "catalog" / f"{stem}.html").read_text(encoding="utf-8")
        train = davies_sym.load(path)
        assert f"img/{stem}_graph.png" in page and (site / "catalog" / "img" / f"{stem}_graph.png").exists()
        visible = re.sub(r"<annotation.*?</annotation>", "", page, flags=re.S)
        assert "$$" not in visible and "\\frac" not in visible, stem
        if (train.degrees_of_freedom or 1) > 1:
            si = derive_several_inputs(train)
            formulas = [r.efficiency for r in si.regions]
            symbols = [*train.symbols.values(), *si.speeds, LOAD_TORQUE]
            sections = {None: page}
            expected = {None: formulas}
        else:
            symbols = list(train.symbols.values())
            names = [st.name for st in train.states] or [None]
            sections = _state_sections(page) if train.states else {None: page}
            assert list(sections) == names, stem
            expected = {}
            for name in names:
                one = train_in_state(train, train.state(name)) if name else train
                expected[name] = [v.efficiency for v in derive_variants(one).variants]
        for key, formulas in expected.items():
            shown = [m for m in _display_equations(sections[key]) if annotation(m).startswith("\\eta_{(")]
            assert len(shown) == len(formulas), (stem, key)
            for element, formula in zip(shown, formulas, strict=True):
                shown = with_angle_symbols(read_mathml(element, symbols), train)
                assert equal_at_random_points(shown, formula), (stem, key)
                tex = annotation(element).split("=", 1)[1]
                assert equal_at_random_points(with_angle_symbols(read_latex(tex, symbols), train), formula), (
                    stem,
                    key,
                    tex,
                )
        assert "**differs**" not in page and "<strong>differs</strong>" not in page, stem


def test_humpage_page_states_laus_number_and_why_it_differs(site):
    """Laus 2011 sec. 3.5.1.2 reports 42.5 %; the catalog's consistent geometry gives
    0.63265.  The page lists both: Laus's number as published and different, with the
    explanation (his printed planet axis, eq. (80)), and 0.63265 as a regression value,
    not a published one."""
    page = (site / "catalog" / "humpage.html").read_text(encoding="utf-8")
    rows = re.findall(r"<tr>(.*?)</tr>", page, flags=re.S)
    laus = next(r for r in rows if "0.425" in r)
    own = next(r for r in rows if "0.63265 (± 5e-05)" in r)
    assert "differs, explained below" in laus and "Laus 2011, section 3.5.1.2" in laus and "<td>0.632647</td>" in laus
    assert "regression, not published" in own and "<strong>regression</strong>" in own
    assert "Why the derived value differs from 0.425" in page and "eq. (80)" in page


def test_literature_figures_are_on_their_pages(site):
    """Chen Fig. 4.13 (Litvin, efficiency against N4) and Laus Fig. 11 (Humpage, mesh C)."""
    litvin = (site / "catalog" / "litvin_face_drive.html").read_text(encoding="utf-8")
    humpage = (site / "catalog" / "humpage.html").read_text(encoding="utf-8")
    assert "img/litvin_face_drive_literature_N4.png" in litvin and "Fig. 4.13" in litvin
    assert "img/humpage_laus_fig11.png" in humpage and "Fig. 11" in humpage
    for name in ("litvin_face_drive_literature_N4.png", "humpage_laus_fig11.png"):
        assert (site / "catalog" / "img" / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_reference_pages(site):
    """The command line page carries the parser's help; the API page is rendered from the
    docstrings by mkdocstrings (no reStructuredText roles left, signatures shown)."""
    cli = (site / "cli.html").read_text(encoding="utf-8")
    assert "--plot [NAME=START:STOP]" in cli and "--task NAME" in cli and "--python OUT.py" in cli
    api = (site / "api.html").read_text(encoding="utf-8")
    assert 'id="davies_sym.efficiency.variants.derive_variants"' in api
    assert 'id="davies_sym.efficiency.variants.VariantSet.evaluate"' in api
    for role in (":func:", ":class:", ":mod:", ":data:", ":meth:", "doctest: +SKIP"):
        assert role not in api, role
    topology = (site / "topology.html").read_text(encoding="utf-8")
    assert "Topology language" in topology or "topology" in topology.lower()


def test_package_docstring_example_runs():
    """The example of the package docstring (the API page's first code) gives what its
    comments say: Laus eq. (136), and 49/50 at eta_C = 0.98 (a pair with ordinary
    efficiency eta_C has that efficiency)."""
    code = re.search(r"```python\n(.*?)```", davies_sym.__doc__ or "", flags=re.S)
    assert code is not None
    tree = ast.parse(code.group(1))
    namespace: dict[str, object] = {}
    values = []
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        for statement in tree.body:
            if isinstance(statement, ast.Expr):
                values.append(eval(compile(ast.Expression(statement.value), "docstring", "eval"), namespace))
            else:
                exec(compile(ast.Module([statement], []), "docstring", "exec"), namespace)
    finally:
        os.chdir(cwd)
    r1, r2, zeta = (
        davies_sym.load(os.path.join(CATALOG, "simple_pair.yaml")).symbols[n] for n in ("r1", "r2", "zeta_C")
    )
    assert "# r1*(r2 - zeta_C)/(r2*(r1 + zeta_C))" in code.group(1) and "# 49/50" in code.group(1)
    assert sympy.simplify(values[0] - r1 * (r2 - zeta) / (r2 * (r1 + zeta))) == 0
    assert values[-1] == sympy.Rational(49, 50)


# --- the site in a real browser -------------------------------------------------------


def _browser():
    """Headless Chromium driven by Selenium, every network request logged, no proxy that
    answers (so nothing could leave even if a page asked)."""
    webdriver = pytest.importorskip("selenium.webdriver")
    from selenium.webdriver.chrome.service import Service

    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_path = shutil.which("chromedriver")
    if chromium is None or driver_path is None:
        pytest.skip("chromium and chromedriver are not installed (.ci/run installs them)")
    options = webdriver.ChromeOptions()
    options.binary_location = chromium
    for argument in (
        "--headless=new",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-dev-shm-usage",
        "--proxy-server=127.0.0.1:9",
        "--window-size=1280,1000",
    ):
        options.add_argument(argument)
    options.set_capability("goog:loggingPrefs", {"performance": "ALL", "browser": "ALL"})
    os.environ.setdefault("SE_OFFLINE", "true")  # Selenium Manager must not look for drivers online
    return webdriver.Chrome(options=options, service=Service(driver_path))


@pytest.fixture(scope="module")
def browser():
    driver = _browser()
    yield driver
    driver.quit()


_MATH_STATE = """
return Array.from(document.querySelectorAll('math')).map(m => {
  const r = m.getBoundingClientRect();
  return [m instanceof MathMLElement, r.width, r.height, m.getAttribute('display')];
});
"""

_FRACTION_LAYOUT = """
const f = document.querySelector('math mfrac');
if (!f) return null;
const [num, den] = f.children;
return [num.getBoundingClientRect().bottom, den.getBoundingClientRect().top];
"""

_LINKS = """
return Array.from(document.querySelectorAll('a[href]')).map(a => [a.href, a.closest('nav') !== null]);
"""


def test_every_page_loads_offline_with_math_and_live_links(site, browser):
    """Every page of the site, opened from disk (file://): it loads, no request goes
    anywhere but the site's own files, every <math> is a MathML element with a size,
    fractions are laid out (numerator above denominator), no raw TeX is visible, and
    every link of the navigation and of the page leads to a file of the site."""
    # 404.html is the web server's error page: its links are absolute ("/assets/..."), so
    # that it works at any address of a served site; from disk no link leads to it.
    pages = sorted(p for p in site.rglob("*.html") if p.name != "404.html")
    # Sixteen hand-written or reference pages (the atlas and its definitions the last
    # two), the catalog index and one page per catalog file.
    assert len(pages) == 18 + len(glob.glob(os.path.join(CATALOG, "*.yaml")))
    assert site / "search.html" in pages
    fraction_pages = 0
    for page in pages:
        browser.get(page.as_uri())
        title = browser.title
        assert title and "davies_sym" in title, page
        for entry in browser.get_log("performance"):
            message = json.loads(entry["message"])["message"]
            if message["method"] == "Network.requestWillBeSent":
                url = message["params"]["request"]["url"]
                assert url.split(":", 1)[0] in ("file", "data", "blob", "about"), (page, url)
        severe = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
        assert not severe, (page, severe)
        maths = browser.execute_script(_MATH_STATE)
        for is_mathml, width, height, _ in maths:
            assert is_mathml and width > 0 and height > 0, page
        if maths:
            text = browser.execute_script("return document.body.innerText")
            assert "\\frac" not in text and "$$" not in text, page
        layout = browser.execute_script(_FRACTION_LAYOUT)
        if layout is not None:
            numerator_bottom, denominator_top = layout
            assert numerator_bottom <= denominator_top + 1, page
            fraction_pages += 1
        for href, _in_nav in browser.execute_script(_LINKS):
            if not href.startswith("file://"):
                assert href.startswith(("http://", "https://", "mailto:")), (page, href)
                continue
            target = Path(href[len("file://") :].split("#", 1)[0].split("?", 1)[0])
            assert target.is_file(), (page, href)
    assert fraction_pages >= 10
