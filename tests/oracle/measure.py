"""Pass table of the engine against the oracle over seeded random trains.

    python3 tests/oracle/measure.py 300                # 300 seeds of every family
    python3 tests/oracle/measure.py 20 --families planetary,stepped --spellings catalog,reversed
    python3 tests/oracle/measure.py 50 --jobs 8 --yaml wrong.txt   # YAML of the wrong-number cases

Run from the worktree with ``PYTHONPATH`` set to it.  Per family x spelling it prints, over
the trains: how many derive (every state), how many give only correct numbers, how many
give a wrong number, a refusal or a traceback; then every failure class (refusal message
class, exception type) with a count and an example, and the wrong-number cases with both
values.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
import time
from collections import Counter, defaultdict
from concurrent.futures import ProcessPoolExecutor

if __package__ in (None, ""):
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from oracle.compare import LOCKING, OK, ORACLE, REFUSAL, TRACEBACK, WRONG, Outcome, compare
    from oracle.random_trains import FAMILIES, SPELLINGS, generate, spellings
else:  # pragma: no cover - imported as a module
    from .compare import LOCKING, OK, ORACLE, REFUSAL, TRACEBACK, WRONG, Outcome, compare
    from .random_trains import FAMILIES, SPELLINGS, generate, spellings


def message_class(detail: str) -> str:
    """A refusal or exception message without its train-specific parts."""
    text = re.sub(r"oracle\.yaml:\d+: ", "", detail)
    text = re.sub(r"couplings\.[^:\s]+", "couplings.X", text)
    text = re.sub(r"states\.[^:\s]+", "states.X", text)
    text = re.sub(r"'[^']*'", "'…'", text)
    text = re.sub(r"\([^()]*(\([^()]*\)[^()]*)*\)", "(…)", text)
    text = re.sub(r"\bmesh \S+:", "mesh X:", text)
    text = re.sub(r"\b\d+(/\d+)?\b", "N", text)
    text = re.sub(r"sign of .* under", "sign of … under", text)
    text = re.sub(r"signs \{.*\}", "signs {…}", text)
    return text[:150]


def run_one(args: tuple[str, int, tuple[str, ...]]) -> list[tuple[Outcome, str]]:
    """Every outcome of one train (all the given spellings), with the YAML of the spelling."""
    family, seed, names = args
    train = generate(family, seed)
    out = []
    for sp in spellings(train, names).values():
        try:
            outcomes = compare(train, sp)
        except Exception as exc:  # a crash of the comparison itself
            outcomes = [Outcome(family, seed, sp.name, "-", "-", "derive", ORACLE, f"{type(exc).__name__}: {exc}")]
        values = ", ".join(f"{k}: {v}" for k, v in sp.values.items())
        out += [(o, f"# values: {{{values}}}\n{sp.yaml}") for o in outcomes]
    from oracle import engine_adapter

    engine_adapter.clear_cache()
    return out


def train_verdict(outcomes: list[Outcome]) -> str:
    """The worst outcome of one spelling of one train."""
    kinds = {o.kind for o in outcomes}
    for kind in (TRACEBACK, REFUSAL, WRONG, ORACLE):
        if kind in kinds:
            return kind
    return OK


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("n", type=int, nargs="?", default=20, help="seeds per family (0 .. n-1)")
    parser.add_argument("--start", type=int, default=0)
    parser.add_argument("--families", default=",".join(FAMILIES))
    parser.add_argument("--spellings", default=",".join(SPELLINGS))
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--yaml", help="write the YAML and both values of every wrong-number case here")
    parser.add_argument("--examples", type=int, default=3, help="wrong-number examples printed per family x spelling")
    args = parser.parse_args(argv)
    families = tuple(args.families.split(","))
    names = tuple(args.spellings.split(","))
    jobs = [(f, s, names) for s in range(args.start, args.start + args.n) for f in families]
    t0 = time.time()
    results: list[tuple[Outcome, str]] = []
    if args.jobs > 1:
        with ProcessPoolExecutor(args.jobs) as pool:
            for chunk in pool.map(run_one, jobs, chunksize=1):
                results += chunk
    else:
        for job in jobs:
            results += run_one(job)
    by_train: dict[tuple[str, str, int], list[Outcome]] = defaultdict(list)
    for o, _ in results:
        by_train[(o.family, o.spelling, o.seed)].append(o)

    print(f"{args.n} seeds x {len(families)} families, {len(results)} comparisons, {time.time() - t0:.0f} s")
    print(
        "Per train (every state, both inputs): trains / derive ok / all correct / wrong number / "
        "refusal / traceback / oracle error; self-locking cases where both agree count as correct"
    )
    header = (
        f"{'family':14s} {'spelling':9s} {'n':>4s} {'derive':>6s} {'correct':>7s} {'wrong':>5s} "
        f"{'refuse':>6s} {'trace':>5s} {'oracle':>6s}  comparisons ok/all"
    )
    print(header)
    print("-" * len(header))
    for family in families:
        for name in names:
            keys = [k for k in by_train if k[0] == family and k[1] == name]
            if not keys:
                continue
            verdicts = Counter(train_verdict(by_train[k]) for k in keys)
            derive_ok = sum(
                all(o.kind not in (REFUSAL, TRACEBACK) for o in by_train[k] if o.quantity == "derive") for k in keys
            )
            comps = [o for k in keys for o in by_train[k] if o.quantity != "derive"]
            good = sum(o.kind in (OK, LOCKING) for o in comps)
            print(
                f"{family:14s} {name:9s} {len(keys):4d} {derive_ok:6d} {verdicts[OK]:7d} {verdicts[WRONG]:5d} "
                f"{verdicts[REFUSAL]:6d} {verdicts[TRACEBACK]:5d} {verdicts[ORACLE]:6d}  {good}/{len(comps)}"
            )
    print()
    print("Failure classes (count of outcomes, family/spelling, example):")
    classes: dict[tuple[str, str], list[Outcome]] = defaultdict(list)
    for o, _ in results:
        if o.kind in (REFUSAL, TRACEBACK, ORACLE):
            classes[(o.kind, message_class(o.detail))].append(o)
    for (kind, text), items in sorted(classes.items(), key=lambda kv: -len(kv[1])):
        where = Counter(f"{o.family}/{o.spelling}" for o in items)
        print(f"  [{kind}] x{len(items)}: {text}")
        print(f"      in: {', '.join(f'{k} {v}' for k, v in sorted(where.items()))}")
        print(f"      e.g. {items[0].case}: {items[0].detail[:300]}")
    print()
    wrong = [(o, y) for o, y in results if o.kind == WRONG]
    print(f"Wrong numbers: {len(wrong)} comparisons")
    shown: Counter[tuple[str, str]] = Counter()
    for o, _ in wrong:
        key = (o.family, o.spelling)
        if shown[key] < args.examples:
            shown[key] += 1
            print(
                f"  {o.case}: engine {o.engine} ({float(o.engine) if o.engine is not None else None}), "
                f"oracle {o.oracle} ({float(o.oracle) if o.oracle is not None else None})"
            )
    if args.yaml:
        with open(args.yaml, "w", encoding="utf-8") as handle:
            for o, y in wrong:
                handle.write(
                    f"# {o.case}\n# engine {o.engine} = {float(o.engine) if o.engine is not None else None}"
                    f"\n# oracle {o.oracle} = {float(o.oracle) if o.oracle is not None else None}\n"
                )
                handle.write(y + "---\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
