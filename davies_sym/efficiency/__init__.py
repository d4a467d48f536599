"""Efficiency stage: from the solved network to every turning-condition variant -> `VariantSet`.

It owns motions relative to any link (`.absolute_motion`, Laus eqs. (6)-(7), (85)),
the virtual power through each mesh and its carrier (`.virtual_power`, Laus
section 3.1, eqs. (69)-(75)), the turning conditions (`.turning_conditions`, Laus
Table 6), the variants in ordinary mesh efficiencies with their checks
(`.variants`, Laus Tables 5-6 and section 3.6.2), the admissible parameters
(`.parameter_domain`, `.parameters`), the loss of each friction element
(`.power_losses`) and Chen's virtual-power balance as an independent second
route (`.virtual_power_balance`, Chen 2006 ch. 4).
"""
