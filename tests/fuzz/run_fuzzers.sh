#!/bin/sh
# Builds the recorded-flight reader fuzzers, the ACMI writer/reader round trip and the image inputs with
# clang's libFuzzer (+ AddressSanitizer, UndefinedBehaviorSanitizer, LeakSanitizer) and runs each for SECONDS,
# starting from a seed corpus of real inputs (the first lines of the DCS recording, an IGC file, the demo flight
# CSV, small EXR/PNG/HDR images made with oiiotool). Fails on any crash, leak, timeout (a hang: 10 s per input)
# or out-of-memory; prints the executions each made (libFuzzer's final stats).
#   tests/fuzz/run_fuzzers.sh SOURCE_DIR WORK_DIR SECONDS     (ctest runs it with 10 s; longer by hand)
set -eu
SRC=$1
WORK=$2
SECONDS_EACH=${3:-15}
CXX=${PACIFICA_FUZZ_CXX:-clang++-14}
command -v "$CXX" >/dev/null || { echo "run_fuzzers: $CXX not found (apt-get install clang-14 libclang-rt-14-dev)"; exit 1; }
mkdir -p "$WORK"
FLAGS="-std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
-I$SRC/engine/recording/include -I$SRC/tools/src -I$SRC/engine/include"
LIB="$SRC/engine/recording/src/Recording.cpp $SRC/engine/recording/src/Acmi.cpp $SRC/engine/recording/src/Igc.cpp \
$SRC/engine/recording/src/AcmiWriter.cpp $SRC/tools/src/FlightPath.cpp $SRC/engine/src/Pose.cpp"
TARGETS="acmi igc csv acmi_roundtrip image game_options tool_options ocio_config"
# fuzz_image: the image inputs (height maps, environment maps, EXRs) through OpenImageIO.
IMAGE_SRC="$SRC/engine/src/capture/Capture.cpp $SRC/engine/src/capture/Png.cpp $SRC/engine/src/AtomicFile.cpp \
$SRC/tools/src/ImageInputs.cpp $SRC/ocean/src/HeightOctaves.cpp $SRC/ocean/src/Lighting.cpp $SRC/ocean/src/SurfaceModel.cpp"
# fuzz_game_options: pacifica-game's command line.
GAME_SRC="$SRC/game/Options.cpp $SRC/ocean/src/Presets.cpp"
# fuzz_tool_options: pacifica's command line (tools/src/Commands.cpp) down to the ocean's description, which
# makes an ocean for --sea-state (the component's CPU side, no renderer).
TOOL_SRC="$SRC/tools/src/Commands.cpp $SRC/tools/src/OceanOptions.cpp $SRC/tools/src/Usage.cpp \
$SRC/tools/src/ChunkFrames.cpp $SRC/tools/src/ImageInputs.cpp $SRC/engine/src/capture/Capture.cpp \
$SRC/engine/src/capture/Png.cpp $SRC/engine/src/AtomicFile.cpp $SRC/engine/src/Log.cpp $SRC/ocean/src/HeightOctaves.cpp \
$SRC/ocean/src/Lighting.cpp $SRC/ocean/src/SurfaceModel.cpp $SRC/ocean/src/Presets.cpp $SRC/ocean/src/SeaState.cpp \
$SRC/ocean/src/RadialGrid.cpp $SRC/ocean/src/OceanComponent.cpp $SRC/ocean/src/OceanHost.cpp \
$SRC/ocean/src/SurfaceModels.cpp $SRC/ocean/src/FftOcean.cpp $SRC/ocean/src/GerstnerWaves.cpp $SRC/ocean/src/Effects.cpp"
# fuzz_ocio_config: an OCIO config file through the engine's ColorPipeline.
OCIO_SRC="$SRC/engine/src/color/ColorPipeline.cpp $SRC/engine/src/Log.cpp"
for t in $TARGETS; do
    case $t in
    image) deps="$IMAGE_SRC $SRC/engine/include $SRC/ocean/include $SRC/engine/src/capture" ;;
    game_options) deps="$GAME_SRC $SRC/game/Options.h $SRC/ocean/include" ;;
    tool_options) deps="$TOOL_SRC $SRC/tools/src $SRC/ocean/include $SRC/ocean/src $SRC/engine/include $SRC/engine/src/capture" ;;
    ocio_config) deps="$OCIO_SRC $SRC/engine/include $SRC/engine/src/color" ;;
    *) deps="$LIB $SRC/engine/recording" ;;
    esac
    # shellcheck disable=SC2086
    if [ ! -x "$WORK/fuzz_$t" ] || [ -n "$(find $deps "$SRC/tools/src/ImageInputs.h" "$SRC/tests/fuzz" \
        -newer "$WORK/fuzz_$t" -type f 2>/dev/null | head -1)" ]; then
        echo "building fuzz_$t"
        if [ "$t" = image ]; then
            # shellcheck disable=SC2086
            "$CXX" $FLAGS -I"$SRC/ocean/include" -I/usr/include/OpenEXR -I/usr/include/Imath \
                "$SRC/tests/fuzz/fuzz_image.cpp" $IMAGE_SRC -lOpenImageIO -lOpenImageIO_Util -lxxhash -lpng \
                -o "$WORK/fuzz_$t"
        elif [ "$t" = game_options ]; then
            # shellcheck disable=SC2086
            "$CXX" $FLAGS -I"$SRC/game" -I"$SRC/game/include" -I"$SRC/ocean/include" \
                "$SRC/tests/fuzz/fuzz_game_options.cpp" $GAME_SRC -o "$WORK/fuzz_$t"
        elif [ "$t" = tool_options ]; then
            # shellcheck disable=SC2086
            "$CXX" $FLAGS -I"$SRC/ocean/include" "$SRC/tests/fuzz/fuzz_tool_options.cpp" $TOOL_SRC \
                -lOpenImageIO -lOpenImageIO_Util -lxxhash -lpng -lkissfft-float -o "$WORK/fuzz_$t"
        elif [ "$t" = ocio_config ]; then
            # shellcheck disable=SC2086
            "$CXX" $FLAGS "$SRC/tests/fuzz/fuzz_ocio_config.cpp" $OCIO_SRC -lOpenColorIO -o "$WORK/fuzz_$t"
        else
            # shellcheck disable=SC2086
            "$CXX" $FLAGS "$SRC/tests/fuzz/fuzz_$t.cpp" $LIB -lzip -lisal -o "$WORK/fuzz_$t"
        fi
    fi
done
# Seed corpora.
mkdir -p "$WORK/corpus_acmi" "$WORK/corpus_igc" "$WORK/corpus_csv" "$WORK/corpus_acmi_roundtrip" "$WORK/corpus_image" \
    "$WORK/corpus_game_options" "$WORK/corpus_tool_options" "$WORK/corpus_ocio_config"
# The real DCS recording's first 6000 bytes, when the shared data directory ($PACIFICA_SHARED_DIR) has it.
DCS="${PACIFICA_SHARED_DIR:-}/data/flights/dcs-blacksea-f14b.txt.acmi"
if [ -n "${PACIFICA_SHARED_DIR:-}" ] && [ -f "$DCS" ]; then
    head -c 6000 "$DCS" | sed '1s/^/\x07/' > "$WORK/corpus_acmi/dcs_head"
fi
printf '\001FileType=text/acmi/tacview\r\nFileVersion=2.1\r\n0,Comments=a\\\r\n-b\\\r\n#c\r\n1f,T=1|2|3|4|5|6,Name=A\\, B\r\n#1\r\n1f,T=||9\r\n0,Event=Destroyed|1f|x\r\n-1f\r\n' \
    > "$WORK/corpus_acmi/edge"
printf 'AXXX\r\nHFDTEDATE:150717,01\r\nHFPLTPILOTINCHARGE:A\r\nB2359584600000N00700000EA0100001000\r\nB0000024600100N00700100EA0100501050\r\nB0000064600200N00700300EV-001000000\r\n' \
    > "$WORK/corpus_igc/rollover"
head -c 4000 "$SRC/tools/data/demo_flight.csv" > "$WORK/corpus_csv/demo_head"
# The game's command lines, one argument a line: the e2e sortie's, a headless wipe, a bench with --help.
printf -- '--autopilot\n--frames\n202\n--fps\n4\n--quality\nlow\n--size\n640x360\n--camera\nweapon\n--screenshot\n1:deck.png' \
    > "$WORK/corpus_game_options/sortie"
printf -- '--headless\n--frames\n10\n--wind\n25\n--model\nfft\n--wipe\nACES\n--wipe-position\n0.3\n--no-hud\n--view\nRaw' \
    > "$WORK/corpus_game_options/wipe"
printf -- '--bench\nb.json\n--record\nk.acmi\n--summary\ns.json\n--help' > "$WORK/corpus_game_options/bench"
# pacifica's command lines, one argument a line: a replay with views and frames, a tonemap comparison, a farm
# run with replay options after --, a replay with the lighting and FFT knobs.
printf -- 'replay\nf.csv\n--out\nout\n--size\n320x180\n--fps\n2\n--model\nfft\n--frames\n0-9\n--view\nRaw\n--egl-device\nauto' \
    > "$WORK/corpus_tool_options/replay"
printf -- 'tonemap\ncompare\na.exr\n--out\ncmp\n--lut3d\n17\n--pair\nhable,agx\n--tile-width\n200\n--max-pixels\n1000' \
    > "$WORK/corpus_tool_options/compare"
printf -- 'farm\nrun\na.acmi\n--out\nrun\n--chunk-frames\n50\n--workers\n2\n--\n--size\n160x90\n--quality\nlow\n--sun-elevation\n20' \
    > "$WORK/corpus_tool_options/farm"
printf -- 'replay\nf.csv\n--out\no\n--quality\nmedium\n--grid\nprojected\n--fog-color\n0.5,0.6,0.7\n--fft-cascades\n3\n--rig\norbit:1,size=64x64' \
    > "$WORK/corpus_tool_options/lighting"
# OCIO configs: a small v2 config (two views, a matrix, a gamma, a range), and the ACES CG config when the shared
# data directory has it.
printf 'ocio_profile_version: 2\nroles:\n  scene_linear: lin\n  default: lin\ndisplays:\n  sRGB:\n    - !<View> {name: Gamma, colorspace: srgb}\n    - !<View> {name: Raw, colorspace: lin}\ncolorspaces:\n  - !<ColorSpace>\n    name: lin\n  - !<ColorSpace>\n    name: srgb\n    from_scene_reference: !<GroupTransform>\n      children:\n        - !<MatrixTransform> {matrix: [0.9, 0.1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}\n        - !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055, direction: inverse}\n        - !<RangeTransform> {min_in_value: 0, max_in_value: 1, min_out_value: 0, max_out_value: 1}\n' \
    > "$WORK/corpus_ocio_config/small"
CG="${PACIFICA_SHARED_DIR:-}/data/ocio/cg-config-v1.0.0_aces-v1.3_ocio-v2.1.ocio"
if [ -n "${PACIFICA_SHARED_DIR:-}" ] && [ -f "$CG" ]; then
    cp "$CG" "$WORK/corpus_ocio_config/aces_cg"
fi
# Images: the first byte picks the file type (0 EXR, 1 PNG, 2 Radiance HDR, 3 TIFF), the rest is the file: a
# two-frame 16 x 32 height map (half EXR), a grey PNG, an RGB HDR, a PIZ-compressed RGBA EXR.
if [ ! -s "$WORK/corpus_image/piz_exr" ]; then
    oiiotool --pattern noise:type=uniform:min=0:max=1 16x32 3 -d half -o "$WORK/seed.exr" &&
        { printf '\000'; cat "$WORK/seed.exr"; } > "$WORK/corpus_image/height_exr"
    oiiotool --pattern noise:type=uniform 16x16 1 -d uint8 -o "$WORK/seed.png" &&
        { printf '\001'; cat "$WORK/seed.png"; } > "$WORK/corpus_image/grey_png"
    oiiotool --pattern fill:top=0.1,0.2,0.3:bottom=2,3,4 8x4 3 -o "$WORK/seed.hdr" &&
        { printf '\002'; cat "$WORK/seed.hdr"; } > "$WORK/corpus_image/sky_hdr"
    oiiotool --pattern noise:type=uniform 16x16 4 -d half --compression piz -o "$WORK/seed.exr" &&
        { printf '\000'; cat "$WORK/seed.exr"; } > "$WORK/corpus_image/piz_exr"
fi
status=0
for t in $TARGETS; do
    echo "fuzz_$t: ${SECONDS_EACH} s"
    # fuzz_image: OpenImageIO's leaks on malformed files are suppressed by name (lsan-image.supp explains
    # each), which needs full stacks through the non-instrumented libraries (slow unwinding); readImage may
    # take 2 GiB for a declared 16384 x 8192 RGBA image (MAX_READ_SAMPLES), hence the larger RSS limit.
    # intercept_tls_get_addr=0: the leak check's tracer otherwise faults at exit now and then in a process
    # that did nothing wrong (the runtime's TLS interceptor, tests/sanitizers/run_sanitizers.sh explains).
    asan=detect_leaks=1:intercept_tls_get_addr=0 rss=2048
    [ "$t" = image ] && asan=detect_leaks=1:intercept_tls_get_addr=0:fast_unwind_on_malloc=0 rss=3072
    if ! ASAN_OPTIONS=$asan LSAN_OPTIONS="suppressions=$SRC/tests/fuzz/lsan-image.supp:print_suppressions=0" \
        "$WORK/fuzz_$t" "$WORK/corpus_$t" -max_total_time="$SECONDS_EACH" \
        -timeout=10 -rss_limit_mb=$rss -max_len=65536 -print_final_stats=1 -artifact_prefix="$WORK/crash_$t-" \
        > "$WORK/fuzz_$t.log" 2>&1; then
        echo "fuzz_$t FAILED:"; tail -40 "$WORK/fuzz_$t.log"; status=1
    fi
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$WORK/fuzz_$t.log" | sed "s/^/  fuzz_$t /"
done
[ $status -eq 0 ] && echo "$(echo $TARGETS | wc -w) passed, 0 failed" || echo "fuzzing found a problem: inputs are in $WORK/crash_*"
exit $status
