"""The command line, the last stage: it reads what the user typed (``arguments``), asks
the stages before it for the derivation, and writes what was asked for, one train at a
time (``one_input``, ``several_inputs``) or a catalog into a directory (``command``);
``derive calibrate`` is the calibration stage's own command."""

from davies_sym.cli.arguments import parser
from davies_sym.cli.command import main

__all__ = ["main", "parser"]
