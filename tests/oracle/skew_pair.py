"""Independent numeric statics of two gears on crossed axes touching at the pitch point.

Shares no code with the package: its own frame (gear 1 on the z axis, gear 2 across it
along x), its own kinematics (the meshing condition solved for the second speed), and
the equilibrium of each gear about its own axis with the normal force N and the Coulomb
friction mu |N| against the sliding of one flank on the other.  Angles in radians; gear 1
has helix angle beta_1, gear 2 beta_2, same hand, so the shaft angle is beta_1 + beta_2
(a worm of lead angle gamma: beta_1 = pi/2 - gamma, beta_2 = gamma).
"""

from __future__ import annotations

from dataclasses import dataclass
from math import cos, sin


def _sub(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, ...]:
    return tuple(x - y for x, y in zip(a, b, strict=True))


def _dot(a: tuple[float, ...], b: tuple[float, ...]) -> float:
    return sum(x * y for x, y in zip(a, b, strict=True))


def _cross(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, float, float]:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _scaled(k: float, a: tuple[float, ...]) -> tuple[float, ...]:
    return tuple(k * x for x in a)


@dataclass(frozen=True)
class SkewPair:
    r1: float
    r2: float
    beta_1: float
    beta_2: float
    alpha_n: float
    mu: float

    def efficiency(self, input_gear: int = 1) -> float | None:
        """-P_out / P_in with ``input_gear`` (1 or 2) driven by a unit torque at unit speed;
        None where the input cannot drive the pair (self-locking: no sign of the normal
        force, or both, balance the input torque with the friction against the sliding)."""
        c1, p1 = (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)  # gear 1: centre, axis
        shaft = self.beta_1 + self.beta_2
        c2, p2 = (self.r1 + self.r2, 0.0, 0.0), (0.0, sin(shaft), cos(shaft))
        point = (self.r1, 0.0, 0.0)
        # The tooth line (0, sin b1, cos b1) leans by beta_1 from gear 1's axis; the normal
        # lies in the plane across it, leaning out of the pitch plane by alpha_n.
        across = (0.0, cos(self.beta_1), -sin(self.beta_1))
        normal = tuple(cos(self.alpha_n) * a + sin(self.alpha_n) * x for a, x in zip(across, (1, 0, 0), strict=True))

        def speed_at(centre: tuple[float, ...], axis: tuple[float, ...], w: float) -> tuple[float, ...]:
            return _scaled(w, _cross(axis, _sub(point, centre)))

        # Meshing: both flanks move alike along the normal.  The input turns at +1.
        ratio = _dot(speed_at(c1, p1, 1.0), normal) / _dot(speed_at(c2, p2, 1.0), normal)  # w2 / w1
        w1, w2 = (1.0, ratio) if input_gear == 1 else (1.0 / ratio, 1.0)
        sliding = _sub(speed_at(c2, p2, w2), speed_at(c1, p1, w1))  # of gear 2's flank on gear 1's
        norm = _dot(sliding, sliding) ** 0.5
        slide = _scaled(1 / norm, sliding) if norm > 1e-15 else (0.0, 0.0, 0.0)

        def moment(centre: tuple[float, ...], axis: tuple[float, ...], force: tuple[float, ...]) -> float:
            return _dot(_cross(_sub(point, centre), force), axis)

        frames = {1: (c1, p1, w1), 2: (c2, p2, w2)}
        driven = 3 - input_gear
        found = []
        for sign in (1.0, -1.0):
            # Force on gear 2 per unit |N| (N = sign |N|): normal force and friction against
            # gear 2's sliding; gear 1 takes the opposite force.
            on_2 = tuple(sign * n - self.mu * s for n, s in zip(normal, slide, strict=True))
            on = {2: on_2, 1: _scaled(-1.0, on_2)}
            centre, axis, _ = frames[input_gear]
            contact = moment(centre, axis, on[input_gear])
            if contact == 0:
                continue
            magnitude = -1.0 / contact  # equilibrium of the input gear with T_in = 1
            if magnitude <= 0:
                continue
            centre, axis, speed = frames[driven]
            t_out = -magnitude * moment(centre, axis, on[driven])  # the load's torque
            found.append(-t_out * speed)  # -P_out / P_in, P_in = 1
        # A consistent sign whose load gives power back (efficiency <= 0) describes no
        # driven motion; near self-locking it coexists with the working one.
        working = [value for value in found if value > 0]
        if len(working) > 1:
            raise ValueError(f"two working signs of the normal force: {working}")
        return working[0] if working else None
