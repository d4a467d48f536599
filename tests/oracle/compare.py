"""Engine against oracle for one spelling of one random train: every state, both input
directions, speed ratio and efficiency; each comparison classified."""

from __future__ import annotations

import traceback
from dataclasses import dataclass
from fractions import Fraction

from davies_sym.errors import NotCoveredError

from . import engine_adapter as engine
from .balance import OracleError, SelfLocking, solve
from .random_trains import RandomTrain, Spelling

RTOL = 1e-9

#: Outcome kinds, from good to bad.
OK = "ok"
LOCKING = "self-locking"  # oracle: efficiency <= 0, and the engine's is <= 0 too
WRONG = "wrong number"
REFUSAL = "refusal"
TRACEBACK = "traceback"
ORACLE = "oracle error"


@dataclass
class Outcome:
    family: str
    seed: int
    spelling: str
    state: str
    input: str
    quantity: str  # "derive", "speed ratio" or "efficiency"
    kind: str
    detail: str = ""
    engine: Fraction | float | None = None
    oracle: Fraction | float | None = None

    @property
    def case(self) -> str:
        return f"{self.family}-{self.seed}[{self.spelling}] {self.state} in={self.input} {self.quantity}"


def close(a: Fraction | float, b: Fraction | float, rtol: float = RTOL) -> bool:
    """|a - b| <= rtol * max(1, |b|) (exact when both are fractions)."""
    if isinstance(a, Fraction) and isinstance(b, Fraction):
        return abs(a - b) <= Fraction(rtol) * max(Fraction(1), abs(b))
    return abs(float(a) - float(b)) <= rtol * max(1.0, abs(float(b)))


def _failure(exc: BaseException) -> tuple[str, str]:
    if isinstance(exc, engine.REFUSALS):
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
        return REFUSAL, f"{type(exc).__name__}: {first}"
    tb = traceback.extract_tb(exc.__traceback__)
    where = f" at {tb[-1].filename.rsplit('/', 1)[-1]}:{tb[-1].lineno}" if tb else ""
    return TRACEBACK, f"{type(exc).__name__}: {str(exc).strip().splitlines()[0] if str(exc).strip() else ''}{where}"


def compare(train: RandomTrain, sp: Spelling) -> list[Outcome]:
    """Every comparison for ``sp`` (one outcome per quantity, state and input)."""
    spec = train.oracle()
    out: list[Outcome] = []

    def add(
        state: str,
        port: str,
        quantity: str,
        kind: str,
        detail: str = "",
        e: Fraction | float | None = None,
        o: Fraction | float | None = None,
    ) -> None:
        out.append(Outcome(train.family, train.seed, sp.name, state, port, quantity, kind, detail, e, o))

    for state in train.oracle_states():
        estate = sp.engine_state(state.name)
        try:
            engine.engine_derive(sp.yaml, estate)
        except Exception as exc:  # the engine refused or crashed: one outcome for the state
            kind, detail = _failure(exc)
            add(state.name, "-", "derive", kind, detail)
            continue
        add(state.name, "-", "derive", OK)
        # speed ratio of the declared direction, sign by the port revolutes' orientation
        try:
            expected: Fraction | float | None = solve(spec, state.input, state, lossless=True).speed_ratio
            expected = expected * sp.orientation[state.input] * sp.orientation[state.output]
        except OracleError as exc:
            expected = None
            add(state.name, state.input, "speed ratio", ORACLE, f"{type(exc).__name__}: {exc}")
        if expected is not None:
            try:
                got = engine.engine_speed_ratio(sp.yaml, sp.values, estate)
                ok = close(got, expected)
                add(state.name, state.input, "speed ratio", OK if ok else WRONG, "", got, expected)
            except Exception as exc:
                add(state.name, state.input, "speed ratio", *_failure(exc))
        for port in (state.input, state.output):
            locking: SelfLocking | None = None
            try:
                oracle_value: Fraction | float | None = solve(spec, port, state).efficiency
            except SelfLocking as exc:
                oracle_value, locking = None, exc
            except OracleError as exc:
                add(state.name, port, "efficiency", ORACLE, f"{type(exc).__name__}: {exc}")
                continue
            try:
                got = engine.engine_efficiency(sp.yaml, sp.values, sp.ports[port], estate)
            except NotCoveredError as exc:
                if locking is not None and "self-locks" in str(exc):
                    # Both self-lock: the engine refuses, as every entry point does there.
                    add(state.name, port, "efficiency", LOCKING, f"oracle: {locking}; engine: {exc}")
                else:
                    add(state.name, port, "efficiency", *_failure(exc))
                continue
            except Exception as exc:
                add(state.name, port, "efficiency", *_failure(exc))
                continue
            if locking is not None:
                # Both self-lock; the number itself (which driver assignment) has no physical meaning.
                add(
                    state.name,
                    port,
                    "efficiency",
                    LOCKING if got <= 0 else WRONG,
                    f"oracle: {locking}",
                    got,
                    locking.value,
                )
            else:
                assert oracle_value is not None
                add(state.name, port, "efficiency", OK if close(got, oracle_value) else WRONG, "", got, oracle_value)
    return out
