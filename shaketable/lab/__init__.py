"""The laboratory: the shaking table (command, limits, servo, the 12 Hz pitch) and
the instruments (potentiometers, accelerometers, the digitizer at 50 samples/s),
report Sections 3.2-3.4.
"""

from shaketable.lab.command import TableCommand, displacement_command
from shaketable.lab.limits import LimitExceedance, TableLimits, check_limits
from shaketable.lab.pitch import Pitch, motion_at_block, pitch_history
from shaketable.lab.servo import Actuator, achieved, achieved_displacement

__all__ = ["Actuator", "LimitExceedance", "Pitch", "TableCommand", "TableLimits", "achieved",
           "achieved_displacement", "check_limits", "displacement_command", "motion_at_block",
           "pitch_history"]
