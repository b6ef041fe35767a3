# Install rules and the package config, so an outside project can
#   find_package(Pacifica CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE Pacifica::ocean)   # and/or Pacifica::engine, Pacifica::capture,
#                                                        # Pacifica::recording
include(CMakePackageConfigHelpers)

set(PACIFICA_EXPORTED_TARGETS pacifica_engine pacifica_ocean pacifica_recording)
if(PACIFICA_WITH_OIIO)
    list(APPEND PACIFICA_EXPORTED_TARGETS pacifica_capture)
endif()
install(TARGETS ${PACIFICA_EXPORTED_TARGETS} EXPORT PacificaTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/ ${PROJECT_SOURCE_DIR}/ocean/include/
                  ${PROJECT_SOURCE_DIR}/tools/recording/include/
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

set(PACIFICA_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Pacifica)
install(EXPORT PacificaTargets NAMESPACE Pacifica:: DESTINATION ${PACIFICA_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/PacificaConfig.cmake.in
    ${PROJECT_BINARY_DIR}/PacificaConfig.cmake INSTALL_DESTINATION ${PACIFICA_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/PacificaConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/PacificaConfig.cmake ${PROJECT_BINARY_DIR}/PacificaConfigVersion.cmake
    DESTINATION ${PACIFICA_CMAKE_DIR})
