"""The documentation site: every catalog page with every variant, the literature
figures (Chen Fig. 4.13, Laus Fig. 11), and a strict MkDocs build without warnings."""

from __future__ import annotations

import glob
import os
import re
import subprocess
import sys

import pytest
from docs_site import BUILD_ENVIRONMENT, stage
from hand.latex import equal_at_random_points, read_latex

import davies_sym
from davies_sym.efficiency.variants import derive_variants
from davies_sym.topology.states import train_in_state

from conftest import CATALOG, ROOT, read_text

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def staged(tmp_path_factory):
    staging = tmp_path_factory.mktemp("docs")
    config = stage(ROOT, str(staging), lambda message: None)
    return staging, config


def test_every_catalog_train_has_a_page_showing_every_variant(staged):
    staging, _ = staged
    for path in sorted(glob.glob(os.path.join(CATALOG, "*.yaml"))):
        stem = os.path.splitext(os.path.basename(path))[0]
        page = os.path.join(staging, "docs", "catalog", f"{stem}.md")
        assert os.path.exists(page), stem
        text = read_text(page)
        train = davies_sym.load(path)
        assert f"img/{stem}_graph.png" in text and os.path.exists(os.path.join(staging, "docs", "catalog", "img",
                                                                                 f"{stem}_graph.png"))
        if (train.degrees_of_freedom or 1) > 1:
            assert "degrees of freedom" in text
            continue
        if train.states:
            sections = _state_sections(text)
            assert list(sections) == [st.name for st in train.states], stem
        else:
            sections = {None: text}
        for state, section in sections.items():
            vs = derive_variants(train_in_state(train, train.state(state)) if state else train)
            shown = re.findall(r"^\$\$\\eta_\{\((\d+)\)\} = (.*)\$\$$", section, flags=re.MULTILINE)
            assert [number for number, _ in shown] == [str(v.number) for v in vs.variants], (stem, state)
            for (_, latex), v in zip(shown, vs.variants, strict=True):
                # The LaTeX read back (not printed again) equals the variant's formula.
                assert equal_at_random_points(read_latex(latex, train.symbols.values()), v.efficiency), \
                    (stem, state, v.name, latex)
        assert "**differs**" not in text, stem


def _state_sections(text: str) -> dict[str, str]:
    """The page's "## State NAME" sections by state name."""
    parts = re.split(r"^## State ([^:\n]+).*$", text, flags=re.MULTILINE)
    return dict(zip(parts[1::2], parts[2::2], strict=True))


def test_literature_figures_are_on_their_pages(staged):
    """Chen Fig. 4.13 (Litvin, efficiency against N4) and Laus Fig. 11 (Humpage, mesh C)."""
    staging, _ = staged
    img = os.path.join(staging, "docs", "catalog", "img")
    litvin = read_text(os.path.join(staging, "docs", "catalog", "litvin_face_drive.md"))
    humpage = read_text(os.path.join(staging, "docs", "catalog", "humpage.md"))
    assert "img/litvin_face_drive_literature_N4.png" in litvin and "Fig. 4.13" in litvin
    assert "img/humpage_laus_fig11.png" in humpage and "Fig. 11" in humpage
    for name in ("litvin_face_drive_literature_N4.png", "humpage_laus_fig11.png"):
        with open(os.path.join(img, name), "rb") as handle:
            assert handle.read(8) == b"\x89PNG\r\n\x1a\n"


def test_reference_pages(staged):
    staging, _ = staged
    cli = read_text(os.path.join(staging, "docs", "cli.md"))
    assert "--plot NAME=START:STOP" in cli and "--python OUT.py" in cli
    api = read_text(os.path.join(staging, "docs", "api.md"))
    assert "## `davies_sym.efficiency.variants`" in api and "### `derive_variants`" in api
    assert read_text(os.path.join(staging, "docs", "topology.md")) == read_text(os.path.join(ROOT, "docs",
                                                                                          "topology.md"))


def test_site_builds_in_strict_mode(staged, tmp_path):
    """mkdocs build --strict: a broken link or a missing image fails."""
    _, config = staged
    result = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f", config, "-d",
                             str(tmp_path / "site")], capture_output=True, text=True, check=False,
                            env=BUILD_ENVIRONMENT)
    assert result.returncode == 0, result.stdout + result.stderr
    assert not [line for line in result.stderr.splitlines() if line.startswith("WARNING")], result.stderr
    assert (tmp_path / "site" / "catalog" / "humpage" / "index.html").exists()
