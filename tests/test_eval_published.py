"""``--eval published`` evaluates the design of a file's first published check, and an
evaluation that lacks values says so where the file holds one."""

from __future__ import annotations

from pathlib import Path

from harness.helpers import assert_refused, run_main

from conftest import catalog_path


def test_published_design_of_tuplin_is_laus_eq_76() -> None:
    """Laus 2011, section 3.4.1.6: eq. (76) gives 0.9462 for Tuplin's train (the file's first check)."""
    result = run_main([catalog_path("tuplin"), "--eval", "published", "--quiet"])
    assert result.returncode == 0, result.describe()
    assert round(float(result.stdout.split()[-1]), 4) == 0.9462


def test_a_value_after_published_replaces_the_published_one() -> None:
    published = run_main([catalog_path("tuplin"), "--eval", "published", "eta_C=0.9", "--quiet"])
    spelled = run_main(
        [catalog_path("tuplin"), "--eval", "r1=40", "r2=60", "r3=15", "eta_C=0.9", "eta_D=0.99", "--quiet"]
    )
    assert published.returncode == spelled.returncode == 0, published.describe()
    assert published.stdout == spelled.stdout
    assert float(published.stdout.split()[-1]) < 0.9462


def test_missing_values_point_at_the_published_design() -> None:
    result = run_main([catalog_path("humpage"), "--eval", "--quiet"])
    assert_refused(result, catalog_path("humpage"), ("--eval",), line=False)
    assert "missing values for" in result.stderr and "--eval published" in result.stderr


def test_published_without_a_published_design_is_refused(tmp_path: Path) -> None:
    text = Path(catalog_path("simple_pair")).read_text(encoding="utf-8")
    train = tmp_path / "pair.yaml"
    train.write_text(text[: text.index("expected:")], encoding="utf-8")
    result = run_main([str(train), "--eval", "published", "--quiet"])
    assert_refused(result, train, ("--eval",), line=False)
    assert "expected:" in result.stderr
    plain = run_main([str(train), "--eval", "--quiet"])
    assert plain.returncode == 2 and "--eval published" not in plain.stderr
