/* swap_timer.c: an LD_PRELOAD frame timer for a GLX program we cannot change (osgOcean's oceanExample,
 * tools/bench/osgocean_compare.sh). It wraps glXSwapBuffers: each swap first waits for the frame with
 * glFinish() -- the project's clock for llvmpipe, whose timer queries are wrong (docs/PERFORMANCE.md) -- then
 * takes CLOCK_MONOTONIC, so one frame's time is the span between two swaps: the program's own work and the
 * rendering. After SWAP_TIMER_WARMUP swaps (default 10) it records SWAP_TIMER_FRAMES frames (default 60),
 * writes them to SWAP_TIMER_OUT (one "ms" per line, then "median MS") and ends the process, since the
 * example loops until its window is closed. Works only for programs that call glXSwapBuffers through
 * the dynamic linker (osgViewer does; GLFW looks it up with dlsym in libGL and is not seen).
 * Build: cc -O2 -shared -fPIC swap_timer.c -o swap_timer.so -ldl */
#define _GNU_SOURCE
#include <GL/glx.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

typedef void (*SwapFn)(Display*, GLXDrawable);
typedef void (*FinishFn)(void);

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static long env_long(const char* name, long fallback) {
    const char* v = getenv(name);
    if (!v || !*v)
        return fallback;
    char* end = NULL;
    long x = strtol(v, &end, 10);
    if (*end != '\0' || x < 0 || x > 1000000) {
        fprintf(stderr, "swap_timer: %s=%s is not a count of frames\n", name, v);
        _exit(2);
    }
    return x;
}

static int compare_double(const void* a, const void* b) {
    double x = *(const double*)a, y = *(const double*)b;
    return (x > y) - (x < y);
}

static void finish_run(const double* ms, long n) {
    const char* path = getenv("SWAP_TIMER_OUT");
    double* sorted = malloc(sizeof(double) * (size_t)n);
    for (long i = 0; i < n; ++i)
        sorted[i] = ms[i];
    qsort(sorted, (size_t)n, sizeof(double), compare_double);
    double median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    /* Written to a temporary name and renamed: no half-written result. */
    char tmp[4096];
    FILE* out = stdout;
    if (path && *path) {
        snprintf(tmp, sizeof tmp, "%s.part", path);
        out = fopen(tmp, "w");
        if (!out) {
            fprintf(stderr, "swap_timer: cannot write %s\n", tmp);
            _exit(2);
        }
    }
    for (long i = 0; i < n; ++i)
        fprintf(out, "%.3f\n", ms[i]);
    fprintf(out, "median %.3f\n", median);
    if (out != stdout) {
        if (fclose(out) != 0 || rename(tmp, path) != 0) {
            fprintf(stderr, "swap_timer: cannot write %s\n", path);
            _exit(2);
        }
    }
    fprintf(stderr, "swap_timer: %ld frames, median %.3f ms\n", n, median);
    free(sorted);
    _exit(0);
}

void glXSwapBuffers(Display* dpy, GLXDrawable drawable) {
    static SwapFn swap;
    static FinishFn finish;
    static long warmup = -1, frames, seen;
    static double last, *ms;
    if (!swap) {
        swap = (SwapFn)dlsym(RTLD_NEXT, "glXSwapBuffers");
        finish = (FinishFn)dlsym(RTLD_NEXT, "glFinish");
        if (!swap || !finish) {
            fprintf(stderr, "swap_timer: glXSwapBuffers/glFinish not found behind the preload\n");
            _exit(2);
        }
        warmup = env_long("SWAP_TIMER_WARMUP", 10);
        frames = env_long("SWAP_TIMER_FRAMES", 60);
        if (frames < 1) {
            fprintf(stderr, "swap_timer: SWAP_TIMER_FRAMES must be at least 1\n");
            _exit(2);
        }
        ms = calloc((size_t)frames, sizeof(double));
    }
    finish();
    double t = now_ms();
    if (seen > warmup) /* seen == warmup starts the first recorded span */
        ms[seen - warmup - 1] = t - last;
    last = t;
    ++seen;
    if (seen > warmup + frames)
        finish_run(ms, frames);
    swap(dpy, drawable);
}
