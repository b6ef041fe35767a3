# Third-party dependencies, all from Debian 12 packages. See docs/PLATFORM.md for the quirks
# worked around here (OCIO and epoxy through pkg-config, OIIO's stale opencv include path).
find_package(PkgConfig REQUIRED)
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
pkg_check_modules(OCIO REQUIRED IMPORTED_TARGET OpenColorIO)
find_package(glm CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(Threads REQUIRED)

if(PACIFICA_WITH_GLFW)
    find_package(glfw3 CONFIG REQUIRED)
endif()

if(PACIFICA_WITH_OIIO)
    find_package(OpenImageIO CONFIG REQUIRED)
    # Debian 12's OpenImageIO targets list /usr/include/opencv4, which only exists with libopencv-dev.
    foreach(tgt OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
        if(TARGET ${tgt})
            get_target_property(dirs ${tgt} INTERFACE_INCLUDE_DIRECTORIES)
            if(dirs)
                list(FILTER dirs EXCLUDE REGEX "opencv4")
                set_target_properties(${tgt} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${dirs}")
            endif()
        endif()
    endforeach()
endif()

if(PACIFICA_BUILD_TESTS)
    find_package(GTest CONFIG REQUIRED)
    find_package(benchmark CONFIG QUIET)
endif()
