"""Assignment: the optimal linear assignment (Jonker-Volgenant), Murty's k best assignments and
the Gibbs sampler over assignments of Vo, Vo & Hoang (2017), which rank the GLMB's hypotheses.
"""

from ._core import gibbs_assignments, linear_assignment, murty

__all__ = ["gibbs_assignments", "linear_assignment", "murty"]
