"""The planar block with friction (rest, slide, rock, slide-rock, flight): its physics,
Shenton's start criteria, the compiled event-driven engine, the SciPy and Moreau-Jean
references, the batch and the results
(:class:`~shaketable.models.planar.result.PlanarResult`)."""
