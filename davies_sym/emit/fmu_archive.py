"""``derive FILE --emit fmu -o TRAIN.fmu``: the Functional Mock-up Unit of a train (FMI 2.0
co-simulation, `davies_sym.emit.fmu_sources`), its sources included so
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

from davies_sym.emit.fmu_sources import FmuModel, model_description, wrapper_source
from davies_sym.errors import MissingDependencyError

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
        command = [
            compiler(),
            "-std=c99",
            "-O2",
            "-fvisibility=hidden",
            "-shared",
            "-fPIC",
            "-o",
            library,
            list(sources)[-1],
            "-lm",
        ]
        done = subprocess.run(command, cwd=folder, capture_output=True, text=True, check=False)
        if done.returncode != 0:
            raise RuntimeError(f"the C compiler refused the unit's source: {done.stderr.strip()[:2000]}")
        with open(library, "rb") as handle:
            return handle.read()


def fmu_archive(model: FmuModel, formulas: str) -> bytes:
    """The ``.fmu`` archive (a zip) of ``model``, around the formulas' C source ``formulas``."""
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
