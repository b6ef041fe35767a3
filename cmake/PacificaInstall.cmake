# Install rules and the package config, so an outside project can
#   find_package(Pacifica CONFIG REQUIRED)                     # every component
#   find_package(Pacifica CONFIG REQUIRED COMPONENTS ocean)    # the ocean and the engine core only
#   target_link_libraries(app PRIVATE Pacifica::ocean)   # and/or Pacifica::engine, Pacifica::color,
#                                                        # Pacifica::window, Pacifica::png,
#                                                        # Pacifica::capture,
#                                                        # Pacifica::recording
# Each target is its own install component and export set, and the config looks for a component's
# dependencies only when it is asked for (cmake/PacificaConfig.cmake.in): an ocean-only host needs neither
# OpenColorIO nor netCDF.
include(CMakePackageConfigHelpers)

set(PACIFICA_COMPONENTS engine color window png ocean recording) # in dependency order
if(PACIFICA_WITH_OIIO)
    list(APPEND PACIFICA_COMPONENTS capture)
endif()
set(PACIFICA_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Pacifica)
foreach(component IN LISTS PACIFICA_COMPONENTS)
    install(TARGETS pacifica_${component} EXPORT Pacifica_${component}Targets COMPONENT ${component}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    install(EXPORT Pacifica_${component}Targets NAMESPACE Pacifica:: DESTINATION ${PACIFICA_CMAKE_DIR}
        COMPONENT ${component})
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/ ${PROJECT_SOURCE_DIR}/ocean/include/
                  ${PROJECT_SOURCE_DIR}/engine/recording/include/
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
    PATTERN ObjectRenderer.h EXCLUDE) # the demo hosts' objects (pacifica_objects) are not installed

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/PacificaConfig.cmake.in
    ${PROJECT_BINARY_DIR}/PacificaConfig.cmake INSTALL_DESTINATION ${PACIFICA_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/PacificaConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/PacificaConfig.cmake ${PROJECT_BINARY_DIR}/PacificaConfigVersion.cmake
    DESTINATION ${PACIFICA_CMAKE_DIR})
