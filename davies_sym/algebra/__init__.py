"""Exact algebra every stage shares; nothing here knows about gears.

- `.polynomials`: one python-flint polynomial ring per train, rational functions
  kept with factored numerator and denominator (the representation of PERFORMANCE.md).
- `.linalg`: sparse fraction-free Gauss-Jordan elimination over that ring, the
  null spaces of M_N and D_A (Laus eqs. (19), (23), (56)).
- `.radicals`: square roots of the geometry as symbols s with s^2 = m (Laus App. C).
- `.signs`: provable signs of expressions in positive symbols.
- `.symbol_order`: symbols sorted by name, then assumptions (never hash order).
- `.screws`: Plücker coordinates, twists in axis and wrenches in ray formation,
  power as their inner product (Laus section 2.2, eq. (5)).
"""
