# Gives the long runs of long_runs.txt the label `validate` and their cost (the slowest start
# first when tools/validate runs them side by side). Read by ctest after the discovered tests'
# files, so their names exist.
file(STRINGS ${CMAKE_CURRENT_LIST_DIR}/long_runs.txt swell_long_runs REGEX "^[A-Za-z]")
foreach(name IN LISTS swell_long_runs)
    if(name MATCHES "^Validation\\.")
        set_tests_properties(${name} PROPERTIES LABELS "bake;validation;validate" COST 500)
    endif()
endforeach()
