"""davies_sym: closed-form mechanical efficiency of gear trains by Davies' method.

>>> import davies_sym
>>> train = davies_sym.load("catalog/simple_pair.yaml")   # doctest: +SKIP
>>> davies_sym.analyse(train).efficiency                   # doctest: +SKIP
r1*(r2 - zeta_C)/(r2*(r1 + zeta_C))
"""

from .analysis import Analysis, SignCondition, analyse
from .errors import (
    DaviesError,
    DerivationError,
    GeometryError,
    InputError,
    MobilityError,
    TopologyError,
    TopologySyntaxError,
)
from .loader import load, loads
from .model import Gear, Link, Ports, Train

__all__ = [
    "Analysis",
    "DaviesError",
    "DerivationError",
    "Gear",
    "GeometryError",
    "InputError",
    "Link",
    "MobilityError",
    "Ports",
    "SignCondition",
    "TopologyError",
    "TopologySyntaxError",
    "Train",
    "analyse",
    "load",
    "loads",
]

__version__ = "0.1.0"
