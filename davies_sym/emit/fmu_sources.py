"""The texts of a Functional Mock-up Unit (FMI 2.0, co-simulation): ``modelDescription.xml``
and the C source of the FMI functions, around the formulas' own C file
(`davies_sym.emit.languages.c`), which the source includes so that its helpers stay
``static``.

What is shared by every unit lives here: its variables (parameters by the formulas'
names, then the inputs, the real outputs and the integer outputs ``variant`` and
``status``), the instance (parameters ``p``, inputs ``u``, outputs ``y``, the signs
``memory`` remembered for the limits at zero speed), the XML and the FMI functions.  What
each kind of train computes per step, its ``Interface`` and its ``compute`` in C, comes from
`davies_sym.emit.fmu_one_input` (driven at one port, four quadrants) and
`davies_sym.emit.fmu_several_inputs` (driven at several shafts, by power-flow region).
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

#: The SI units of the variables: name -> exponents of kg, m, s, rad.
UNITS = {"rad/s": {"s": -1, "rad": 1}, "N.m": {"kg": 1, "m": 2, "s": -2}, "W": {"kg": 1, "m": 2, "s": -3}}


@dataclass(frozen=True)
class Interface:
    """A kind of unit: its real inputs and outputs (name, unit, description), the
    descriptions of its integer outputs ``variant`` and ``status``, the reasons its
    status numbers, and how many signs it remembers."""

    inputs: tuple[tuple[str, str, str], ...]
    outputs: tuple[tuple[str, str, str], ...]
    variant: str
    reasons: tuple[str, ...]
    memory: int

    @property
    def status(self) -> str:
        return "; ".join(f"{k} {text}" for k, text in enumerate(self.reasons))


@dataclass(frozen=True)
class FmuModel:
    """What the unit is made of: its C identifier, its name and description, the
    formulas' program and parameters (with their start values) in value-reference order,
    its interface and the C text of its step (``compute``, ``rest`` and their helpers)."""

    identifier: str
    name: str
    description: str
    program: Program
    parameters: tuple[Parameter, ...]
    starts: Mapping[str, float]
    interface: Interface
    step: str

    def guid(self, formulas: str) -> str:
        """The same GUID for the same formulas and variables, a new one for any change."""
        digest = hashlib.sha256((formulas + repr(sorted(self.starts.items()))).encode("utf-8")).hexdigest()
        return "{" + str(uuid.UUID(digest[:32])) + "}"


def model_description(model: FmuModel, guid: str) -> bytes:
    """``modelDescription.xml`` (FMI 2.0): the parameters by their names with start values
    and ranges, the inputs, the real outputs and the integer outputs."""
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
    interface = model.interface
    first = len(model.parameters)
    for k, (name, unit, what) in enumerate(interface.inputs):
        ET.SubElement(_variable(variables, name, first + k, "input", what), "Real", {"unit": unit, "start": "0.0"})
    outputs = []
    for k, (name, unit, what) in enumerate(interface.outputs):
        element = _variable(variables, name, first + len(interface.inputs) + k, "output", what)
        ET.SubElement(element, "Real", {"unit": unit} if unit != "1" else {})
        outputs.append(len(variables))
    for k, (name, what) in enumerate((("variant", interface.variant), ("status", interface.status))):
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


def c_call(routine: Routine, arguments: Mapping[str, str]) -> str:
    """The C call of ``routine``, each argument the C text ``arguments`` gives for it."""
    return f"{routine.name}({', '.join(arguments[a] for a in routine.argument_names)})"


def parameter_texts(parameters: Sequence[str]) -> dict[str, str]:
    """The C text of each of the instance's parameters."""
    return {name: f"c->p[{k}]" for k, name in enumerate(parameters)}


def wrapper_source(model: FmuModel, formulas_file: str, guid: str) -> str:
    """The C source of the FMI 2.0 co-simulation functions of ``model``."""
    names = [p.name for p in model.parameters]
    interface = model.interface
    starts = "\n".join(f"    c->p[{k}] = {float(model.starts[n])!r};" for k, n in enumerate(names))
    reasons = "\n".join(f"    {_c_string(text)}," for text in interface.reasons)
    fields = {
        "FORMULAS": formulas_file,
        "PARAMETERS": str(max(1, len(names))),
        "COUNT": str(len(names)),
        "INPUTS": str(len(interface.inputs)),
        "OUTPUTS": str(len(interface.outputs)),
        "MEMORY": str(max(1, interface.memory)),
        "STATUSES": str(len(interface.reasons)),
        "REASONS": reasons,
        "IDENTIFIER": model.identifier,
        "GUID": guid,
        "STARTS": starts,
        "RESET": starts.replace("c->p", "i->p"),
    }
    return filled(_TEMPLATE.replace("@STEP@", model.step).replace("@FUNCTIONS@", FMI_FUNCTIONS), fields)


def filled(template: str, fields: Mapping[str, str]) -> str:
    """``template`` with each ``@KEY@`` replaced by ``fields[KEY]``."""
    for key, value in fields.items():
        template = template.replace(f"@{key}@", value)
    return template


def _c_string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


_TEMPLATE = r"""/* FMI 2.0 co-simulation functions of @IDENTIFIER@, around its formulas (@FORMULAS@).
 * Generated by davies_sym; do not edit.
 * Build: cc -std=c99 -O2 -fvisibility=hidden -shared -fPIC -o @IDENTIFIER@.so this.c -lm */
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
#define FIRST_INPUT (PARAMETERS)
#define FIRST_OUTPUT (PARAMETERS + @INPUTS@)
#define REALS (FIRST_OUTPUT + @OUTPUTS@)
#define STATUSES @STATUSES@

typedef struct {
    double p[@PARAMETERS@];
    double u[@INPUTS@];
    double y[@OUTPUTS@];
    int variant, status;
    double memory[@MEMORY@]; /* the signs last seen: the limits taken where a speed is zero */
    double time;
    char *name;
    fmi2CallbackFunctions callbacks;
    int logging;
} Instance;

static const char *const REASONS[] = {
@REASONS@
};

@STEP@
@FUNCTIONS@
"""
