"""The package's foundation: units, validation, geometry, the ground motion, closed forms,
the end-of-motion verdict. Imports nothing above it.

The models' own modules that lived here (the equation of motion, the results, Shenton's
criteria, ``Friction``) moved into :mod:`shaketable.models`; their old paths still
import, with a :class:`DeprecationWarning` (:mod:`shaketable._moved`).
"""

from shaketable._moved import install, moved_attribute

install()


def __getattr__(name):
    return moved_attribute(__name__, name)
