# The slowest bake tests and their run times in seconds (a clean-clone `.ci/run` on the 2-core
# VM, 2026-12-03). ctest starts tests in descending COST; without this, a clean build has no
# timing history and the progressive wave (about 5-8 min) starts half-way through the suite
# and runs alone at its end. Only an order hint: a stale figure costs time, never a result.
set_tests_properties(
    Validation.ProgressiveWaveKeepsItsHeightOverThreeWavelengthsAtCiResolution
    PROPERTIES COST 490)
set_tests_properties(Validation.StillTankAtHalfTheStepIsCalmWithTheDampingAgainstTheShift
    PROPERTIES COST 100)
set_tests_properties(Validation.StandingWaveKeepsLinearTheorysPeriodAtCiResolution
    PROPERTIES COST 50)
set_tests_properties(Validation.SolitaryWaveKeepsItsCelerityAtCiResolution
    PROPERTIES COST 60)
set_tests_properties(Validation.WetDamBreakFollowsStokerAtCiResolution
    PROPERTIES COST 60)
set_tests_properties(Validation.ShoalingFollowsGrilliAtCiResolution
    PROPERTIES COST 150)
