"""Reading an input file (a gear train or a machine) into a parsed YAML document,
with its size and encoding bounded first."""

from __future__ import annotations

import os

from davies_sym.errors import Problem, TopologyError
from davies_sym.topology.yaml_source import SourceDocument, parse_yaml

#: Largest input file read (bytes).
MAX_FILE_BYTES = 1_000_000


def read_train_file(path: str | os.PathLike[str]) -> bytes:
    """The bytes of an input file, at most one byte past the size limit
    (`document_from_bytes` refuses the rest); `TopologyError` when it cannot be read."""
    try:
        with open(path, "rb") as handle:
            return handle.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise TopologyError([Problem("", f"cannot read the file: {exc.strerror}")], os.fspath(path)) from None


def document_from_bytes(data: bytes, name: str | None = None) -> SourceDocument:
    """The parsed document of an input file's bytes; ``name`` is used in messages."""
    if len(data) > MAX_FILE_BYTES:
        raise TopologyError(
            [Problem("", f"the file is larger than {MAX_FILE_BYTES // 1000} kB; a train file is a few kB")], name
        )
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise TopologyError(
            [Problem("", f"the file is not UTF-8 text (byte {exc.start}); save it as UTF-8")], name
        ) from None
    return parse_yaml(text, name)


def read_document(path: str | os.PathLike[str]) -> SourceDocument:
    """Read and parse the input file at ``path``."""
    return document_from_bytes(read_train_file(path), os.fspath(path))
