/* swap_timer.c: an LD_PRELOAD frame timer for a GLX program we cannot change (osgOcean's oceanExample,
 * tools/bench/osgocean_compare.sh). It wraps glXSwapBuffers: each swap first waits for the frame with
 * glFinish() -- the project's clock for llvmpipe, whose timer queries are wrong (docs/PERFORMANCE.md) -- then
 * takes CLOCK_MONOTONIC, so one frame's time is the span between two swaps: the program's own work and the
 * rendering. After SWAP_TIMER_WARMUP swaps (default 10) it records SWAP_TIMER_FRAMES frames (default 60),
 * writes them to SWAP_TIMER_OUT (one "ms" per line, then "median MS") and ends the process, since the
 * example loops until its window is closed. Works only for programs that call glXSwapBuffers through
 * the dynamic linker (osgViewer does; GLFW looks it up with dlsym in libGL and is not seen).
 * With SWAP_TIMER_SHOT=PATH it also keeps what the last timed frame drew: the back buffer, read after the
 * glFinish and before the swap, written as an 8-bit RGB PNG, and prints one line of statistics on stderr
 * ("swap_timer: shot WxH mean M top_mean T top_stddev S", luma 0-255; "top" is the image's top quarter,
 * the sky in osgOcean's example), so a caller can refuse a black or sky-less frame that only looks fast.
 * Build: cc -O2 -shared -fPIC swap_timer.c -o swap_timer.so -ldl -lz -lm */
#define _GNU_SOURCE
#include <GL/glx.h>
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

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

/* One PNG chunk: length, type, data, CRC-32 of type and data (PNG specification, 5.3 "Chunk layout"). */
static int put_chunk(FILE* f, const char* type, const unsigned char* data, unsigned long n) {
    unsigned char be[4] = {(unsigned char)(n >> 24), (unsigned char)(n >> 16), (unsigned char)(n >> 8),
                           (unsigned char)n};
    unsigned long crc = crc32(crc32(0L, Z_NULL, 0), (const Bytef*)type, 4);
    if (n)
        crc = crc32(crc, data, (uInt)n);
    unsigned char c[4] = {(unsigned char)(crc >> 24), (unsigned char)(crc >> 16), (unsigned char)(crc >> 8),
                          (unsigned char)crc};
    return fwrite(be, 1, 4, f) == 4 && fwrite(type, 1, 4, f) == 4 && (!n || fwrite(data, 1, n, f) == n) &&
           fwrite(c, 1, 4, f) == 4;
}

/* rgb: w*h*3 bytes as glReadPixels returns them, bottom row first; the PNG gets them top row first. Each row
 * gets filter type 0 (none); IDAT is one zlib stream. */
static int write_png(const char* path, const unsigned char* rgb, int w, int h) {
    unsigned long raw_n = (unsigned long)h * (3ul * (unsigned long)w + 1ul);
    unsigned char* raw = malloc(raw_n);
    uLongf z_n = compressBound(raw_n);
    unsigned char* z = malloc(z_n);
    int ok = raw && z;
    for (int y = 0; ok && y < h; ++y) {
        raw[(unsigned long)y * (3ul * (unsigned long)w + 1ul)] = 0;
        memcpy(raw + (unsigned long)y * (3ul * (unsigned long)w + 1ul) + 1,
               rgb + (size_t)(h - 1 - y) * 3u * (size_t)w, 3u * (size_t)w);
    }
    ok = ok && compress2(z, &z_n, raw, raw_n, 6) == Z_OK;
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.part", path);
    FILE* f = ok ? fopen(tmp, "wb") : NULL;
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char ihdr[13] = {(unsigned char)(w >> 24),
                              (unsigned char)(w >> 16),
                              (unsigned char)(w >> 8),
                              (unsigned char)w,
                              (unsigned char)(h >> 24),
                              (unsigned char)(h >> 16),
                              (unsigned char)(h >> 8),
                              (unsigned char)h,
                              8,
                              2,
                              0,
                              0,
                              0}; /* 8-bit RGB */
    ok = f && fwrite(sig, 1, 8, f) == 8 && put_chunk(f, "IHDR", ihdr, 13) && put_chunk(f, "IDAT", z, z_n) &&
         put_chunk(f, "IEND", NULL, 0);
    if (f)
        ok = (fclose(f) == 0) && ok;
    ok = ok && rename(tmp, path) == 0;
    if (!ok)
        remove(tmp);
    free(raw);
    free(z);
    return ok;
}

typedef void (*ReadPixelsFn)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void*);
typedef void (*PixelStoreFn)(GLenum, GLint);
typedef void (*ReadBufferFn)(GLenum);
typedef void (*QueryDrawableFn)(Display*, GLXDrawable, int, unsigned int*);

/* The back buffer of the current context as a PNG at SWAP_TIMER_SHOT, with its luma statistics (Rec. 709
 * weights on the stored 8-bit values) on stderr. */
static void take_shot(Display* dpy, GLXDrawable drawable, const char* path) {
    ReadPixelsFn read_pixels = (ReadPixelsFn)dlsym(RTLD_DEFAULT, "glReadPixels");
    PixelStoreFn pixel_store = (PixelStoreFn)dlsym(RTLD_DEFAULT, "glPixelStorei");
    ReadBufferFn read_buffer = (ReadBufferFn)dlsym(RTLD_DEFAULT, "glReadBuffer");
    QueryDrawableFn query_drawable = (QueryDrawableFn)dlsym(RTLD_DEFAULT, "glXQueryDrawable");
    if (!read_pixels || !pixel_store || !read_buffer || !query_drawable) {
        fprintf(stderr, "swap_timer: glReadPixels or glXQueryDrawable not found: no shot\n");
        _exit(2);
    }
    /* The window's size, not GL_VIEWPORT's: the example's last camera (its HUD) leaves a smaller viewport.
     * The default framebuffer is bound for reading, whatever render target the program used last. */
    typedef void (*BindFramebufferFn)(GLenum, GLuint);
    typedef void (*(*GetProcFn)(const GLubyte*))(void);
    GetProcFn get_proc = (GetProcFn)dlsym(RTLD_DEFAULT, "glXGetProcAddress");
    BindFramebufferFn bind_framebuffer =
        get_proc ? (BindFramebufferFn)get_proc((const GLubyte*)"glBindFramebuffer") : NULL;
    unsigned int dw = 0, dh = 0;
    query_drawable(dpy, drawable, GLX_WIDTH, &dw);
    query_drawable(dpy, drawable, GLX_HEIGHT, &dh);
    if (bind_framebuffer)
        bind_framebuffer(0x8CA8 /* GL_READ_FRAMEBUFFER */, 0);
    int w = (int)dw, h = (int)dh;
    unsigned char* rows = w > 0 && h > 0 ? malloc((size_t)w * (size_t)h * 3u) : NULL;
    if (!rows) {
        fprintf(stderr, "swap_timer: the window is %dx%d: no shot\n", w, h);
        _exit(2);
    }
    read_buffer(GL_BACK);
    pixel_store(GL_PACK_ALIGNMENT, 1);
    read_pixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rows);
    double sum = 0.0, top_sum = 0.0, top_sq = 0.0;
    long top_n = 0;
    for (int y = 0; y < h; ++y) { /* y counts from the top; GL's rows run bottom-up */
        const unsigned char* src = rows + (size_t)(h - 1 - y) * 3u * (size_t)w;
        for (int x = 0; x < w; ++x) {
            double l = 0.2126 * src[3 * x] + 0.7152 * src[3 * x + 1] + 0.0722 * src[3 * x + 2];
            sum += l;
            if (y < h / 4) {
                top_sum += l;
                top_sq += l * l;
                ++top_n;
            }
        }
    }
    double mean = sum / ((double)w * h), top_mean = top_n ? top_sum / top_n : 0.0;
    double top_var = top_n ? top_sq / top_n - top_mean * top_mean : 0.0;
    if (!write_png(path, rows, w, h)) {
        fprintf(stderr, "swap_timer: cannot write %s\n", path);
        _exit(2);
    }
    fprintf(stderr, "swap_timer: shot %dx%d mean %.2f top_mean %.2f top_stddev %.2f\n", w, h, mean, top_mean,
            sqrt(top_var > 0.0 ? top_var : 0.0));
    free(rows);
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
    if (seen > warmup + frames) {
        const char* shot = getenv("SWAP_TIMER_SHOT");
        if (shot && *shot)
            take_shot(dpy, drawable, shot);
        finish_run(ms, frames);
    }
    swap(dpy, drawable);
}
