"""The sliding block (Coulomb stick-slip, exact between samples): the engine, the friction
input (:class:`~shaketable.models.sliding.result.Friction`) and the result."""
