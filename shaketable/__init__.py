"""shaketable: virtual shaking-table tests of free-standing rigid blocks.

Reproduces Aslam, Godden & Scalise, *Rocking and overturning response of rigid
bodies to earthquake motions* (LBL / UC Berkeley; program BLOKROC).
"""

from shaketable.core.constants import FOOT, INCH, G
from shaketable.core.geometry import Block, PrestressRods
from shaketable.core.motion import Motion
from shaketable.core.results import RockingResult
from shaketable.solvers.api import METHODS, simulate

__all__ = ["Block", "PrestressRods", "Motion", "RockingResult", "simulate", "METHODS", "G",
           "INCH", "FOOT"]
__version__ = "0.1.0"
