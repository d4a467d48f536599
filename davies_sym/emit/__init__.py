"""Output stage: what the user reads and imports, written from the results of the stages before.

Text reports (:mod:`.report`, :mod:`.variant_report`), JSON documents, LaTeX
(:mod:`.latex`), generated formula modules for design code (:mod:`.python_module`),
figures (:mod:`.plots`, :mod:`.graph_drawing`), the ``--eval`` answer (:mod:`.evaluation`)
and atomic file writing (:mod:`.atomic`). Nothing here derives; it only formats.
"""
