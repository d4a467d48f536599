"""`--emit modelica` of a train driven at one port holds ``model Gear``: the train between
two rotational flanges of the Modelica Standard Library, its efficiency chosen from the
power the output flange takes in, as the FMU chooses it.  Its equations are read here
and evaluated in Python (the Modelica ``if .. then .. else`` as Python's), against the
Python formula module's efficiency of the input port that drives; the whole file is
parsed by modelicalang's Modelica 3.5 grammar."""

from __future__ import annotations

import re

import pytest
from harness.helpers import run_main

from davies_sym.efficiency.variants import derive_variants
from davies_sym.emit.formula_code import compiled_module
from davies_sym.emit.python_module import python_module
from davies_sym.topology.loader import load

from conftest import catalog_path


def _modelica(name: str) -> str:
    result = run_main([catalog_path(name), "--emit", "modelica", "--quiet"])
    assert result.returncode == 0, result.describe()
    return result.stdout


def _model(text: str) -> str:
    return re.search(r"  model Gear .*?  end Gear;", text, re.S).group(0)  # type: ignore[union-attr]


def test_the_model_connects_two_flanges_and_every_parameter() -> None:
    model = _model(_modelica("simple_pair"))
    assert "Modelica.Mechanics.Rotational.Interfaces.Flange_a flange_a" in model
    assert "Modelica.Mechanics.Rotational.Interfaces.Flange_b flange_b" in model
    # The efficiency's parameter and the radii the speed ratio needs, all parameters.
    assert re.findall(r"parameter Real (\w+);", model) == ["eta_C", "r1", "r2"]
    assert "flange_a.phi = ratio * flange_b.phi;" in model


@pytest.mark.parametrize(("torque", "speed"), [(3.0, 2.0), (-3.0, 2.0), (3.0, -2.0), (-3.0, -2.0), (5.0, 0.0)])
def test_the_torque_equation_is_the_formula_modules_in_four_quadrants(torque: float, speed: float) -> None:
    """flange_b's torque ``torque`` at its speed ``speed``: flange_a's torque by the model's
    equation equals -tau_b / (ratio eta_in) where flange_b takes power out of the train
    (the input drives), -eta_out tau_b / ratio where it puts power in."""
    model = _model(_modelica("planetary_simple"))
    values = {"eta_G": 0.97, "rA": 20.0, "rB": 40.0}
    train = load(catalog_path("planetary_simple"))
    module = compiled_module(python_module(derive_variants(train)), "p")
    ports = (train.ports.input, train.ports.output)
    eta = {k: float(module.efficiency(input=ports[k], **values)) for k in (0, 1)}
    ratio = float(module.speed_ratio(rA=values["rA"], rB=values["rB"]))
    (equation,) = re.findall(r"flange_a\.tau = (.*?);", model, re.S)
    python = re.sub(r"if (.*?) then (.*?)\s+else (.*)", r"(\2) if (\1) else (\3)", " ".join(equation.split()))
    scope = {"ratio": ratio, "eta_ab": eta[0], "eta_ba": eta[1], "power_b": torque * speed, "flange_b": None}
    tau_a = eval(python.replace("flange_b.tau", repr(torque)), {}, scope)  # the model's own equation
    expected = -eta[1] * torque / ratio if torque * speed > 0 else -torque / (ratio * eta[0])
    assert tau_a == pytest.approx(expected, rel=1e-15)
    # The power balance the model keeps: what flange_b takes out, over what flange_a puts in.
    power_a, power_b = tau_a * ratio * speed, torque * speed
    assert power_a + power_b >= -1e-12


def test_modelicalang_parses_the_file_with_its_model() -> None:
    arpeggio = pytest.importorskip("arpeggio")
    syntax = pytest.importorskip("modelicalang").latest.Syntax
    with syntax:

        def whole_file():  # a rule's name must differ from the grammar's
            return syntax.stored_definition, arpeggio.EOF

        parser = arpeggio.ParserPython(whole_file, comment_def=syntax.COMMENT)
    text = _modelica("planetary_simple")
    assert "model Gear" in text
    parser.parse(text)  # raises NoMatch on a syntax error
