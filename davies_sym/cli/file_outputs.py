"""The outputs ``derive FILE`` computes for one parsed file, whichever kind it is: a
machine, a train driven at several ports, or one driven at one port.  The single-file
command and ``derive FILES --out DIR --json`` (or ``--latex``) both read them here, so
that the two ways give the same bytes."""

from __future__ import annotations

import argparse

from davies_sym.cli.machine_input import machine_outputs
from davies_sym.cli.one_input_outputs import one_input_outputs
from davies_sym.cli.several_input_outputs import several_degrees_of_freedom, several_outputs
from davies_sym.cli.state_failures import StateFailures
from davies_sym.errors import InputError, Problem
from davies_sym.machines.machine_loader import build_machine, is_machine
from davies_sym.progress import Progress
from davies_sym.topology.loader import build_train
from davies_sym.topology.yaml_source import SourceDocument

Outputs = list[tuple[str | None, str | bytes]]


def file_outputs(
    document: SourceDocument, args: argparse.Namespace, progress: Progress, failures: StateFailures
) -> Outputs:
    """The outputs of ``document`` (the file ``args.files[0]``) for the options ``args``
    (target and content; None: the standard output); the states of a train that cannot be
    derived are reported in ``failures``."""
    if is_machine(document.data):
        return machine_outputs(build_machine(document), args, progress)
    train = build_train(document)
    if args.task or args.plot == "":
        option = "--task" if args.task else "--plot"
        raise InputError(
            [Problem(option, "--task is for machines; for a gear train write --plot NAME=START:STOP")], args.files[0]
        )
    if several_degrees_of_freedom(train):
        return several_outputs(train, args, progress)
    return one_input_outputs(train, args, progress, failures)
