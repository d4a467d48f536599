"""The topology language, version 1, as data.

One table describes every entry a train file may hold: the loader checks files against
it and ``docs/topology.md`` is generated from it (``python3 tools/topology_doc.py``).
Coupling kinds add their own entries (see `davies_sym.topology.couplings`).
"""

from __future__ import annotations

from dataclasses import dataclass

FORMAT_VERSION = 1


@dataclass(frozen=True)
class Field:
    """One key of a mapping in a train file."""

    key: str
    kind: str
    required: bool
    doc: str


TOP_LEVEL = (
    Field("format", "integer", False, f"Topology language version; {FORMAT_VERSION} if omitted."),
    Field("name", "string", True, "Name of the train, used in reports."),
    Field("source", "string", False, "Where the train comes from (document, figure, equation or table)."),
    Field(
        "links", "list or mapping", True, "The members (links). A list of names, or a mapping name -> {description}."
    ),
    Field(
        "reference",
        "link",
        False,
        "The link common to input and output (usually the housing); motions are "
        "measured against it. Default: the link that both port couplings touch.",
    ),
    Field("gears", "mapping", False, "Gears: name -> gear entry (see below)."),
    Field(
        "couplings",
        "mapping",
        True,
        "Couplings (edges of the coupling graph): name -> coupling entry. The "
        "direction of an edge is from the first to the second link (or gear).",
    ),
    Field("ports", "mapping", True, "Ports: `input` and `output`, each a coupling name."),
    Field("degrees_of_freedom", "integer", False, "Expected mobility; a mismatch with the derived one is an error."),
    Field("states", "mapping", False, "Operating states of a multi-speed set: name -> state entry (see *States*)."),
    Field(
        "placement",
        "[x, y] or an angle in degrees",
        False,
        "Draw a planar train in 2-D (planet-planet meshes off the centre line): the direction "
        "from the main axis along which the first planet is placed. Planets meshing two placed "
        "gears close their triangle. Omit to draw the train on one line.",
    ),
    Field(
        "independent",
        "list of symbols",
        False,
        "Which parameters stay free where the loops of meshes over-determine the radii "
        "(r1 - r3 = r2 - r4): each geometric constraint is solved for one of the others. "
        "Default: the annulus radius when it is a sum of the others (r_R = r_S + 2 r_P), "
        "else a radius of the mesh that closes the loop, its planet's gear first.",
    ),
    Field("expected", "list", False, "Published numbers to check (used by the catalog tests)."),
    Field(
        "calibrate",
        "mapping",
        False,
        "Loss parameters `derive calibrate` fits when the command line names none (see *Calibration*).",
    ),
    Field("notes", "string", False, "Free text."),
)

LINK = (Field("description", "string", False, "What the member is."),)

GEAR = (
    Field("link", "link", True, "The link the gear is fixed to."),
    Field("radius", "number or expression", False, "Pitch radius (a number, a symbol such as `r1`, or an expression)."),
    Field(
        "teeth",
        "integer or symbol",
        False,
        "Tooth count (a whole number or a symbol such as `z1`); with `module` gives radius = module*teeth/2.",
    ),
    Field("module", "number or expression", False, "Module (used with `teeth`)."),
    Field("internal", "boolean", False, "True for an annulus (internal teeth). Default false."),
    Field(
        "about",
        "link",
        False,
        "The link whose axis the gear is centred on, when it is not its own link's: a gear fixed to a "
        "carrier about one of the pins it holds (the link turning on that pin). Parallel-axis trains only.",
    ),
    Field(
        "axis",
        "`x`, `y`, `z`, `-z`, ... or [x, y, z], or `tilted`",
        False,
        "Direction of the gear axis through the common apex, for bevel and face-gear trains "
        "(all axes meet at the origin; entries may use `sqrt`). The pitch point of a mesh lies "
        "on the side the two axis directions point to. `tilted`: a bevel planet meshing two "
        "coaxial gears that face each other; its axis follows from the cone geometry, in the "
        "plane of the main axis and +y (Laus eq. (80)). Another gear on the same link may omit "
        "the axis. Omit for parallel-axis trains.",
    ),
)

PORTS = (
    Field(
        "input",
        "coupling or list of couplings",
        True,
        "Coupling that carries the input torque (or force); a train with several degrees of freedom "
        "lists one input per degree of freedom (a differential driven on two shafts).",
    ),
    Field("output", "coupling", True, "Coupling that carries the output torque (or force)."),
)

#: The keys of the ports, of the file and of each operating state.
PORT_KEYS = tuple(f.key for f in PORTS)

STATE = (
    Field("input", "coupling", True, "Input port in this state."),
    Field("output", "coupling", True, "Output port in this state."),
    Field(
        "brake",
        "list of links",
        False,
        "Members braked to the housing (the reference link): each is joined rigidly to it.",
    ),
    Field("clutch", "list of [link, link]", False, "Pairs of members clutched together (joined rigidly)."),
    Field(
        "free",
        "list of links",
        False,
        "Members running free (unloaded): removed with their couplings, they carry no power and no loss.",
    ),
    Field("description", "string", False, "What the state is (e.g. first gear)."),
)

EXPECTED = (
    Field("quantity", "`efficiency`", False, "What the check compares; `efficiency` (the default) is the only one."),
    Field(
        "values",
        "mapping",
        True,
        "The design: symbol -> number (exact as written, `0.98` is 49/50), for every symbol of the formula.",
    ),
    Field("value", "number", True, "The published number."),
    Field("tolerance", "number", False, "Largest accepted difference from `value` (positive); default 5e-5."),
    Field("source", "string", False, "Where the number is published (document, equation, table)."),
    Field("input", "coupling", False, "The input port of the check; default the train's input."),
    Field("state", "state", False, "The operating state of the check (trains with `states`)."),
    Field(
        "published",
        "boolean",
        False,
        "`false` for a regression value of this file's own geometry, not a number from the literature; default `true`.",
    ),
    Field(
        "differs",
        "string",
        False,
        "A published number this file does not reproduce, and why (the check then asserts that the derived "
        "value differs from it by more than the tolerance).",
    ),
)

COUPLING_COMMON = (
    Field("type", "string", True, "Coupling kind: the `type:` of one of the kinds below."),
    Field("friction", "mapping or `none`", False, "Friction laws and coefficients; see *Friction*."),
)

FRICTION = (
    Field(
        "coulomb",
        "symbol or number",
        False,
        "Coulomb law, Laus Table 2 eq. (10): T = -zeta |U| sign(t). The coefficient has "
        "the unit of length and is positive. Default for gear meshes: `zeta_<coupling>`.",
    ),
    Field(
        "linear",
        "symbol or number",
        False,
        "Signed linear law of Laus eqs. (63)-(64): T = zeta U with a real coefficient "
        "whose sign the user controls (no sign functions).",
    ),
    Field(
        "viscous",
        "symbol or number",
        False,
        "Linear viscous law, Laus Table 2 eq. (11): T = -b t, a dependent source "
        "(eqs. (50)-(53)); makes the efficiency depend on the input torque and speed.",
    ),
    Field(
        "drag",
        "symbol or number",
        False,
        "Load-independent drag: a constant torque against the coupling's relative motion "
        "(churning, seals), a dependent source like the viscous law; makes the efficiency "
        "depend on the input torque.",
    ),
    Field(
        "bearing",
        "mapping",
        False,
        "Journal bearing (Laus App. D): `mu` (friction coefficient), `radius` (journal radius) "
        "and optionally `contact` (`catalogue`: mu is the bearing's own coefficient, the default; "
        "`new`: uniform pressure, mu times pi/2; `worn`: cosine pressure, mu times 4/pi). Gives the "
        "Coulomb law with the friction-circle radius zeta_<coupling> = k mu radius, loaded by the "
        "bearing's radial reaction force.",
    ),
    Field(
        "thrust",
        "mapping",
        False,
        "Thrust face of a bearing (a collar, a thrust washer, the axial side of a rolling bearing): "
        "`mu` (friction coefficient) and `radius` (the friction radius of the face, e.g. the mean "
        "radius of a worn-in collar). Gives the Coulomb law zeta_<coupling> = mu radius loaded by the "
        "bearing's axial reaction, the thrust of helical gears. One load-dependent law per bearing: "
        "not with `bearing`.",
    ),
    Field(
        "pressed_by",
        "mesh",
        False,
        "On a prismatic guide: the mesh whose tooth force presses the guide (a rack's mesh with a "
        "`pressure_angle`). Its separating component, tan(pressure angle) times the tangential tooth "
        "force U, loads the guide's `coulomb` law: F = -mu tan(alpha) |U| sign(v), mu the guide's "
        "friction coefficient.",
    ),
)

THRUST = (
    Field("mu", "symbol or number", True, "Friction coefficient of the thrust face."),
    Field("radius", "symbol or number", True, "Friction radius of the thrust face (the unit of the pitch radii)."),
)

BEARING = (
    Field("mu", "symbol or number", True, "Friction coefficient of the journal."),
    Field("radius", "symbol or number", True, "Journal radius (the unit of the pitch radii)."),
    Field(
        "contact",
        "`catalogue`, `new` or `worn`",
        False,
        "How the pressure spreads over the journal (Laus Table 16); default `catalogue`.",
    ),
)

TOOTH_CONTACT = (
    Field("mu", "symbol or number", True, "Sliding friction coefficient of the tooth flanks."),
    Field("pressure_angle", "number (degrees)", True, "Pressure angle of the involute teeth."),
    Field(
        "addendum",
        "symbol or number",
        False,
        "Addendum of both gears; default: the gears' module (both gears need the same one).",
    ),
    Field(
        "approach",
        "symbol or number",
        False,
        "Approach length DP along the path of contact (Laus eq. (135)); default: from the addenda.",
    ),
    Field(
        "recess",
        "symbol or number",
        False,
        "Recess length EP (Laus eq. (134)); default: from the addenda. Give both or neither.",
    ),
)


def fields_table(fields: tuple[Field, ...]) -> str:
    """A Markdown table of ``fields``."""
    rows = ["| key | kind | required | meaning |", "| --- | --- | --- | --- |"]
    for f in fields:
        rows.append(f"| `{f.key}` | {f.kind} | {'yes' if f.required else 'no'} | {f.doc} |")
    return "\n".join(rows)


CALIBRATE = (
    Field("fit", "list of symbols", True, "The loss parameters fitted to measured data."),
    Field(
        "start",
        "mapping",
        False,
        "Start values of the fit (symbol -> positive number); default: 0.95 for "
        "an efficiency, 0.1 for other coefficients.",
    ),
    Field(
        "data",
        "file",
        False,
        "The measurements (CSV) the parameters are fitted to, relative to this file: `derive calibrate "
        "TRAIN.yaml` (or `--catalog NAME`) then needs no DATA.csv.",
    ),
    Field(
        "predict",
        "list of files",
        False,
        "Other measurements (CSV, relative to this file) the fitted model predicts when the command line "
        "gives neither DATA.csv nor --predict.",
    ),
)
