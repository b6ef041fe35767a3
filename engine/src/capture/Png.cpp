// Png: PNG files through libpng (the PNG reference library), encoded in memory and written with
// writeFileAtomically(), so a file appears whole or not at all. libpng reports errors by longjmp: only plain
// data lives between its setjmp and the calls that may jump.
#include <engine/capture/Png.h>

#include <engine/AtomicFile.h>

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace pacifica::capture {

namespace {

void checkArguments(const std::filesystem::path& path, const char* function, int width, int height,
                    int channels, const float* pixels) {
    if (width <= 0 || height <= 0)
        throw CaptureError(path, std::string(function) + ": expected a positive size, got " +
                                     std::to_string(width) + "x" + std::to_string(height));
    if (channels < 1 || channels > 4)
        throw CaptureError(path, std::string(function) + ": expected 1 to 4 channels, got " +
                                     std::to_string(channels));
    if (pixels == nullptr)
        throw CaptureError(path, std::string(function) + ": pixel pointer is null");
}

/// Code values in [0, 1] (clamped, NaN -> 0) quantised as round(v * max) into T, big-endian as PNG stores
/// 16-bit samples.
template <typename T>
std::vector<T> quantise(const float* values, size_t count) {
    constexpr float MAX = static_cast<float>(std::numeric_limits<T>::max());
    std::vector<T> out(count);
    for (size_t i = 0; i < count; ++i) {
        const float v = values[i];
        const float clamped = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
        const auto q = static_cast<T>(std::lround(clamped * MAX));
        if constexpr (sizeof(T) == 2)
            out[i] = static_cast<T>((q >> 8) | (q << 8));
        else
            out[i] = q;
    }
    return out;
}

void appendBytes(png_structp png, png_bytep data, png_size_t length) {
    static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), length);
}

void noFlush(png_structp) {}

struct Encoding {
    int width = 0, height = 0, channels = 0, bitDepth = 8;
    const unsigned char* samples = nullptr; // rows top-down, big-endian 16-bit samples
    bool srgb = false;
    int zlibLevel = 6;
};

/// The PNG file's bytes into `out`; false (and libpng's message in `why`) on failure.
bool encode(const Encoding& e, std::string& out, std::string& why) {
    png_structp png = png_create_write_struct(
        PNG_LIBPNG_VER_STRING, &why,
        [](png_structp p, png_const_charp message) {
            *static_cast<std::string*>(png_get_error_ptr(p)) = message;
            png_longjmp(p, 1);
        },
        nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        why = "libpng could not allocate its writer";
        return false;
    }
    const size_t rowBytes = static_cast<size_t>(e.width) * e.channels * (e.bitDepth / 8);
    std::vector<png_bytep> rows(static_cast<size_t>(e.height));
    for (size_t y = 0; y < rows.size(); ++y)
        rows[y] = const_cast<png_bytep>(e.samples + y * rowBytes);
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    static const int COLOUR[5] = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                  PNG_COLOR_TYPE_RGB_ALPHA};
    png_set_write_fn(png, &out, appendBytes, noFlush);
    png_set_compression_level(png, e.zlibLevel);
    png_set_IHDR(png, info, static_cast<png_uint_32>(e.width), static_cast<png_uint_32>(e.height), e.bitDepth,
                 COLOUR[e.channels], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (e.srgb)
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    png_write_image(png, rows.data());
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return true;
}

void writePng(const std::filesystem::path& path, const Encoding& e) {
    std::string bytes, why;
    if (!encode(e, bytes, why))
        throw CaptureError(path, "cannot encode PNG: " + why);
    try {
        writeFileAtomically(path, bytes);
    } catch (const std::exception& ex) {
        throw CaptureError(path, ex.what());
    }
}

size_t sampleCount(int width, int height, int channels) {
    return static_cast<size_t>(width) * static_cast<size_t>(height) * static_cast<size_t>(channels);
}

} // namespace

CaptureError::CaptureError(const std::filesystem::path& file, const std::string& message)
    : std::runtime_error(file.string() + ": " + message), mFile(file) {}

void writePng8(const std::filesystem::path& path, int width, int height, int channels,
               const float* displayTopDown, Compression compression) {
    checkArguments(path, "writePng8()", width, height, channels, displayTopDown);
    const std::vector<uint8_t> bytes =
        quantise<uint8_t>(displayTopDown, sampleCount(width, height, channels));
    // zlib level 6 (its default) or 1 (Compression::Fast).
    writePng(path,
             {width, height, channels, 8, bytes.data(), true, compression == Compression::Fast ? 1 : 6});
}

void writePng16(const std::filesystem::path& path, int width, int height, int channels,
                const float* codeTopDown) {
    checkArguments(path, "writePng16()", width, height, channels, codeTopDown);
    const std::vector<uint16_t> values =
        quantise<uint16_t>(codeTopDown, sampleCount(width, height, channels));
    writePng(path,
             {width, height, channels, 16, reinterpret_cast<const unsigned char*>(values.data()), false, 6});
}

} // namespace pacifica::capture
