"""The command line, the last stage: it parses what the user typed (``parser``, which
loads nothing heavy, so ``--help`` is immediate) and reads it (``arguments``), asks
the stages before it for the derivation, and writes what was asked for, one train at a
time (``one_input``, ``several_inputs``) or a catalog into a directory (``command``);
``derive calibrate`` is the calibration stage's own command."""

from davies_sym.cli.command import main
from davies_sym.cli.parser import parser

__all__ = ["main", "parser"]
