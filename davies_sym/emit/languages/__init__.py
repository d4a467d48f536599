"""Formula code in other languages than Python (``derive FILE --emit c|julia|octave|rust|modelica``).

A train's variants (Laus 2011, Tables 5 and 6: the input port and the signs of the
turning conditions say which gear drives in each mesh) or power-flow regions are first
described once, language-neutral (`.program`: routines of named arguments, local
steps and a result, all sympy expressions), by `.one_input` and
`.several_inputs`; then each language module (`.c`, `.julia`,
`.octave`, `.rust`, `.modelica`) prints the expressions with sympy's code
printer for it (`.printers`; Modelica's own in `.modelica_printer`) and writes
the frame: the opening comment, function heads, declarations.  The choice function picks
the variant exactly as the generated Python module does.
"""

from davies_sym.emit.language_names import LANGUAGES
from davies_sym.emit.languages.registry import TARGETS, emit_code, program_of

__all__ = ["LANGUAGES", "TARGETS", "emit_code", "program_of"]
