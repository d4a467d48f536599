"""``derive FILE --emit fmu -o TRAIN.fmu``: the Functional Mock-up Unit of a train driven at
one port (FMI 2.0 co-simulation, `davies_sym.emit.fmu_sources`), its sources included so
that any tool can rebuild it, and its binary for this platform compiled with the C
compiler found (``$CC``, else ``cc``).  The archive has the same bytes for the same
formulas, start values and compiler."""

from __future__ import annotations

import io
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import zipfile
from collections.abc import Mapping

import sympy

from davies_sym.algebra.symbol_order import sorted_symbols
from davies_sym.efficiency.operating_point import OPERATING_SYMBOLS
from davies_sym.efficiency.parameter_ranges import OPERATING_PARAMETERS, parameters_of_train
from davies_sym.emit.derived_result import OneInputResult
from davies_sym.emit.fmu_sources import FmuModel, model_description, wrapper_source
from davies_sym.emit.languages import emit_code, program_of
from davies_sym.emit.languages.one_input_program import RATIO
from davies_sym.errors import InputError, MissingDependencyError, Problem

#: Every entry of the archive has this time stamp (the same bytes from run to run).
STAMP = (1980, 1, 1, 0, 0, 0)


def platform_folder() -> tuple[str, str]:
    """The FMI 2.0 folder of this platform's binaries and the library suffix."""
    bits = "64" if sys.maxsize > 2**32 else "32"
    system = platform.system()
    if system == "Windows":
        return f"win{bits}", ".dll"
    if system == "Darwin":
        return f"darwin{bits}", ".dylib"
    return f"linux{bits}", ".so"


def compiler() -> str:
    """The C compiler: ``$CC`` or ``cc``; a `MissingDependencyError` (exit status 2) where
    there is none."""
    chosen = os.environ.get("CC") or "cc"
    found = shutil.which(chosen)
    if found is None:
        why = f"--emit fmu compiles the unit's binary with a C compiler, and {chosen!r} is not found: install one"
        raise MissingDependencyError(why + " (cc, gcc or clang) or name it in the CC environment variable")
    return found


def _compiled(identifier: str, sources: Mapping[str, str], suffix: str) -> bytes:
    """The shared library of ``sources`` (file name -> text; the last one is compiled)."""
    with tempfile.TemporaryDirectory() as folder:
        for name, text in sources.items():
            with open(os.path.join(folder, name), "w", encoding="utf-8") as handle:
                handle.write(text)
        library = os.path.join(folder, identifier + suffix)
        command = [compiler(), "-std=c99", "-O2", "-shared", "-fPIC", "-o", library, list(sources)[-1], "-lm"]
        done = subprocess.run(command, cwd=folder, capture_output=True, text=True, check=False)
        if done.returncode != 0:
            raise RuntimeError(f"the C compiler refused the unit's source: {done.stderr.strip()[:2000]}")
        with open(library, "rb") as handle:
            return handle.read()


def fmu_model(result: OneInputResult, starts: Mapping[str, float]) -> tuple[FmuModel, str]:
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
        tuple((v.number, v.name) for v in variants.variants),
    )
    return model, emit_code(result, "c")


def fmu_archive(result: OneInputResult, starts: Mapping[str, float]) -> bytes:
    """The ``.fmu`` archive (a zip) of ``result`` with the parameters' ``starts``."""
    model, formulas = fmu_model(result, starts)
    guid = model.guid(formulas)
    formulas_file = f"{model.identifier}_formulas.c"
    sources = {formulas_file: formulas, f"{model.identifier}.c": wrapper_source(model, formulas_file, guid)}
    folder, suffix = platform_folder()
    entries = {
        "modelDescription.xml": model_description(model, guid),
        **{f"sources/{name}": text.encode("utf-8") for name, text in sources.items()},
        f"binaries/{folder}/{model.identifier}{suffix}": _compiled(model.identifier, sources, suffix),
    }
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in entries.items():
            info = zipfile.ZipInfo(name, STAMP)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            archive.writestr(info, data)
    return buffer.getvalue()
