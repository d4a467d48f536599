"""Loss models: closed forms that turn what a designer knows about a coupling (tooth
geometry and a sliding friction coefficient, a journal's radius and contact law) into
the constitutive coefficients of the network (ordinary mesh efficiencies, friction-circle
radii), each as a `Definition` of a symbol that
the derivation keeps and the outputs substitute (Laus App. A and App. D)."""

from davies_sym.losses.definitions import Definition
from davies_sym.losses.journal_bearing import CONTACT_LAWS, friction_circle_radius
from davies_sym.losses.tooth_contact import contact_lengths, spur_mesh_efficiency

__all__ = ["CONTACT_LAWS", "Definition", "contact_lengths", "friction_circle_radius", "spur_mesh_efficiency"]
