"""The package's foundation: units, validation, geometry, the ground motion, the equation
of motion (Eq. 2-13/2-14), closed forms and the result object. Imports nothing above it.
"""
