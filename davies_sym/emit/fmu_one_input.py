"""The unit of a train driven at one port (`davies_sym.emit.fmu_sources`): driven by the
speed of the declared input port, ``omega_in`` (rad/s), and loaded by the torque the load
applies at the output port, ``tau_out`` (N m; power into the train at a port is its
torque times its speed).  Each step it chooses the variant from the direction of power
flow (four quadrants):

- the load takes power (``tau_out omega_out < 0``): the input drives, and the input's
  variants hold (``efficiency(..., 0)``): ``P_in = -P_out / eta``;
- the load gives power (``tau_out omega_out > 0``): the output drives the input
  (``efficiency(..., 1)``): ``P_in = -eta P_out``; where the train self-locks this way
  (``eta <= 0``) the input must still drive, the formula's value gives the torque the
  locking asks of it, and ``status`` says 3;
- at zero input speed the power is zero and the torque is the limit of the side the
  speed last came from (the positive side before any motion), never a division by zero.

Outputs: ``tau_in`` (the torque the driving shaft applies at the input port), ``omega_out``,
``P_loss = P_in + P_out >= 0``, ``efficiency`` (of the variant that holds, the
transmitted power over the driving power), ``variant`` (its number, as the text report
numbers it; 0: none) and ``status`` (0: covered; else the formulas' reason: 1 outside the
admissible parameters, 2 no variant's power flow agrees with its forces, 3 self-locking,
4 a port does not turn), where a status other than 0 and 3 leaves the torque, loss and
efficiency NaN and the step is reported to the logger.
"""

from __future__ import annotations

from collections.abc import Mapping

import sympy

from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.operating_point import OPERATING_SYMBOLS
from davies_sym.efficiency.parameter_ranges import OPERATING_PARAMETERS, parameters_of_train
from davies_sym.emit.derived_result import OneInputResult
from davies_sym.emit.fmu_sources import FmuModel, Interface, c_call, filled, parameter_texts
from davies_sym.emit.languages import emit_code, program_of
from davies_sym.emit.languages.one_input_program import RATIO
from davies_sym.emit.languages.program import Kind, Program, Routine
from davies_sym.errors import InputError, Problem

INTERFACE = Interface(
    inputs=(
        ("omega_in", "rad/s", "speed of the input port"),
        ("tau_out", "N.m", "torque the load applies at the output port (power into the train: tau_out omega_out)"),
    ),
    outputs=(
        ("tau_in", "N.m", "torque applied at the input port (power into the train: tau_in omega_in)"),
        ("omega_out", "rad/s", "speed of the output port"),
        ("P_loss", "W", "power lost in the train, P_in + P_out >= 0"),
        ("efficiency", "1", "efficiency of the variant that holds (transmitted over driving power)"),
    ),
    variant="number of the variant that holds, as the text report numbers it (0: none)",
    reasons=(
        "covered",
        "outside the admissible parameters",
        "no variant's power flow agrees with its forces (the losses reverse forces as no variant covers)",
        "the train self-locks this way: the input must drive (the torque the locking asks of it)",
        "a port does not turn (speed ratio 0 or infinite, or the train locks: a denominator of the motions vanishes)",
    ),
    memory=1,
)


def _port(routine: Routine, number: int) -> dict[str, str]:
    """The port argument of ``routine`` (named clear of the parameters) as ``number``."""
    return {a.name: str(number) for a in routine.arguments if a.kind is Kind.PORT}


def _step(program: Program, parameters: tuple[str, ...], variants: tuple[tuple[int, str], ...]) -> str:
    """The C text of ``rest`` and ``compute``: the variant of the direction of power flow."""
    by_name = {r.name: r for r in program.routines}
    given = parameter_texts(parameters)
    fields = {
        "RATIO": c_call(by_name[RATIO], given),
        **{
            f"{what.upper()}_{k}": c_call(by_name[what], {**given, **_port(by_name[what], k)})
            for what in ("efficiency", "variant", "reason")
            for k in (0, 1)
        },
        "CASES": "\n".join(
            f"    case {number}:\n        return {c_call(by_name[name], given)};" for number, name in variants
        ),
    }
    return filled(_STEP, fields)


def one_input_fmu_model(result: OneInputResult, starts: Mapping[str, float]) -> tuple[FmuModel, str]:
    """The unit's model and the formulas' C source (with the speed ratio in every symbol
    it takes, which the unit needs for the output speed); a train whose formulas take
    the load (drag, Coulomb friction: `tau_in`, `omega_in`) is refused (exit status 2)."""
    variants = result.chosen
    train = result.train
    program = program_of(result, "c")
    table = {p.name: p for p in variants.parameter_table}
    if any(n not in table for n in program.parameters) or any(str(s) in program.parameters for s in OPERATING_SYMBOLS):
        why = "the formulas depend on the load (the input torque or speed): an FMU takes formulas of the geometry "
        raise InputError([Problem("--emit", why + "and the efficiencies alone")], train.path)
    ratio = next(r for r in program.routines if r.name == RATIO)
    extra = sorted_symbols(sympy.Symbol(n) for n in ratio.argument_names if n not in program.parameters)
    names = (*program.parameters, *(str(s) for s in extra))
    laws = variants.analysis.network.laws
    by_name = {str(s): s for s in variants.train.symbols.values()}
    parameters = (
        *(table[n] for n in program.parameters),
        *parameters_of_train(train, laws, [by_name.get(str(s), s) for s in extra], OPERATING_PARAMETERS),
    )
    needed = [n for n in names if n not in starts]
    if needed:
        why = f"give the start value of {', '.join(needed)} (NAME=VALUE): the FMU's parameters start there"
        raise InputError([Problem("--at", why)], train.path)
    model = FmuModel(
        program.module,
        train.name or program.module,
        f"{train.name}: efficiency by Davies' method, four quadrants"
        + (f" (state {result.state})" if result.state else ""),
        program,
        tuple(parameters),
        dict(starts),
        INTERFACE,
        _step(program, names, tuple((v.number, v.name) for v in variants.variants)),
    )
    return model, emit_code(result, "c", program)


_STEP = r"""/* The raw efficiency of variant `number` (self-locking or not). */
static double raw_efficiency(const Instance *c, int number) {
    switch (number) {
@CASES@
    default:
        return NAN;
    }
}

/* Before any motion the limit at zero speed is taken from the positive side. */
static void rest(Instance *c) { c->memory[0] = 1.0; }

/* The outputs of the present inputs and parameters (see the module's documentation). */
static void compute(Instance *c) {
    const double omega_in = c->u[0], tau_out = c->u[1];
    double ratio = @RATIO@;
    double side = omega_in > 0 ? 1.0 : (omega_in < 0 ? -1.0 : c->memory[0]);
    double per_speed, eta, tau_in, omega_out;
    int port;
    c->memory[0] = side;
    if (!(isfinite(ratio) && ratio != 0.0)) {
        ratio = NAN;
    }
    omega_out = omega_in / ratio;
    c->y[1] = omega_out;
    /* The load's power per unit of input speed magnitude: its sign says which port drives. */
    per_speed = tau_out * side / ratio;
    port = per_speed > 0 ? 1 : 0;
    c->variant = (int)(port == 0 ? @VARIANT_0@ : @VARIANT_1@);
    c->status = (int)(port == 0 ? @REASON_0@ : @REASON_1@);
    eta = port == 0 ? @EFFICIENCY_0@ : @EFFICIENCY_1@;
    if (c->status == 3 && port == 1 && c->variant > 0) {
        eta = raw_efficiency(c, c->variant); /* locked against the load: the input must drive */
    } else if (c->status != 0) {
        c->y[0] = NAN;
        c->y[2] = NAN;
        c->y[3] = NAN;
        return;
    }
    tau_in = port == 0 ? -per_speed / eta / side : -eta * per_speed / side;
    c->y[0] = tau_in;
    c->y[2] = tau_in * omega_in + tau_out * omega_out;
    c->y[3] = eta;
}
"""
