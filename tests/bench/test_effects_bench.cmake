# bench_effects_quick: runs `pacifica-bench-effects --quick --frames 3 --out OUT_DIR` and checks its CSV: the
# header, the plain, zero_effect, explosion (1, 4) and wake (1, 2) rows, finite positive times,
# that the field without the view cull evaluates more tiles than with it (wakes_no_view_cull), that the
# zero-effect frame did no effect work (0 effect passes, draws, uploads and vertices in every timed
# frame: the columns are maxima over the frames), and that every explosion and wake of a setting was active
# and drawn with one pass and one instanced draw of its kind. It asserts nothing about speed.
# Usage: cmake -DEFFECTS_EXE=... -DOUT_DIR=... -P test_effects_bench.cmake
cmake_minimum_required(VERSION 3.25) # IN_LIST (CMP0057) in script mode
file(REMOVE_RECURSE "${OUT_DIR}")
execute_process(COMMAND "${EFFECTS_EXE}" --quick --frames 3 --out "${OUT_DIR}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pacifica-bench-effects --quick exited with ${rc}")
endif()
foreach(f effects.csv effects.md effects.json)
    if(NOT EXISTS "${OUT_DIR}/${f}")
        message(FATAL_ERROR "missing ${OUT_DIR}/${f}")
    endif()
endforeach()
file(STRINGS "${OUT_DIR}/effects.csv" lines)
list(GET lines 0 header)
set(expectedHeader "setting,kind,count,active,drawn,ms_median,ms_p90,us_per_effect_vs_plain,update_us_median,\
render_cpu_ms_median,vertices,fx_vertices,fx_passes,fx_draws,fx_uploads,passes,draws,uploads,programs_built,\
field_tiles,compute_ms,sea_ms,effects_ms,shade_ms,clock,renderer")
if(NOT header STREQUAL expectedHeader)
    message(FATAL_ERROR "unexpected header: ${header}")
endif()
list(REMOVE_AT lines 0)
set(num "[-+]?[0-9]*\\.?[0-9]+([eE][-+]?[0-9]+)?")
set(seen "")
foreach(line IN LISTS lines)
    # setting,kind,count,active,drawn,ms,p90,us_per_effect,update_us,render_cpu,vertices,fx_vertices,fx_passes,
    # fx_draws,fx_uploads,passes,draws,uploads,programs_built,field_tiles,compute_ms,sea_ms,effects_ms,
    # shade_ms,"clock","renderer"
    if(NOT line MATCHES "^([a-z_]+),([a-z]+),([0-9]+),([^\"]*),\"([^\"]*)\",\"([^\"]*)\"$")
        message(FATAL_ERROR "malformed row: ${line}")
    endif()
    set(setting "${CMAKE_MATCH_1}")
    set(kind "${CMAKE_MATCH_2}")
    set(count "${CMAKE_MATCH_3}")
    set(clock "${CMAKE_MATCH_5}")
    set(renderer "${CMAKE_MATCH_6}")
    string(REPLACE "," ";" f "${CMAKE_MATCH_4}")
    list(LENGTH f nf)
    if(NOT nf EQUAL 21)
        message(FATAL_ERROR "expected 26 columns: ${line}")
    endif()
    # The per-pass times of the profiled renderer (same frames, setPassTiming): numbers >= 0.
    foreach(i 17 18 19 20)
        list(GET f ${i} passMs)
        if(NOT passMs MATCHES "^${num}$" OR passMs LESS 0)
            message(FATAL_ERROR "pass time column ${i} '${passMs}' is not a number >= 0: ${line}")
        endif()
    endforeach()
    list(GET f 0 active)
    list(GET f 1 drawn)
    list(GET f 2 ms)
    list(GET f 3 p90)
    list(GET f 9 fxPasses)
    list(GET f 10 fxDraws)
    list(GET f 11 fxUploads)
    list(GET f 8 fxVertices)
    list(GET f 15 programsBuilt)
    list(GET f 16 fieldTiles)
    if(NOT ms MATCHES "^${num}$" OR NOT p90 MATCHES "^${num}$" OR NOT ms GREATER 0 OR p90 LESS ms)
        message(FATAL_ERROR "ms median '${ms}' / p90 '${p90}' not positive numbers with p90 >= median: ${line}")
    endif()
    if(clock STREQUAL "" OR renderer STREQUAL "")
        message(FATAL_ERROR "empty clock or renderer: ${line}")
    endif()
    # Two warm-up frames build the shader variants and upload the grid meshes: the timed frames build none.
    if(NOT programsBuilt EQUAL 0)
        message(FATAL_ERROR "${programsBuilt} shader programs built during timed frames: ${line}")
    endif()
    if(kind STREQUAL "none")
        # No effects (with or without an EffectsSystem): no effect pass, draw, upload or vertex, ever.
        if(NOT fxPasses EQUAL 0 OR NOT fxDraws EQUAL 0 OR NOT fxUploads EQUAL 0 OR NOT fxVertices EQUAL 0
           OR NOT fieldTiles EQUAL 0)
            message(FATAL_ERROR "${setting} did effect work (passes ${fxPasses}, draws ${fxDraws}, uploads "
                                "${fxUploads}, vertices ${fxVertices}): ${line}")
        endif()
    elseif(setting MATCHES "_every_grid$")
        # A grid for every effect (all in view, the bench places them so): the field's compute pass, one
        # grid pass with one instanced draw of `count` grids.
        if(NOT active EQUAL count OR NOT drawn EQUAL count OR NOT fxPasses EQUAL 2 OR NOT fxDraws EQUAL 1
           OR NOT fxVertices GREATER 0 OR NOT fieldTiles GREATER 0)
            message(FATAL_ERROR "${setting} x${count}: active ${active} drawn ${drawn} passes ${fxPasses} draws "
                                "${fxDraws} vertices ${fxVertices} tiles ${fieldTiles}: ${line}")
        endif()
    elseif(setting MATCHES "_no_view_cull$")
        # EffectFieldDesc::viewCull off: every tile the effects touch. The trails run back past the camera, out
        # of its view sector, so the same wakes evaluate more tiles than with the cull.
        if(NOT active EQUAL count OR NOT fieldTiles GREATER "${tiles_${kind}_${count}}")
            message(FATAL_ERROR "${setting} x${count}: active ${active}, tiles ${fieldTiles} not above the "
                                "culled ${tiles_${kind}_${count}}: ${line}")
        endif()
    elseif(kind STREQUAL "fleet")
        # Wakes and explosions together (count = both kinds): every one active and in the field, a grid pass
        # and draw per kind with grids at most.
        if(NOT active EQUAL count OR drawn GREATER count OR NOT fieldTiles GREATER tiles_wake_2
           OR fxPasses GREATER 3 OR fxDraws GREATER 2)
            message(FATAL_ERROR "fleet x${count}: active ${active}, drawn ${drawn}, tiles ${fieldTiles}, passes "
                                "${fxPasses}, draws ${fxDraws}: ${line}")
        endif()
        set(tiles_fleet_${count} "${fieldTiles}")
    else()
        # The defaults: every effect in the field (its compute pass over the tiles they touch, the effect
        # data uploaded each frame), grids only for those next to the eye (a grid pass and draw if any).
        if(NOT active EQUAL count OR drawn GREATER count OR fxUploads LESS 1 OR NOT fieldTiles GREATER 0)
            message(FATAL_ERROR "${count} ${kind}s: active ${active}, drawn ${drawn}, uploads ${fxUploads}, "
                                "field tiles ${fieldTiles}: ${line}")
        endif()
        set(withGrid 0)
        if(drawn GREATER 0)
            set(withGrid 1)
        endif()
        set(tiles_${kind}_${count} "${fieldTiles}")
        math(EXPR wantPasses "1 + ${withGrid}")
        if(NOT fxPasses EQUAL wantPasses OR NOT fxDraws EQUAL withGrid)
            message(FATAL_ERROR "${kind} x${count}: passes ${fxPasses}, draws ${fxDraws} with ${drawn} grids: ${line}")
        endif()
    endif()
    list(APPEND seen "${setting}:${kind}:${count}")
endforeach()
foreach(expected "plain:none:0" "zero_effect:none:0" "explosions:explosion:1" "explosions:explosion:4"
                 "wakes:wake:1" "wakes:wake:2" "explosions_every_grid:explosion:4" "wakes_every_grid:wake:2"
                 "fleet:fleet:4" "wakes_no_view_cull:wake:1")
    if(NOT expected IN_LIST seen)
        message(FATAL_ERROR "missing row ${expected}; rows: ${seen}")
    endif()
endforeach()
# The field's tiles grow with the count (more effects touch more of the sea).
if(NOT tiles_explosion_4 GREATER tiles_explosion_1)
    message(FATAL_ERROR "field tiles do not grow with the explosions: ${tiles_explosion_1} -> ${tiles_explosion_4}")
endif()
file(READ "${OUT_DIR}/effects.md" md)
if(NOT md MATCHES "GL_RENDERER: [^\n]+" OR NOT md MATCHES "## Zero-effect frame")
    message(FATAL_ERROR "effects.md lacks the renderer line or the zero-effect table")
endif()
message(STATUS "effects quick: rows ${seen}; explosion vertices ${vertices_explosion_1}, wake ${vertices_wake_1}")
# The grid density knob (effects_grid.csv): each density has a finite error and a time, and the finer
# explosion grid interpolates the field better (lower mesh RMS) than the coarser one.
file(STRINGS "${OUT_DIR}/effects_grid.csv" gridLines)
list(LENGTH gridLines gridCount)
if(NOT gridCount EQUAL 4)
    message(FATAL_ERROR "effects_grid.csv: expected a header and 3 rows, got ${gridCount} lines")
endif()
list(GET gridLines 1 coarse)
list(GET gridLines 2 fine)
string(REPLACE "," ";" coarse "${coarse}")
string(REPLACE "," ";" fine "${fine}")
list(GET coarse 7 coarseRms)
list(GET fine 7 fineRms)
list(GET fine 9 fineMs)
if(NOT coarseRms MATCHES "^[0-9.e+-]+$" OR NOT fineRms MATCHES "^[0-9.e+-]+$" OR NOT fineMs MATCHES "^[0-9.e+-]+$")
    message(FATAL_ERROR "effects_grid.csv: non-numeric error or time: ${coarse} / ${fine}")
endif()
if(NOT coarseRms GREATER fineRms)
    message(FATAL_ERROR "effects_grid.csv: the 48x96 explosion grid (rms ${fineRms}) is not more accurate than "
                        "24x48 (rms ${coarseRms})")
endif()
message(STATUS "effects grid knob: explosion mesh rms/A ${coarseRms} (24x48) -> ${fineRms} (48x96)")
