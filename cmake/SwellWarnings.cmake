# Per-target warning and sanitizer flags (STYLE.md #12). C++20 is a usage requirement of the
# C++ libraries (their headers need it); PRIVATE_STD keeps it private (the C API library, whose
# users may be C programs).
function(swell_target_defaults target)
    cmake_parse_arguments(arg "PRIVATE_STD" "" "" ${ARGN})
    if(arg_PRIVATE_STD)
        target_compile_features(${target} PRIVATE cxx_std_20)
    else()
        target_compile_features(${target} PUBLIC cxx_std_20)
    endif()
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
    if(SWELL_WERROR)
        target_compile_options(${target} PRIVATE -Werror)
    endif()
endfunction()
