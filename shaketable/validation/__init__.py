"""Validation against measured shake-table tests: read a folder of tests, calibrate an
equivalent block by maximum likelihood, predict verdicts with probabilities, score them.

Modules: folder (the folder of tests), model (the equivalent block, the candidate grid,
the candidates' simulated verdicts), fit (likelihood, calibration, intervals, ensemble),
score (accuracy, confusion, log loss, Brier, reliability, fragility), check
(cross-validation with baselines, bootstrap check of the intervals), workflow (the three
steps on folders).
"""
