"""The rocking block (Eq. 2-13/2-14): its physics, the compiled engine and its steppers,
the SciPy reference, the batch, the run over velocity steps, the asymmetric block and
the results (:class:`~shaketable.models.rocking.result.RockingResult`)."""
