# Read by CTest after the discovered GoogleTest lists (TEST_INCLUDE_FILES).
# Adds the label `optimised` to the long runs that the Release suite makes
# and the asan-ubsan stage of scripts/ci-checks.sh leaves out
# (ctest -LE optimised): each walks code that shorter tests already take
# through the sanitizers, and under them each takes half a minute to two
# minutes (docs/reliability.md). Each line: test, then its binary's label.
# A high COST starts them first where CTest has no timings of its own yet
# (a clean clone, as in CI), rather than last, alone on one core.
set(ibfvs_optimised_only
    Readme.EveryCommandLineItShowsRuns apps
    QualityGLTest.MeasuresOnTheBumpySphereCowAndKnot gl
    CurvatureIrregular.ScannedMeshAgainstItsLoopLimitSurface core
    CurvatureIrregular.AtLeastAsAccurateAsCgalJetFitting core
    Curvature.RealMeshesAreWellFormed core
    SceneCommand.EveryExampleSceneRenders apps
    QualityGLTest.RedBackgroundDoesNotBleedIntoTheSphere gl
    StatedNumbers.StatedPageSizesAreThePrograms apps)
while(ibfvs_optimised_only)
  list(POP_FRONT ibfvs_optimised_only test label)
  set_tests_properties(${test} PROPERTIES LABELS "${label};optimised" COST 60)
endwhile()
