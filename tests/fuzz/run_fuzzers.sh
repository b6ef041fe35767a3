#!/bin/sh
# Builds the recorded-flight reader fuzzers with clang's libFuzzer (+ AddressSanitizer, UndefinedBehaviorSanitizer,
# LeakSanitizer) and runs each for SECONDS, starting from a seed corpus of real inputs (the first lines of the
# DCS recording, an IGC file, the demo flight CSV). Fails on any crash, leak, timeout (a hang: 10 s per input)
# or out-of-memory; prints the executions each made (libFuzzer's final stats).
#   tests/fuzz/run_fuzzers.sh SOURCE_DIR WORK_DIR SECONDS     (ctest runs it with 15 s; longer by hand)
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
$SRC/tools/src/FlightPath.cpp $SRC/engine/src/Pose.cpp"
for t in acmi igc csv; do
    if [ ! -x "$WORK/fuzz_$t" ] || [ -n "$(find "$SRC/engine/recording" "$SRC/tools/src/FlightPath.cpp" \
        "$SRC/tests/fuzz" -newer "$WORK/fuzz_$t" -type f 2>/dev/null | head -1)" ]; then
        echo "building fuzz_$t"
        # shellcheck disable=SC2086
        "$CXX" $FLAGS "$SRC/tests/fuzz/fuzz_$t.cpp" $LIB -lzip -lisal -o "$WORK/fuzz_$t"
    fi
done
# Seed corpora.
mkdir -p "$WORK/corpus_acmi" "$WORK/corpus_igc" "$WORK/corpus_csv"
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
status=0
for t in acmi igc csv; do
    echo "fuzz_$t: ${SECONDS_EACH} s"
    if ! ASAN_OPTIONS=detect_leaks=1 "$WORK/fuzz_$t" "$WORK/corpus_$t" -max_total_time="$SECONDS_EACH" \
        -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 -artifact_prefix="$WORK/crash_$t-" \
        > "$WORK/fuzz_$t.log" 2>&1; then
        echo "fuzz_$t FAILED:"; tail -40 "$WORK/fuzz_$t.log"; status=1
    fi
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$WORK/fuzz_$t.log" | sed "s/^/  fuzz_$t /"
done
[ $status -eq 0 ] && echo "3 passed, 0 failed" || echo "fuzzing found a problem: inputs are in $WORK/crash_*"
exit $status
