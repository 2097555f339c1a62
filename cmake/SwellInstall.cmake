# cmake --install: libraries, public headers, programs, the CMake package (find_package(swell
# CONFIG): swell::cache, swell::bake, swell::runtime, swell::swell) and a pkg-config file for the
# C API (docs/embedding.md). The C++ libraries are static; the package finds their private
# dependencies again (Debian ships no CMake config for zstd, xxhash, FFTW, EGL, libpng).
include(CMakePackageConfigHelpers)

set(SWELL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/swell)

install(TARGETS swell_cache swell_bake swell_runtime swell_shaders swell_c
    EXPORT swellTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS swell-bake swell-play swell-cache
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(dir cache bake runtime shaders)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
install(EXPORT swellTargets NAMESPACE swell:: DESTINATION ${SWELL_CMAKE_DIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/swellConfig.cmake.in
    ${PROJECT_BINARY_DIR}/swellConfig.cmake INSTALL_DESTINATION ${SWELL_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/swellConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/swellConfig.cmake ${PROJECT_BINARY_DIR}/swellConfigVersion.cmake
    DESTINATION ${SWELL_CMAKE_DIR})

# The .pc file finds the prefix from its own folder, so an installed tree can be moved.
file(RELATIVE_PATH SWELL_PC_TO_PREFIX "/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/")
string(REGEX REPLACE "/$" "" SWELL_PC_TO_PREFIX "${SWELL_PC_TO_PREFIX}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/swell.pc.in ${PROJECT_BINARY_DIR}/swell.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/swell.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes DESTINATION ${CMAKE_INSTALL_DATADIR}/swell)
