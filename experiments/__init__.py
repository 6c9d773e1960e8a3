"""The report's experiments as scene files (installed as ``shaketable.experiments``)."""
