"""A train file that YAML cannot safely read is refused while it is read (docs/errors.md).

Unknown or Python tags, merge keys, alias bombs, 10,000 levels of nesting, 50 MB, a 2 MB
single entry, bytes that are not UTF-8, a byte-order mark, nothing, a list or a scalar
instead of a mapping, a key given twice: exit status 2 before any derivation, the message
naming the bound that was hit (the file's size, its nesting depth, its number of entries),
one short message naming the file (and the line where one is meaningful), never a
traceback, never the huge value echoed back, and no payload executed.  The attacks that
would exhaust memory if the reader expanded them run in a fresh process under an
address-space limit.
"""

from __future__ import annotations

import re
from functools import partial

import pytest
from harness.helpers import (
    CATALOG,
    HANG_GUARD,
    assert_not_executed,
    assert_refused,
    replaced,
    run_cli,
    run_main,
)
from harness.helpers import write_file as write

from davies_sym.topology.documents import MAX_FILE_BYTES
from davies_sym.topology.yaml_source import MAX_DEPTH, MAX_NODES

SIMPLE_PAIR = (CATALOG / "simple_pair.yaml").read_text(encoding="utf-8")
RADIUS_LINE = "  1: {link: 1, radius: r1}"  # line 11 of simple_pair.yaml
#: The simple pair with its first ``old`` (which must be there) replaced by ``new``.
simple_pair_with = partial(replaced, SIMPLE_PAIR)
#: A hang guard only, never a claim about speed: a run still going after this long is killed
#: (and fails); how little work a refusal takes is asserted as the bound it names (`READ_BOUNDS`).
KILL_AFTER = HANG_GUARD
#: The attacks in a fresh process run with this address-space limit: one that expanded the
#: document in memory would fail in its own process instead of starving the machine.
ATTACK_MEMORY = 2 * 1024**3
#: The refusal happens while the file is read: the message begins with the reading stage's kind.
READING_STAGE = re.compile(r"^(YAML syntax error|topology error): ")


def _alias_bomb() -> str:
    lines = ['a0: &a0 ["lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol", "lol"]']
    for i in range(1, 10):
        lines.append(f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]")
    return SIMPLE_PAIR + "notes_bomb:\n  " + "\n  ".join(lines) + "\n"


def _fifty_megabytes() -> bytes:
    padding = ("# " + "x" * 98 + "\n").encode() * (50 * 1024 * 1024 // 100)
    return SIMPLE_PAIR.encode() + padding


YAML_ATTACKS: dict[str, tuple[object, int | None, bool]] = {
    "python_object_apply_tag": (
        simple_pair_with(RADIUS_LINE, '  1: {link: 1, radius: !!python/object/apply:os.system ["touch {m}"]}'),
        11,
        False,
    ),
    "python_name_tag": (simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: !!python/name:os.system }"), 11, False),
    "unknown_local_tag": (simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: !gear r1}"), 11, False),
    "merge_key": (simple_pair_with("  2: {link: 2, radius: r2}", "  2: {<<: {link: 2}, radius: r2}"), 12, False),
    "merge_key_with_anchor": (
        simple_pair_with(
            "  1: {link: 1, radius: r1}\n  2: {link: 2, radius: r2}",
            "  1: &g {link: 1, radius: r1}\n  2:\n    <<: *g\n    link: 2",
        ),
        13,
        False,
    ),
    "alias_bomb": (_alias_bomb(), None, True),
    "deep_nesting": (SIMPLE_PAIR + "notes: " + "[" * 10000 + "]" * 10000 + "\n", 27, True),
    "fifty_megabytes": (_fifty_megabytes(), None, True),
    "two_megabyte_entry": (simple_pair_with("name: Simple gear pair", "name: " + "x" * (2 * 1024 * 1024)), None, True),
    "two_megabyte_number": (
        simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: " + "7" * (2 * 1024 * 1024) + "}"),
        None,
        True,
    ),
    "not_utf8": (
        simple_pair_with("name: Simple gear pair", "name: Simple gear pair caf\udce9").encode(
            "utf-8", errors="surrogateescape"
        ),
        None,
        False,
    ),
    "byte_order_mark": (b"\xef\xbb\xbf" + SIMPLE_PAIR.encode(), None, False),
    "utf16": (SIMPLE_PAIR.encode("utf-16"), None, False),
    "empty": (b"", None, False),
    "comments_only": (b"# nothing here\n\n", None, False),
    "list": ("- format: 1\n- name: x\n", None, False),
    "scalar": ("just some text\n", None, False),
    "null_document": ("~\n", None, False),
    "two_documents": (SIMPLE_PAIR + "---\n" + SIMPLE_PAIR, 27, False),
    "duplicate_top_level_key": (simple_pair_with("source:", "name: Another name\nsource:"), 4, False),
    "duplicate_gear": (
        simple_pair_with("  2: {link: 2, radius: r2}", "  2: {link: 2, radius: r2}\n  2: {link: 2, radius: r3}"),
        13,
        False,
    ),
    "duplicate_key_in_entry": (simple_pair_with(RADIUS_LINE, "  1: {link: 1, radius: r1, radius: r9}"), 11, False),
    "control_character": (simple_pair_with("name: Simple gear pair", "name: Simple \x07 gear pair"), 3, False),
}
#: The bound each large attack hits, as its message names it: the work done is bounded by it,
#: whatever the machine's load (the file read at most to its size limit, the document
#: converted at most to its depth and entry limits).
READ_BOUNDS = {
    "alias_bomb": f"more than {MAX_NODES} entries through aliases",
    "deep_nesting": f"nests deeper than {MAX_DEPTH} levels",
    "fifty_megabytes": f"larger than {MAX_FILE_BYTES // 1000} kB",
    "two_megabyte_entry": f"larger than {MAX_FILE_BYTES // 1000} kB",
    "two_megabyte_number": f"larger than {MAX_FILE_BYTES // 1000} kB",
}


@pytest.mark.parametrize("attack", list(YAML_ATTACKS))
def test_yaml_attack_gives_one_short_clear_refusal(tmp_path, attack):
    content, line, fresh = YAML_ATTACKS[attack]
    marker = tmp_path / "MARKER"
    if isinstance(content, str):
        content = content.replace("{m}", str(marker))
    path = write(tmp_path, f"{attack}.yaml", content)  # type: ignore[arg-type]
    args = [str(path), "--quiet"]
    result = run_cli(args, timeout=KILL_AFTER, memory=ATTACK_MEMORY) if fresh else run_main(args, timeout=KILL_AFTER)
    assert_not_executed(marker, result=result)
    assert_refused(result, path, line=line is not None, max_lines=None)
    assert READING_STAGE.match(result.stderr), f"not refused while reading the file:\n{result.describe()}"
    if attack in READ_BOUNDS:
        assert READ_BOUNDS[attack] in result.stderr, f"the message names no bound:\n{result.describe()}"
    if line is not None:
        assert re.search(re.escape(str(path)) + f":{line}:", result.stderr), (
            f"the message does not give line {line}:\n{result.describe()}"
        )
