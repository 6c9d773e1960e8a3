"""Models laid out one folder each, behind one interface (:mod:`shaketable.models.base`).

A model folder holds its physics, its engine, its independent reference and its result
class; :mod:`shaketable.models.registry` names the models. ``stack`` (a column of rigid
blocks rocking on each other) is the first model laid out this way.
"""
