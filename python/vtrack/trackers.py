"""Multi-object trackers (the C++ ``filters`` layer), one surface for all of them.

Every tracker is built with keyword parameters that have the papers' defaults
(``Tracker.default_params()``; ``tracker.params`` gives the values in force; an unknown or
wrongly typed keyword is a ``TypeError`` naming it), and ``step`` returns a :class:`Tracks`:
``ids`` (int64, stable for a track's life), ``boxes`` (N x 4 x, y, w, h), ``scores``, and the
filter's own extras (``states``, ``covariances``, GLMB ``labels``).
:func:`vtrack.io.mot_rows` turns any of them into MOTChallenge rows.

=========================  ===============================================  =====================
tracker                    built with                                       step(...)
=========================  ===============================================  =====================
MultiBernoulliTracker      ``(image_size, **params)``                       ``y`` (H x W float32)
ReclusteringSirTracker     ``(image_size, **params)``                       ``y`` (H x W float32)
BoxTracker                 ``(image_size, **params)``                       ``boxes`` (M x 4 or 5)
GlmbTracker                ``(motion, observation, births, **params)``      ``detections`` (M x z)
=========================  ===============================================  =====================

Single-object trackers initialised with a box, in the shape of OpenCV's tracker API
(``t.init(frame, box)``, ``ok, box = t.update(frame)``): ``ColorParticleTracker`` (the colour-
histogram particle filter) and ``PartParticleTracker`` (the part-based particle filter on a
graphical model), part-based-graphical-model-pf.txt; ``vtrack.follow`` runs them on a video.
"""

from ._core import (
    BernoulliComponent,
    BoxTracker,
    ColorParticleTracker,
    GlmbTracker,
    MultiBernoulliTracker,
    PartParticleTracker,
    ReclusteringSirTracker,
    Tracks,
    ellipse_log_likelihood,
)

__all__ = ["BernoulliComponent", "BoxTracker", "ColorParticleTracker", "GlmbTracker",
           "MultiBernoulliTracker", "PartParticleTracker", "ReclusteringSirTracker", "Tracks",
           "ellipse_log_likelihood"]
