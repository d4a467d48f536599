"""The command-line names of the target languages of ``derive --emit``, in the order the
help lists them.  Apart from the printers (`davies_sym.emit.languages`) so that the
parser names them without importing sympy; the registry builds its targets in this order."""

LANGUAGES: tuple[str, ...] = ("c", "julia", "octave", "rust", "modelica")

#: What ``--emit`` writes: the languages, and ``fmu``, a Functional Mock-up Unit (FMI 2.0
#: co-simulation) built from the C code (`davies_sym.emit.fmu_archive`).
EMIT_TARGETS: tuple[str, ...] = (*LANGUAGES, "fmu")
