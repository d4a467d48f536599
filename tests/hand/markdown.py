"""The code blocks of a Markdown page, and the commands of its console blocks with the
output each shows, for the tests that hold the README and the docs to what they show."""

from __future__ import annotations

import re


def blocks(text: str, language: str) -> list[str]:
    return re.findall(rf"^```{language}\n(.*?)^```", text, flags=re.S | re.M)


def commands(block: str) -> list[tuple[str, str]]:
    """(command, the output shown under it) of each ``$`` line of a console block; a line
    ending in a backslash goes on on the next."""
    out: list[tuple[str, str]] = []
    lines = block.splitlines()
    k = 0
    while k < len(lines):
        if not lines[k].startswith("$ "):
            k += 1
            continue
        command = lines[k][2:]
        while command.endswith("\\"):
            k += 1
            command = command[:-1] + " " + lines[k].strip()
        k += 1
        shown = []
        while k < len(lines) and not lines[k].startswith("$ "):
            shown.append(lines[k])
            k += 1
        out.append((command, "\n".join(shown).strip()))
    return out
