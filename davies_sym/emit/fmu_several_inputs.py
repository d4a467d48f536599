"""The unit of a train driven at several shafts (`davies_sym.emit.fmu_sources`), such as
the SR20 differential: driven by the speed of every input port, ``omega_<port>`` (rad/s),
and loaded by the torque the load applies at the output port, ``tau_out`` (N m, signed:
power into the train at a port is its torque times its speed).

Each step it takes the power-flow region (Mantriota and Pennestri 2003) whose speed
conditions have the signs of the present speeds and whose loaded forces agree with the
load's magnitude, and gives the torque each input shaft applies in that region.  Where a
speed condition is exactly zero (both shafts at one speed: the meshes do not roll; a shaft
at rest) the sign it last had is taken (positive before any motion): the limit from the
side the speeds came from, never a division by zero; likewise the efficiency at rest is
the limit along the last direction of the input speeds, and 0 where no power flows at
all (no load and the meshes not rolling: nothing is transmitted).

Outputs: ``tau_<port>`` for each input port, ``omega_out``, ``P_loss`` (the sum of the
powers into the train, >= 0), ``efficiency`` (the region's: output power over the sum of
the input shafts' powers, eq. (6)), ``variant`` (the region's number, as the text report
numbers it) and ``status``: 0 covered; 1 outside the parameters' ranges; 2 no region's
loaded forces agree, or several give different torques; 3 the efficiency is outside
[0, 1] (the torques still given); 5 the load drives the output port (the formulas take a
load that resists the output's motion).  Where the status is 1, 2 or 5 the torques, loss
and efficiency are NaN and the step is reported to the logger.
"""

from __future__ import annotations

from collections.abc import Mapping

from davies_sym.efficiency.power_flow_regions import LOAD_TORQUE, SeveralInputs
from davies_sym.emit.derived_result import SeveralInputResult
from davies_sym.emit.fmu_sources import FmuModel, Interface, c_call, filled, parameter_texts
from davies_sym.emit.languages import emit_code, program_of
from davies_sym.emit.languages.program import Program
from davies_sym.emit.languages.several_input_program import known_symbols
from davies_sym.errors import InputError, Problem

#: What ``status`` numbers (4, a speed-condition line, is the formulas' reason, which the
#: unit replaces by the limit).
REASONS = (
    "covered",
    "outside the parameters' ranges",
    "no region's loaded forces agree with their assumed signs, or several regions give different torques",
    "the efficiency is outside [0, 1] (the torques are the region's)",
    "on a speed-condition line",
    "the load drives the output port: the formulas take a load that resists the output's motion",
)


def _interface(si: SeveralInputs, speeds: tuple[str, ...]) -> Interface:
    """The unit's variables: each input port's speed and torque, the load; it remembers
    a sign per speed condition, the output's sign and the last input speeds."""
    inputs, output = tuple(si.train.ports.inputs), si.train.ports.output
    return Interface(
        inputs=(
            *((s, "rad/s", f"speed of input port {p}") for p, s in zip(inputs, speeds, strict=True)),
            (
                "tau_out",
                "N.m",
                f"torque the load applies at output port {output} (power into the train: tau_out omega_out)",
            ),
        ),
        outputs=(
            *(
                (f"tau_{p}", "N.m", f"torque applied at input port {p} (power into the train: tau_{p} {s})")
                for p, s in zip(inputs, speeds, strict=True)
            ),
            ("omega_out", "rad/s", f"speed of output port {output}"),
            ("P_loss", "W", "power lost in the train, the sum of the powers into it, >= 0"),
            ("efficiency", "1", "efficiency of the region that holds (output power over the input shafts' powers)"),
        ),
        variant="number of the power-flow region that holds, as the text report numbers it (0: none)",
        reasons=REASONS,
        memory=len(si.conditions) + 1 + len(speeds),
    )


def several_inputs_fmu_model(result: SeveralInputResult, starts: Mapping[str, float]) -> tuple[FmuModel, str]:
    """The unit's model and the formulas' C source: the parameters are the formulas'
    less the input speeds and the load, which are the unit's inputs."""
    si = result.regions
    train = si.train
    program = program_of(result, "c")
    speeds = tuple(str(s) for s in si.speeds)
    operating = {*speeds, str(LOAD_TORQUE)}
    names = tuple(n for n in program.parameters if n not in operating)
    known = known_symbols(si)
    parameters = si.parameter_table([known[n] for n in names])
    unknown = sorted(set(starts) - set(names))
    if unknown:
        why = f"unknown symbol {unknown[0]} (the unit's parameters: {', '.join(names)})"
        raise InputError([Problem("--at", why)], train.path)
    needed = [n for n in names if n not in starts]
    if needed:
        why = f"give the start value of {', '.join(needed)} (NAME=VALUE): the FMU's parameters start there"
        raise InputError([Problem("--at", why)], train.path)
    model = FmuModel(
        program.module,
        train.name or program.module,
        f"{train.name}: driven at {', '.join(train.ports.inputs)}, torques by power-flow region (Davies' method)",
        program,
        tuple(parameters),
        dict(starts),
        _interface(si, speeds),
        _step(si, program, names, speeds),
    )
    return model, emit_code(result, "c", program)


def _step(si: SeveralInputs, program: Program, names: tuple[str, ...], speeds: tuple[str, ...]) -> str:
    """The C text of ``rest`` and ``compute``: the region of the present signs."""
    by_name = {r.name: r for r in program.routines}
    conditions = len(si.conditions)
    probe = {s: f"probe[{k}]" for k, s in enumerate(speeds)}
    given = {**parameter_texts(names), **probe, str(LOAD_TORQUE): "m"}
    ports = tuple(si.train.ports.inputs)
    output = si.train.ports.output
    signs = "\n".join(
        f"    sign[{k}] = signed_of(c, {k}, {c_call(by_name[f'condition_{c.name}'], probe)});"
        for k, c in enumerate(si.conditions)
    )
    index = {c.name: k for k, c in enumerate(si.conditions)}
    regions = []
    for r in si.regions:
        tests = [f"sign[{index[n]}] {'>' if s > 0 else '<'} 0" for n, s in r.signs.items()]
        agree = f"region_{r.number}_forces_agree"
        if agree in by_name:
            tests.append(c_call(by_name[agree], given))
        torques = ", ".join(c_call(by_name[f"region_{r.number}_torque_{p}"], given) for p in ports)
        regions.append(
            f"    if ({' && '.join(tests) or '1'}) {{\n"
            f"        const double t[INPUT_PORTS] = {{{torques}}};\n"
            f"        consider(&pick, {r.number}, t);\n    }}"
        )
    cases = "\n".join(
        f"    case {r.number}:\n        return {c_call(by_name[f'region_{r.number}'], given)};" for r in si.regions
    )
    fields = {
        "CONDITIONS": str(conditions),
        "PORTS": str(len(ports)),
        "SIGNS": signs,
        "REGIONS": "\n".join(regions),
        "CASES": cases,
        "SPEED_OUT": c_call(by_name[f"speed_{output}"], {s: f"c->u[{k}]" for k, s in enumerate(speeds)}),
        "IN_RANGES": c_call(by_name["in_ranges"], {**given, str(LOAD_TORQUE): "(m > 0 ? m : 1.0)"}),
    }
    return filled(_STEP, fields)


_STEP = r"""#define CONDITIONS @CONDITIONS@
#define INPUT_PORTS @PORTS@

/* Before any motion every sign is positive and the last input speeds are all 1. */
static void rest(Instance *c) {
    int k;
    for (k = 0; k < CONDITIONS + 1 + INPUT_PORTS; k++) {
        c->memory[k] = 1.0;
    }
}

/* The sign of `value`; where it is zero, the sign memory[k] last had (the limit). */
static double signed_of(Instance *c, int k, double value) {
    double sign = value > 0 ? 1.0 : (value < 0 ? -1.0 : c->memory[k]);
    c->memory[k] = sign;
    return sign;
}

/* The region found, the input torques it gives, and whether another gave others. */
typedef struct {
    int found, region, differ;
    double t[INPUT_PORTS];
} Pick;

static void consider(Pick *pick, int region, const double t[]) {
    int k;
    if (pick->found == 0) {
        pick->region = region;
        for (k = 0; k < INPUT_PORTS; k++) {
            pick->t[k] = t[k];
        }
    } else {
        for (k = 0; k < INPUT_PORTS; k++) {
            if (fabs(t[k] - pick->t[k]) > 1e-12 * (1.0 + fabs(pick->t[k]))) {
                pick->differ = 1;
            }
        }
    }
    pick->found += 1;
}

/* The efficiency of `region` at the speeds `probe` and the load's magnitude m. */
static double region_efficiency(const Instance *c, int region, const double probe[], double m) {
    switch (region) {
@CASES@
    default:
        return NAN;
    }
}

static void not_covered(Instance *c, int status) {
    int k;
    c->status = status;
    c->variant = 0;
    for (k = 0; k < INPUT_PORTS; k++) {
        c->y[k] = NAN;
    }
    c->y[INPUT_PORTS + 1] = NAN;
    c->y[INPUT_PORTS + 2] = NAN;
}

/* The outputs of the present inputs and parameters (see the module's documentation). */
static void compute(Instance *c) {
    const double load = c->u[INPUT_PORTS];
    const double omega_out = @SPEED_OUT@;
    double sign[CONDITIONS > 0 ? CONDITIONS : 1];
    double probe[INPUT_PORTS];
    double m, eta, power = 0.0;
    int k, moving = 0;
    Pick pick = {0, 0, 0, {0.0}};
    for (k = 0; k < INPUT_PORTS; k++) {
        moving = moving || c->u[k] != 0.0;
    }
    /* The speeds the conditions and the efficiency see: the last direction at rest. */
    for (k = 0; k < INPUT_PORTS; k++) {
        if (moving) {
            c->memory[CONDITIONS + 1 + k] = c->u[k];
        }
        probe[k] = moving ? c->u[k] : c->memory[CONDITIONS + 1 + k];
    }
@SIGNS@
    (void)sign;
    c->y[INPUT_PORTS] = omega_out;
    /* The formulas take the load's magnitude, resisting the output's motion. */
    m = -load * signed_of(c, CONDITIONS, omega_out);
    if (m < 0) {
        not_covered(c, 5);
        return;
    }
    if (!@IN_RANGES@) {
        not_covered(c, 1);
        return;
    }
@REGIONS@
    if (pick.found == 0 || pick.differ) {
        not_covered(c, 2);
        return;
    }
    c->variant = pick.region;
    for (k = 0; k < INPUT_PORTS; k++) {
        c->y[k] = pick.t[k];
        power += pick.t[k] * c->u[k];
    }
    c->y[INPUT_PORTS + 1] = power + load * omega_out;
    eta = region_efficiency(c, pick.region, probe, m);
    if (isnan(eta) && m * omega_out == 0.0) {
        eta = 0.0; /* no power reaches the output, and none enters (0/0): nothing transmitted */
    }
    c->y[INPUT_PORTS + 2] = eta;
    c->status = (eta >= 0.0 && eta <= 1.0 + 1e-12) ? 0 : 3;
}
"""
