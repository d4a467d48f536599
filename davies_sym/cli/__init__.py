"""The command line, the last stage: it parses what the user typed (``parser`` for
``derive``, ``subcommand_parsers`` for ``derive atlas``, ``calibrate`` and ``search``
and the table that routes the first word to them; neither loads anything heavy, so
``--help`` is immediate) and reads it (``arguments``), asks the stages before it for
the derivation, and writes what was asked for: one train at a time (``one_input_outputs``,
``several_input_outputs``), many files into a directory (``many_files``), and each other
command in its module (``atlas_command``, ``atlas_search_command``,
``calibrate_command``, ``search_command``)."""

from davies_sym.cli.command import main
from davies_sym.cli.parser import parser

__all__ = ["main", "parser"]
