"""The old home of the solvers, kept so that old imports keep working.

The solvers moved into the models' folders (:mod:`shaketable.models.rocking`,
:mod:`shaketable.models.planar`, :mod:`shaketable.models.sliding`; ``simulate`` into
:mod:`shaketable.models.api`). ``shaketable.solvers.<module>`` still imports, as the
module at its new path, with a :class:`DeprecationWarning` (:mod:`shaketable._moved`).
"""

from shaketable._moved import install, moved_attribute

install()


def __getattr__(name):
    return moved_attribute(__name__, name)
