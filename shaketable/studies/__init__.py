"""The report's studies and the teaching gallery, as data (tables and result objects);
their figures are in :mod:`shaketable.plots`.
"""
