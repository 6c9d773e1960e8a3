"""The laboratory: the shaking table (command, limits, servo, the 12 Hz pitch) and
the instruments (potentiometers, accelerometers, the digitizer at 50 samples/s),
report Sections 3.2-3.4.
"""
