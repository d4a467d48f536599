"""Network stage: Davies' method proper, from a train and its layout to motions, actions and powers.

It owns the coupling graph G_C with its circuit and cutset matrices (`.coupling_graph`,
Laus section 2.1, App. E), the screws each coupling kind contributes (`.shared_screws`,
Laus Tables 3-4, 12-15), the minimal screw system of order d (`.screw_system`), the
network matrices M_N and A_N and the constitutive rows of the friction laws
(`.matrices`, Laus eqs. (19), (22), (40), (51)-(52), (56)), and their null spaces
with the efficiency -P_out/P_in (`.analysis`, Laus eqs. (23)-(32)) -> `Analysis`, run
with `.analysis_options`, its action null space checked by `.action_nullity`, its powers
paired on the condensed screws of `.condensed_screws`.
"""
