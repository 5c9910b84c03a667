"""Multi-object distances that TrackEval lacks: OSPA, OSPA(2) (a track metric) and GOSPA. The
CLEAR-MOT, IDF1 and HOTA scores of MOTChallenge files are in :mod:`vtrack.evaluate` (TrackEval).
"""

from ._core import GospaResult, OspaResult, gospa, ospa, ospa2

__all__ = ["GospaResult", "OspaResult", "gospa", "ospa", "ospa2"]
