"""Script of the gen-files plugin (see ``mkdocs.yml``): the generated pages of the site.

MkDocs runs it on every build; the pages exist only in the build, never in ``docs/``.
"""

from __future__ import annotations

import logging
import os
import sys

import mkdocs_gen_files

TOOLS = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, TOOLS)

from docs_site import generate  # noqa: E402  (the tools folder is not a package)

log = logging.getLogger("mkdocs.plugins.davies_sym")


def _write(path: str, data: bytes) -> None:
    with mkdocs_gen_files.open(path, "wb") as handle:
        handle.write(data)


generate(os.path.dirname(TOOLS), _write, log.info)
