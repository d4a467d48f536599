"""The texts of a Functional Mock-up Unit (FMI 2.0, co-simulation) of a train driven at one
port: ``modelDescription.xml`` and the C source of the FMI functions, around the formulas'
own C file (`davies_sym.emit.languages.c`), which the source includes so that its
helpers stay ``static``.

The unit is driven by the speed of the declared input port, ``omega_in`` (rad/s), and
loaded by the torque the load applies at the output port, ``tau_out`` (N m; power into
the train at a port is its torque times its speed).  Each step it chooses the variant
from the direction of power flow (four quadrants):

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

import hashlib
import math
import uuid
import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

from davies_sym.efficiency.parameter_ranges import Parameter
from davies_sym.emit.fmi2_functions import FMI_FUNCTIONS
from davies_sym.emit.languages.program import Program, Routine

#: The inputs, the real outputs and the integer outputs, with units and descriptions.
INPUTS = (
    ("omega_in", "rad/s", "speed of the input port"),
    ("tau_out", "N.m", "torque the load applies at the output port (power into the train: tau_out omega_out)"),
)
OUTPUTS = (
    ("tau_in", "N.m", "torque applied at the input port (power into the train: tau_in omega_in)"),
    ("omega_out", "rad/s", "speed of the output port"),
    ("P_loss", "W", "power lost in the train, P_in + P_out >= 0"),
    ("efficiency", "1", "efficiency of the variant that holds (transmitted over driving power)"),
)
COUNTS = (
    ("variant", "number of the variant that holds, as the text report numbers it (0: none)"),
    (
        "status",
        "0 covered; 1 outside the admissible parameters; 2 no variant's power flow agrees with its "
        "forces; 3 self-locking (the input must drive); 4 a port does not turn",
    ),
)
#: The SI units of the variables: name -> exponents of kg, m, s, rad.
UNITS = {"rad/s": {"s": -1, "rad": 1}, "N.m": {"kg": 1, "m": 2, "s": -2}, "W": {"kg": 1, "m": 2, "s": -3}}


@dataclass(frozen=True)
class FmuModel:
    """What the unit is made of: its C identifier, its name and description, the
    formulas' program and parameters (with their start values) in value-reference order,
    and the variants' routines."""

    identifier: str
    name: str
    description: str
    program: Program
    parameters: tuple[Parameter, ...]
    starts: Mapping[str, float]
    #: Each variant's number and the name of its routine.
    variants: tuple[tuple[int, str], ...]

    def guid(self, formulas: str) -> str:
        """The same GUID for the same formulas and variables, a new one for any change."""
        digest = hashlib.sha256((formulas + repr(sorted(self.starts.items()))).encode("utf-8")).hexdigest()
        return "{" + str(uuid.UUID(digest[:32])) + "}"


def model_description(model: FmuModel, guid: str) -> bytes:
    """``modelDescription.xml`` (FMI 2.0): the parameters by their names with start values
    and ranges, the two inputs, the four real and two integer outputs."""
    root = ET.Element(
        "fmiModelDescription",
        {
            "fmiVersion": "2.0",
            "modelName": model.name,
            "guid": guid,
            "description": model.description,
            "generationTool": "davies_sym",
            "variableNamingConvention": "flat",
            "numberOfEventIndicators": "0",
        },
    )
    attributes = {"modelIdentifier": model.identifier, "canHandleVariableCommunicationStepSize": "true"}
    ET.SubElement(root, "CoSimulation", {**attributes, "canNotUseMemoryManagementFunctions": "true"})
    units = ET.SubElement(root, "UnitDefinitions")
    for name, exponents in UNITS.items():
        ET.SubElement(
            ET.SubElement(units, "Unit", {"name": name}), "BaseUnit", {k: str(v) for k, v in exponents.items()}
        )
    variables = ET.SubElement(root, "ModelVariables")
    for k, p in enumerate(model.parameters):
        element = _variable(variables, p.name, k, "parameter", f"{p.meaning} [{p.unit}]", "tunable")
        bounds = {"start": repr(float(model.starts[p.name]))}
        if math.isfinite(p.low):
            bounds["min"] = repr(float(p.low))
        if math.isfinite(p.high):
            bounds["max"] = repr(float(p.high))
        ET.SubElement(element, "Real", bounds)
    first = len(model.parameters)
    for k, (name, unit, what) in enumerate(INPUTS):
        ET.SubElement(_variable(variables, name, first + k, "input", what), "Real", {"unit": unit, "start": "0.0"})
    outputs = []
    for k, (name, unit, what) in enumerate(OUTPUTS):
        element = _variable(variables, name, first + len(INPUTS) + k, "output", what)
        ET.SubElement(element, "Real", {"unit": unit} if unit != "1" else {})
        outputs.append(len(variables))
    for k, (name, what) in enumerate(COUNTS):
        ET.SubElement(_variable(variables, name, k, "output", what, "discrete"), "Integer")
        outputs.append(len(variables))
    structure = ET.SubElement(root, "ModelStructure")
    listed = ET.SubElement(structure, "Outputs")
    initial = ET.SubElement(structure, "InitialUnknowns")
    for index in outputs:
        ET.SubElement(listed, "Unknown", {"index": str(index)})
        ET.SubElement(initial, "Unknown", {"index": str(index)})
    ET.indent(root)
    text: bytes = ET.tostring(root, encoding="utf-8")
    return b'<?xml version="1.0" encoding="UTF-8"?>\n' + text + b"\n"


def _variable(
    parent: ET.Element, name: str, reference: int, causality: str, what: str, variability: str = "continuous"
) -> ET.Element:
    return ET.SubElement(
        parent,
        "ScalarVariable",
        {
            "name": name,
            "valueReference": str(reference),
            "causality": causality,
            "variability": variability,
            "description": what,
        },
    )


def _call(routine: Routine, parameters: Sequence[str], port: str | None = None) -> str:
    """The C call of ``routine`` on the instance's parameters (and the port number)."""
    index = {name: k for k, name in enumerate(parameters)}
    arguments = [f"c->p[{index[a]}]" if a in index else str(port) for a in routine.argument_names]
    return f"{routine.name}({', '.join(arguments)})"


def wrapper_source(model: FmuModel, formulas_file: str, guid: str) -> str:
    """The C source of the FMI 2.0 co-simulation functions of ``model``."""
    by_name = {r.name: r for r in model.program.routines}
    names = [p.name for p in model.parameters]
    calls = {
        "RATIO": _call(by_name["speed_ratio"], names),
        **{
            f"{what.upper()}_{k}": _call(by_name[what], names, str(k))
            for what in ("efficiency", "variant", "reason")
            for k in (0, 1)
        },
    }
    cases = "\n".join(
        f"    case {number}:\n        return {_call(by_name[routine], names)};" for number, routine in model.variants
    )
    starts = "\n".join(f"    c->p[{k}] = {float(model.starts[n])!r};" for k, n in enumerate(names))
    fields = {
        "FORMULAS": formulas_file,
        "PARAMETERS": str(max(1, len(names))),
        "COUNT": str(len(names)),
        "IDENTIFIER": model.identifier,
        "GUID": guid,
        "CASES": cases,
        "STARTS": starts,
        "RESET": starts.replace("c->p", "i->p"),
        **calls,
    }
    text = _TEMPLATE.replace("@FUNCTIONS@", FMI_FUNCTIONS)
    for key, value in fields.items():
        text = text.replace(f"@{key}@", value)
    return text


_TEMPLATE = r"""/* FMI 2.0 co-simulation functions of @IDENTIFIER@, around its formulas (@FORMULAS@).
 * Generated by davies_sym; do not edit.  Build: cc -std=c99 -O2 -shared -fPIC -o @IDENTIFIER@.so this.c -lm */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include "@FORMULAS@"

#if defined(_WIN32)
#define FMI_EXPORT __declspec(dllexport)
#else
#define FMI_EXPORT __attribute__((visibility("default")))
#endif

typedef void *fmi2Component;
typedef void *fmi2ComponentEnvironment;
typedef void *fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef char fmi2Char;
typedef const fmi2Char *fmi2String;
typedef char fmi2Byte;
typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;
typedef enum { fmi2DoStepStatus, fmi2PendingStatus, fmi2LastSuccessfulTime, fmi2Terminated } fmi2StatusKind;
typedef void (*fmi2CallbackLogger)(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
typedef void *(*fmi2CallbackAllocateMemory)(size_t, size_t);
typedef void (*fmi2CallbackFreeMemory)(void *);
typedef void (*fmi2StepFinished)(fmi2ComponentEnvironment, fmi2Status);
typedef struct {
    fmi2CallbackLogger logger;
    fmi2CallbackAllocateMemory allocateMemory;
    fmi2CallbackFreeMemory freeMemory;
    fmi2StepFinished stepFinished;
    fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

#define PARAMETERS @COUNT@
#define OMEGA_IN (PARAMETERS)
#define TAU_OUT (PARAMETERS + 1)
#define TAU_IN (PARAMETERS + 2)
#define OMEGA_OUT (PARAMETERS + 3)
#define P_LOSS (PARAMETERS + 4)
#define EFFICIENCY (PARAMETERS + 5)
#define REALS (PARAMETERS + 6)

typedef struct {
    double p[@PARAMETERS@];
    double omega_in, tau_out, tau_in, omega_out, p_loss, eta;
    int variant, status;
    double side; /* the sign of the last non-zero input speed: the limit taken at zero speed */
    double time;
    char *name;
    fmi2CallbackFunctions callbacks;
    int logging;
} Instance;

static const char *const REASONS[] = {
    "covered",
    "outside the admissible parameters",
    "no variant's power flow agrees with its forces (the losses reverse forces as no variant covers)",
    "the train self-locks this way: the input must drive (the torque the locking asks of it)",
    "a port does not turn (speed ratio 0 or infinite)",
};

/* The raw efficiency of variant `number` (self-locking or not). */
static double raw_efficiency(const Instance *c, int number) {
    switch (number) {
@CASES@
    default:
        return NAN;
    }
}

/* The outputs of the present inputs and parameters (see the module's documentation). */
static void compute(Instance *c) {
    double ratio = @RATIO@;
    double side = c->omega_in > 0 ? 1.0 : (c->omega_in < 0 ? -1.0 : c->side);
    double per_speed, eta;
    int port;
    c->side = side;
    if (!(isfinite(ratio) && ratio != 0.0)) {
        ratio = NAN;
    }
    c->omega_out = c->omega_in / ratio;
    /* The load's power per unit of input speed magnitude: its sign says which port drives. */
    per_speed = c->tau_out * side / ratio;
    port = per_speed > 0 ? 1 : 0;
    c->variant = (int)(port == 0 ? @VARIANT_0@ : @VARIANT_1@);
    c->status = (int)(port == 0 ? @REASON_0@ : @REASON_1@);
    eta = port == 0 ? @EFFICIENCY_0@ : @EFFICIENCY_1@;
    if (c->status == 3 && port == 1 && c->variant > 0) {
        eta = raw_efficiency(c, c->variant); /* locked against the load: the input must drive */
    } else if (c->status != 0) {
        c->tau_in = NAN;
        c->p_loss = NAN;
        c->eta = NAN;
        return;
    }
    c->tau_in = port == 0 ? -per_speed / eta / side : -eta * per_speed / side;
    c->p_loss = c->tau_in * c->omega_in + c->tau_out * c->omega_out;
    c->eta = eta;
}

@FUNCTIONS@
"""
