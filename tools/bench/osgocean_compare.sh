#!/bin/sh
# osgocean_compare.sh: Pacifica against osgOcean on this machine, in one session (the performance issue's
# comparison; docs/PERFORMANCE.md "osgOcean"). It builds osgOcean (kbale/osgocean) from its public source
# with Debian's OpenSceneGraph, runs its oceanExample (all effects on, FFT 64^2: the example's defaults)
# under a virtual X server on Mesa's llvmpipe, and times its frames with swap_timer.so -- glFinish before
# every glXSwapBuffers, CLOCK_MONOTONIC between swaps, the wall-clock-around-glFinish method of
# pacifica-bench-frame -- alternating runs with pacifica-bench-frame at the example's window size.
#
#   tools/bench/osgocean_compare.sh --source DIR [--out DIR] [--frames N] [--rounds N]
#
#   --source DIR  an osgOcean checkout or an extracted archive of it (its CMakeLists.txt and resources/;
#                 commit f235e99 is the one measured in docs/PERFORMANCE.md); or $OSGOCEAN_SOURCE; without
#                 either, `apt-get source osgocean` where apt has deb-src entries. Debian 12 packages
#                 OpenSceneGraph but not osgOcean: without a source the script prints the recipe, exits 3.
#   --out DIR     results (default out/osgocean-compare): osgocean-RUN.txt (ms per frame), osgocean-RUN.png
#                 and .look (the example's last timed frame), pacifica-RUN/, compare.md (medians per
#                 round and the ratios)
#   --frames N    timed frames per run (default 30, after 10 warm-up frames); --rounds N (default 3)
#   --bench EXE   a built pacifica-bench-frame (default: `./pacifica build`, then build/tools/...)
#   --skip-install  do not check or install the Debian packages (they are there, or the source needs none)
#
# The example's window is fixed at 1024x768 and its camera at (0, 0, 20) looking along +y with OSG's
# default 30 deg vertical field of view; Pacifica's bench views the sea from 20 m, 3 deg down, 60 deg, at
# the same size. The example runs in OUT/osgocean-run/, whose resources/ links the source's resources/ and
# demo/ as the example's install rules lay them out (the sky cube maps are only in demo/textures/), and
# Debian's OpenSceneGraph, which has no debug libraries, gets its release ones for the example's
# `debug ${OSG*_LIBRARY_DEBUG}` links. Each run keeps the example's last timed frame (osgocean-RUN.png)
# and its luma statistics (osgocean-RUN.look); a nearly black frame or one without a sky fails the run.
# Exit: 0 compared, 1 missing packages (not root), 2 bad arguments or a failed build or run, 3 no
# osgOcean source, 4 the example drew a wrong frame.
set -eu

ROOT=$(CDPATH= cd -- "$(dirname -- "$0")/../.." && pwd)
HERE="$ROOT/tools/bench"
SOURCE=${OSGOCEAN_SOURCE:-}
OUT="$ROOT/out/osgocean-compare"
FRAMES=30
ROUNDS=3
BENCH=""
INSTALL=1
PACKAGES="libopenscenegraph-dev libfftw3-dev zlib1g-dev cmake g++ xvfb xauth"
MIN_MEAN=10        # the shot's mean luma (0-255) below which the frame counts as black
MIN_SKY_STDDEV=2   # the top quarter's luma standard deviation below which it counts as one flat colour

say() { printf '%s\n' "osgocean_compare: $*" >&2; }
fail() { say "$1"; exit "${2:-2}"; }

count() { # a positive count of frames or rounds, else exit 2 naming the option
    case "$2" in '' | *[!0-9]*) fail "$1 needs a positive whole number, got '$2'" ;; esac
    [ "$2" -ge 1 ] || fail "$1 needs a positive whole number, got '$2'"
}

while [ $# -gt 0 ]; do
    case "$1" in
    --source) [ $# -ge 2 ] || fail "--source needs a directory"; SOURCE=$2; shift 2 ;;
    --out) [ $# -ge 2 ] || fail "--out needs a directory"; OUT=$2; shift 2 ;;
    --frames) [ $# -ge 2 ] || fail "--frames needs a number"; count --frames "$2"; FRAMES=$2; shift 2 ;;
    --rounds) [ $# -ge 2 ] || fail "--rounds needs a number"; count --rounds "$2"; ROUNDS=$2; shift 2 ;;
    --bench) [ $# -ge 2 ] && [ -x "$2" ] || fail "--bench needs an executable pacifica-bench-frame"; BENCH=$2; shift 2 ;;
    --skip-install) INSTALL=0; shift ;;
    -h | --help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) fail "unknown argument '$1' (see --help)" ;;
    esac
done

recipe() {
    cat >&2 <<'RECIPE'
The comparison recipe (docs/PERFORMANCE.md, "osgOcean"), for a machine with the source:
  1. git clone https://github.com/kbale/osgocean   (or any copy of it)
  2. sudo apt-get install libopenscenegraph-dev libfftw3-dev zlib1g-dev cmake g++ xvfb xauth
  3. tools/bench/osgocean_compare.sh --source osgocean
     It builds osgOcean with -DUSE_FFTW3F=ON (FFTSS is not packaged), builds swap_timer.so, and alternates
     `xvfb-run ... LIBGL_ALWAYS_SOFTWARE=1 LD_PRELOAD=swap_timer.so oceanExample` (run from a folder whose
     resources/ merges the source's resources/ and demo/) with
     `pacifica-bench-frame --size 1024x768 --only low,medium,high`.
The last run (docs/PERFORMANCE.md, "osgOcean"): osgOcean all effects 102.8-125.3 ms at 1024x768 on llvmpipe.
RECIPE
}

# 1. The source.
if [ -z "$SOURCE" ]; then
    if grep -Eqs '^deb-src|^Types:.*deb-src' /etc/apt/sources.list /etc/apt/sources.list.d/* &&
        command -v apt-get >/dev/null; then
        fetch=$(mktemp -d)
        if (cd "$fetch" && apt-get source -q osgocean >/dev/null 2>&1); then
            SOURCE=$(find "$fetch" -mindepth 1 -maxdepth 1 -type d | head -n 1)
        fi
    fi
fi
if [ -z "$SOURCE" ] || [ ! -f "$SOURCE/CMakeLists.txt" ] || [ ! -d "$SOURCE/resources" ]; then
    if [ -n "$SOURCE" ]; then
        say "osgOcean source not found: '$SOURCE' has no CMakeLists.txt and resources/"
    else
        say "osgOcean source not found: no --source, no \$OSGOCEAN_SOURCE, and apt has no osgocean source package"
    fi
    recipe
    exit 3
fi
SOURCE=$(CDPATH= cd -- "$SOURCE" && pwd)

# 2. Packages.
missing=""
[ "$INSTALL" -eq 1 ] || PACKAGES=""
for p in $PACKAGES; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
    [ "$(id -u)" -eq 0 ] || fail "missing Debian packages:$missing (sudo apt-get install -y$missing)" 1
    say "installing:$missing"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $missing
fi

# 3. Builds: osgOcean, the frame timer, Pacifica's bench.
mkdir -p "$OUT"
OUT=$(CDPATH= cd -- "$OUT" && pwd)
# osgOcean's CMake files link `debug ${OSGSHADOW_LIBRARY_DEBUG}` and the like, and Debian's OpenSceneGraph has
# no debug libraries: the first configure stops on those NOTFOUND variables. Each is given its release
# library (what the cache found as X_LIBRARY_RELEASE; a Release build never links the debug one anyway).
configure() {
    cmake -S "$SOURCE" -B "$OUT/osgocean-build" -DCMAKE_BUILD_TYPE=Release -DUSE_FFTSS=OFF -DUSE_FFTW3F=ON \
        -DENABLE_EXAMPLE=ON "$@" >>"$OUT/osgocean-build.log" 2>&1
}
: >"$OUT/osgocean-build.log"
if ! configure; then
    cache="$OUT/osgocean-build/CMakeCache.txt"
    [ -f "$cache" ] || fail "configuring osgOcean failed: see $OUT/osgocean-build.log"
    fixes=$(sed -n 's/^\([A-Z0-9_]*\)_LIBRARY_DEBUG:FILEPATH=.*-NOTFOUND$/\1/p' "$cache" | while read -r lib; do
        release=$(sed -n "s/^${lib}_LIBRARY_RELEASE:FILEPATH=//p" "$cache")
        case "$release" in '' | *-NOTFOUND) ;; *) printf ' -D%s_LIBRARY_DEBUG=%s' "$lib" "$release" ;; esac
    done)
    [ -n "$fixes" ] || fail "configuring osgOcean failed: see $OUT/osgocean-build.log"
    say "no debug OpenSceneGraph libraries: linking the release ones in their place"
    # shellcheck disable=SC2086 # one -D per word; the library paths hold no spaces (CMake's own cache lines)
    configure $fixes || fail "configuring osgOcean failed: see $OUT/osgocean-build.log"
fi
cmake --build "$OUT/osgocean-build" -j "$(nproc)" >>"$OUT/osgocean-build.log" 2>&1 ||
    fail "building osgOcean failed: see $OUT/osgocean-build.log"
EXAMPLE=$(find "$OUT/osgocean-build" -type f -name oceanExample -perm -u+x | head -n 1)
[ -n "$EXAMPLE" ] || fail "the build made no oceanExample: see $OUT/osgocean-build.log"
cc -O2 -shared -fPIC "$HERE/osgocean/swap_timer.c" -o "$OUT/swap_timer.so" -ldl -lz -lm ||
    fail "building swap_timer.so failed"
# The example reads everything relative to its working directory under resources/ (textures/sky_clear/,
# island/, shaders/), the layout its install rules make from the source's resources/ and demo/ folders; the
# sky cube maps live only in demo/textures/. The run folder merges both as links, leaving the source as it is.
RUN="$OUT/osgocean-run"
rm -rf "$RUN"
mkdir -p "$RUN/resources"
cp -rs "$SOURCE/resources/." "$RUN/resources/" || fail "cannot link $SOURCE/resources into $RUN"
if [ -d "$SOURCE/demo" ]; then
    cp -rs "$SOURCE/demo/." "$RUN/resources/" || fail "cannot link $SOURCE/demo into $RUN/resources"
fi
if [ -z "$BENCH" ]; then
    "$ROOT/pacifica" build >"$OUT/pacifica-build.log" 2>&1 || fail "building Pacifica failed: see $OUT/pacifica-build.log"
    BENCH="${PACIFICA_BUILD_DIR:-$ROOT/build}/tools/pacifica-bench-frame"
fi

# What the example drew in a run's last timed frame (swap_timer's shot line): a frame that is nearly black,
# or whose top quarter -- the sky, from the example's camera 20 m up looking at the horizon -- is one flat
# colour (no sky cube map: missing textures leave the clear colour), fails the run, so a frame that draws
# less cannot pass as a faster one.
look() {
    stats=$(sed -n 's/^swap_timer: shot //p' "$OUT/osgocean-$1.log")
    [ -n "$stats" ] && [ -s "$OUT/osgocean-$1.png" ] || fail "oceanExample's run $1 left no shot: see $OUT/osgocean-$1.log"
    verdict=$(echo "$stats" | awk -v min_mean="$MIN_MEAN" -v min_sky="$MIN_SKY_STDDEV" '{
        for (i = 1; i < NF; ++i) v[$i] = $(i + 1)
        if (v["mean"] < min_mean) printf "nearly black (mean luma %s < %s)", v["mean"], min_mean
        else if (v["top_stddev"] < min_sky) printf "no sky (top quarter luma stddev %s < %s)", v["top_stddev"], min_sky
    }')
    [ -z "$verdict" ] || fail "oceanExample's run $1 drew a wrong frame, $verdict: see $OUT/osgocean-$1.png" 4
    echo "$stats" >"$OUT/osgocean-$1.look"
}

# 4. Alternating runs in one session. An earlier report in OUT goes first: a failed run leaves none.
rm -f "$OUT/compare.md.part" "$OUT/compare.md"
{
    echo "# Pacifica vs osgOcean, $(date -u '+%Y-%m-%d %H:%M UTC')"
    echo
    echo "llvmpipe (LIBGL_ALWAYS_SOFTWARE=1), 1024x768, wall clock around glFinish, median of $FRAMES frames a run."
    echo
    echo "| round | osgOcean all effects ms | Pacifica low ms | medium ms | high ms | osgOcean / medium |"
    echo "|---|---|---|---|---|---|"
} >"$OUT/compare.md.part"
round=1
while [ "$round" -le "$ROUNDS" ]; do
    rm -f "$OUT/osgocean-$round.txt"
    rm -f "$OUT/osgocean-$round.png" "$OUT/osgocean-$round.look"
    (cd "$RUN" && xvfb-run -a -f "$OUT/Xauthority" -s "-screen 0 1280x1024x24" env LIBGL_ALWAYS_SOFTWARE=1 \
        LD_PRELOAD="$OUT/swap_timer.so" SWAP_TIMER_OUT="$OUT/osgocean-$round.txt" SWAP_TIMER_WARMUP=10 \
        SWAP_TIMER_FRAMES="$FRAMES" SWAP_TIMER_SHOT="$OUT/osgocean-$round.png" "$EXAMPLE" \
        >"$OUT/osgocean-$round.log" 2>&1) ||
        fail "oceanExample failed: see $OUT/osgocean-$round.log"
    [ -s "$OUT/osgocean-$round.txt" ] || fail "oceanExample ended before $FRAMES timed frames: see $OUT/osgocean-$round.log"
    look "$round"
    rm -rf "$OUT/pacifica-$round"
    "$BENCH" --size 1024x768 --frames "$FRAMES" --only low,medium,high --out "$OUT/pacifica-$round" \
        >"$OUT/pacifica-$round.log" 2>&1 || fail "pacifica-bench-frame failed: see $OUT/pacifica-$round.log"
    osg=$(sed -n 's/^median //p' "$OUT/osgocean-$round.txt")
    row() { awk -F, -v n="$1" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "ms_median") c = i } $1 == n { print $c }' "$OUT/pacifica-$round/frame.csv"; }
    low=$(row low) medium=$(row medium) high=$(row high)
    ratio=$(awk -v a="$osg" -v b="$medium" 'BEGIN { printf "%.2f", a / b }')
    echo "| $round | $osg | $low | $medium | $high | $ratio |" >>"$OUT/compare.md.part"
    round=$((round + 1))
done
mv "$OUT/compare.md.part" "$OUT/compare.md"
cat "$OUT/compare.md"
