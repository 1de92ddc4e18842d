"""ODE machinery that knows no physics: DOP853 in plain floats (:mod:`.dop853`) and its dense output
(:mod:`.dense`), Taylor-series steps (:mod:`.series`) and event location (:mod:`.events`)."""
