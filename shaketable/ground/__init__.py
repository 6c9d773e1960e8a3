"""Ground motions: generators (harmonic, pulses, artificial accelerograms),
signal utilities (resample, trim, spectra), record readers and the bundled records.
"""
