"""Output stage: what the user reads and imports, written from the results of the stages before.

Text reports (`.variant_report`), JSON documents (`.json_document`), LaTeX
(`.latex`), generated formula modules for design code (`.python_module`), the same
formulas in C, Julia, Octave, Rust and Modelica (`.languages`),
figures (`.plots`, `.graph_drawing`), the ``--eval`` answer (`.evaluation`)
and atomic file writing (`.atomic`). Nothing here derives; it only formats.
"""
