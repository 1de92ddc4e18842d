"""ODE machinery that knows no physics: DOP853 in plain floats (:mod:`.dop853`), its coefficients
(:mod:`.dop853_tableau`) and dense output (:mod:`.dense`), Taylor-series steps (:mod:`.series`), event location
(:mod:`.events`) and root finding (:mod:`.roots`)."""
