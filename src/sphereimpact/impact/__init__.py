"""One impact: the scene (:mod:`.scene`), its solution (:mod:`.solve`: the normal motion from the
integrators, the tangential motion from the contact's tangential model), the outcome (:mod:`.outcome`), the
full planar body that cross-checks the reduced model (:mod:`.planar`) and the damping set from a measured
COR (:mod:`.calibrate`)."""
