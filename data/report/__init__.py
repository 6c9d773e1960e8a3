"""The report's printed tables as CSV (installed as ``shaketable.report_data``)."""
