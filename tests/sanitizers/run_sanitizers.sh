#!/bin/sh
# run_sanitizers.sh ROOT [address|thread|all]: the suite under the sanitizers (`./pacifica sanitize`, CI).
#   address  the whole suite built with AddressSanitizer + UndefinedBehaviorSanitizer, leaks on, in
#            build-asan/ (RelWithDebInfo)
#   thread   the threaded parts built with ThreadSanitizer, in build-tsan/: the replay's encoder thread,
#            the work queue, the sea queries' thread pool and the FFT tiles' jobs (ctest label `threads`)
#   all      both (the default)
# Every sanitizer writes its reports to files (log_path), not to the tests' stderr, so a report in any
# process -- a test, or a binary a Python test started, even one expected to fail -- is seen: the run
# fails if any report file exists, and prints them. Suppressions (each entry explained) are in this folder.
# Environment: PACIFICA_JOBS (default nproc).
set -eu
ROOT=$1
WHICH=${2:-all}
JOBS=${PACIFICA_JOBS:-$(nproc 2>/dev/null || echo 2)}
HERE="$ROOT/tests/sanitizers"

say() { printf '%s\n' "pacifica sanitize: $*" >&2; }

# RelWithDebInfo with -g1 instead of -g: line tables only, which is all a sanitizer's stack trace uses (file
# and line of every frame). With full -g, tools/src/Replay.cpp took 70 s to compile here instead of 58 s, and
# the CLI linked to 115 MB.
configure() { # configure DIR MODE
    if [ ! -f "$1/CMakeCache.txt" ]; then
        cmake -S "$ROOT" -B "$1" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPACIFICA_SANITIZE="$2" \
            "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG"
    fi
}

# check REPORTS_DIR CTEST_STATUS: fails on any report file, then on a failed test.
check() {
    found=0
    for f in "$1"/*; do
        [ -f "$f" ] || continue
        found=1
        say "report: $f"
        cat "$f" >&2
    done
    if [ "$found" -ne 0 ]; then
        say "FAILED: sanitizer reports above"
        return 1
    fi
    if [ "$2" -ne 0 ]; then
        say "FAILED: ctest exit $2"
        return 1
    fi
}

run_address() {
    dir="$ROOT/build-asan"
    configure "$dir" address
    cmake --build "$dir" -j "$JOBS"
    reports="$dir/sanitizer-reports"
    rm -rf "$reports"
    mkdir -p "$reports"
    # intercept_tls_get_addr=0: up to GCC 13 the runtime's __tls_get_addr interceptor takes a dynamic TLS
    # block whose address is 16 bytes past a page boundary for one with a glibc 2.19 header (glibc >= 2.25 has
    # none) and reads the two words before it as a range; LeakSanitizer's tracer then faults on that range at
    # exit ("Tracer caught signal 11", "LeakSanitizer has encountered a fatal error", exit 1) in a process that
    # did nothing wrong -- once in ~hundreds of exits, as malloc happens to place the block. Without the
    # interceptor the dynamic TLS blocks stay reachable through the DTV (a heap block the thread's static TLS
    # points to), so leak checking loses nothing.
    export ASAN_OPTIONS="log_path=$reports/asan:detect_leaks=1:halt_on_error=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1:intercept_tls_get_addr=0"
    export LSAN_OPTIONS="suppressions=$HERE/lsan.supp:print_suppressions=0"
    export UBSAN_OPTIONS="log_path=$reports/ubsan:print_stacktrace=1:halt_on_error=1"
    status=0
    # Label `fuzz` is left out: the fuzzers are clang ASan + UBSan builds of their own, already run by the
    # Release suite; here they would only be built and run a second time. Label `peer` too: it builds and
    # times osgOcean, an uninstrumented program, and what it runs of ours (pacifica-bench-frame through the
    # same script) runs here in e2e_osgocean_stand_in.
    rm -rf "$dir/test-shader-cache" # the tests' shader cache (tests/CMakeLists.txt) starts empty
    ctest --test-dir "$dir" --output-on-failure -j "$JOBS" -LE "fuzz|peer" || status=$?
    unset ASAN_OPTIONS LSAN_OPTIONS UBSAN_OPTIONS
    check "$reports" "$status"
}

run_thread() {
    dir="$ROOT/build-tsan"
    configure "$dir" thread
    cmake --build "$dir" -j "$JOBS" --target pacifica test_worker_queue test_sea_query test_fft_sampled
    reports="$dir/sanitizer-reports"
    rm -rf "$reports"
    mkdir -p "$reports"
    # llvmpipe's own threads are not instrumented: one rasterizer thread keeps them out of the picture.
    export TSAN_OPTIONS="log_path=$reports/tsan:halt_on_error=1:second_deadlock_stack=1:suppressions=$HERE/tsan.supp"
    export LP_NUM_THREADS=0
    status=0
    ctest --test-dir "$dir" --output-on-failure -j "$JOBS" -L threads || status=$?
    unset TSAN_OPTIONS LP_NUM_THREADS
    check "$reports" "$status"
}

case "$WHICH" in
address) run_address ;;
thread) run_thread ;;
all)
    run_address
    run_thread
    ;;
*)
    say "unknown mode '$WHICH' (address, thread or all)"
    exit 2
    ;;
esac
say "passed ($WHICH)"
