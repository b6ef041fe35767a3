# ctest driver: install the build tree into a temporary prefix, configure + build the consumer project
# against it with find_package(Pacifica), and run it. Args: BUILD_DIR, SOURCE_DIR, WORK_DIR.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
function(run)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "command failed (${rc}): ${ARGN}\n${out}\n${err}")
    endif()
    message(STATUS "${out}")
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)

# The ocean alone: only its own dependencies visible. pkg-config sees every installed .pc file except those
# of the other components' libraries; OpenImageIO's and GLFW's CMake packages are switched off.
execute_process(COMMAND pkg-config --variable pc_path pkg-config OUTPUT_VARIABLE pc_path
                OUTPUT_STRIP_TRAILING_WHITESPACE)
string(REPLACE ":" ";" pc_path "${pc_path}")
file(MAKE_DIRECTORY ${WORK_DIR}/pkgconfig)
foreach(dir IN LISTS pc_path)
    file(GLOB pcs ${dir}/*.pc)
    foreach(pc IN LISTS pcs)
        get_filename_component(name ${pc} NAME)
        if(NOT name MATCHES "^(OpenColorIO|netcdf|libzip|geographiclib|libisal)\\.pc$"
           AND NOT EXISTS ${WORK_DIR}/pkgconfig/${name})
            file(CREATE_LINK ${pc} ${WORK_DIR}/pkgconfig/${name} SYMBOLIC)
        endif()
    endforeach()
endforeach()
set(ENV{PKG_CONFIG_LIBDIR} ${WORK_DIR}/pkgconfig)
set(ENV{PKG_CONFIG_PATH} "")
execute_process(COMMAND pkg-config --exists OpenColorIO RESULT_VARIABLE hidden)
if(hidden EQUAL 0)
    message(FATAL_ERROR "OpenColorIO is still visible to pkg-config: the ocean-only check would prove nothing")
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer/ocean_only -B ${WORK_DIR}/ocean_only -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix
    -DCMAKE_DISABLE_FIND_PACKAGE_OpenImageIO=ON -DCMAKE_DISABLE_FIND_PACKAGE_glfw3=ON)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/ocean_only)
run(${WORK_DIR}/ocean_only/consumer_noexcept)
file(REMOVE_RECURSE ${WORK_DIR})
