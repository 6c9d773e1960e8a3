"""shaketable: virtual shaking-table tests of free-standing rigid blocks.

Reproduces Aslam, Godden & Scalise, *Rocking and overturning response of rigid
bodies to earthquake motions* (LBL / UC Berkeley; program BLOKROC).
"""

from .constants import FOOT, G, INCH
from .geometry import Block, PrestressRods
from .motion import Motion
from .results import RockingResult
from .simulate import METHODS, simulate

__all__ = ["Block", "PrestressRods", "Motion", "RockingResult", "simulate", "METHODS", "G",
           "INCH", "FOOT"]
__version__ = "0.1.0"
