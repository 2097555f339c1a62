# Per-target warning and sanitizer flags (STYLE.md #12).
function(swell_target_defaults target)
    target_compile_features(${target} PUBLIC cxx_std_20)
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
    if(SWELL_WERROR)
        target_compile_options(${target} PRIVATE -Werror)
    endif()
endfunction()
