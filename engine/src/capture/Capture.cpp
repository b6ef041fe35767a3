// Capture implementation: OpenImageIO for the file formats (or, built with PACIFICA_CAPTURE_OPENEXR, the
// OpenEXR library alone: engine/capture/OpenExr.h), Imath for float->half, xxHash for frame hashes.
// Every OIIO call's failure is checked and its geterror() text is carried into the CaptureError (an
// ImageOutput destroyed with an unread error would print it to stderr instead). Each write goes to
// ".<name>.tmp-<pid>-<n>" next to the final file and is renamed into place only after close() succeeded;
// rename within one directory is atomic on POSIX, so readers never see a partial image.
#include <engine/capture/Capture.h>

#include <engine/capture/OpenExr.h>

#include "ShortestText.h"

#include <Imath/half.h>
#include <xxhash.h>
#if !PACIFICA_CAPTURE_OPENEXR
#include <OpenImageIO/imageio.h>
#endif

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <system_error>

namespace pacifica::capture {

namespace {

namespace fs = std::filesystem;

// Removes the temp file unless the write was committed (renamed into place), whatever way we leave.
class TempFile {
public:
    explicit TempFile(const fs::path& finalPath) {
        static std::atomic<unsigned> counter{0};
        // ".<name>.tmp-<pid>-<n>": hidden, unique per process and call. Built with append() because
        // GCC 12 -O3 warns falsely (-Wrestrict, GCC bug 105329) on `"." + std::string`.
        std::string name(".");
        name.append(finalPath.filename().string())
            .append(".tmp-")
            .append(std::to_string(::getpid()))
            .append("-")
            .append(std::to_string(counter.fetch_add(1)));
        mPath = finalPath.parent_path() / name;
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    ~TempFile() {
        if (!mCommitted) {
            std::error_code ignored;
            fs::remove(mPath, ignored);
        }
    }

    const fs::path& path() const { return mPath; }
    void commit() { mCommitted = true; }

private:
    fs::path mPath;
    bool mCommitted = false;
};

void checkArguments(const fs::path& path, const char* function, int width, int height, int channels,
                    int minChannels, int maxChannels, const float* pixels) {
    if (width <= 0 || height <= 0) {
        throw CaptureError(path, std::string(function) + ": expected a positive size, got " +
                                     std::to_string(width) + "x" + std::to_string(height));
    }
    if (channels < minChannels || channels > maxChannels) {
        throw CaptureError(path, std::string(function) + ": expected " + std::to_string(minChannels) +
                                     " to " + std::to_string(maxChannels) + " channels, got " +
                                     std::to_string(channels));
    }
    if (pixels == nullptr) {
        throw CaptureError(path, std::string(function) + ": pixel pointer is null");
    }
}

// Renames the finished temp file onto `path` (both backends' last step).
void commitRename(TempFile& temp, const fs::path& path) {
    std::error_code ec;
    fs::rename(temp.path(), path, ec);
    if (ec) {
        throw CaptureError(path, "cannot rename " + temp.path().string() + " into place: " + ec.message());
    }
    temp.commit();
}

#if !PACIFICA_CAPTURE_OPENEXR
// Writes `data` (already in the spec's pixel format) through the named OIIO plugin to a temp file, then
// renames it onto `path`.
void writeAtomically(const fs::path& path, const char* formatName, const OIIO::ImageSpec& spec,
                     const void* data) {
    TempFile temp(path); // declared before `out`, so the writer is closed before the temp file is removed
    auto out = OIIO::ImageOutput::create(formatName);
    if (!out) {
        throw CaptureError(path,
                           std::string("cannot create the ") + formatName + " writer: " + OIIO::geterror());
    }
    if (!out->open(temp.path().string(), spec)) {
        throw CaptureError(path, "cannot open " + temp.path().string() + " for writing: " + out->geterror());
    }
    if (!out->write_image(spec.format, data)) {
        const std::string reason = out->geterror();
        out->close();
        out->geterror(); // drop any follow-up error so the destructor stays quiet
        throw CaptureError(path, "cannot write pixels: " + reason);
    }
    if (!out->close() || out->has_error()) {
        throw CaptureError(path, "cannot finish writing " + temp.path().string() + ": " + out->geterror());
    }
    out.reset();
    commitRename(temp, path);
}

#endif

} // namespace

uint64_t hashHalfPixels(const uint16_t* halfBits, size_t count) {
    return XXH64(halfBits, count * sizeof(uint16_t), 0);
}

std::optional<uint64_t> hashFileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        return std::nullopt;
    std::unique_ptr<XXH64_state_t, XXH_errorcode (*)(XXH64_state_t*)> state(XXH64_createState(),
                                                                            XXH64_freeState);
    if (!state || XXH64_reset(state.get(), 0) != XXH_OK)
        return std::nullopt;
    std::vector<char> block(1 << 20);
    while (in) {
        in.read(block.data(), static_cast<std::streamsize>(block.size()));
        if (in.gcount() > 0)
            XXH64_update(state.get(), block.data(), static_cast<size_t>(in.gcount()));
    }
    if (in.bad())
        return std::nullopt;
    return XXH64_digest(state.get());
}

std::vector<uint16_t> toHalf(const float* data, size_t count) {
    std::vector<uint16_t> bits(count);
    for (size_t i = 0; i < count; ++i) {
        bits[i] = Imath::half(data[i]).bits(); // Imath: round to nearest, ties to even
    }
    return bits;
}

uint64_t writeExrHalf(const std::filesystem::path& path, int width, int height, int channels,
                      const float* pixelsTopDown, const Metadata& metadata, Compression compression) {
    checkArguments(path, "writeExrHalf()", width, height, channels, 3, 4, pixelsTopDown);

    const size_t count =
        static_cast<size_t>(width) * static_cast<size_t>(height) * static_cast<size_t>(channels);
    // Convert once and hand the writer the half bits themselves, so the hash is of exactly what lands in the
    // file.
    const std::vector<uint16_t> halves = toHalf(pixelsTopDown, count);
#if PACIFICA_CAPTURE_OPENEXR
    TempFile temp(path);
    openexr::writeHalf(temp.path(), path, width, height, channels, halves.data(), metadata, compression);
    commitRename(temp, path);
#else
    // The default channel names for 3 and 4 channels are R,G,B(,A), with A as the alpha channel.
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::HALF);
    // ZIP (lossless zlib) at OpenEXR's default level 4, or at level 1 (Compression::Fast: 22 vs 35 ms and
    // 1.11x the bytes for a 640x360 RGBA frame on this project's machine, docs/PERFORMANCE.md).
    spec.attribute("compression", compression == Compression::Fast ? "zip:1" : "zip");
    for (const auto& [name, value] : metadata.strings) {
        spec.attribute("pacifica:" + name, value);
    }
    for (const auto& [name, value] : metadata.numbers) {
        spec.attribute("pacifica:" + name, OIIO::TypeDesc::DOUBLE, &value);
    }
    writeAtomically(path, "openexr", spec, halves.data());
#endif
    return hashHalfPixels(halves.data(), halves.size());
}

#if PACIFICA_CAPTURE_OPENEXR
Image readImage(const std::filesystem::path& path) {
    if (!openexr::isOpenExr(path)) {
        std::error_code ec;
        if (!fs::exists(path, ec))
            throw CaptureError(path, "cannot open image: no such file");
        if (!std::ifstream(path, std::ios::binary))
            throw CaptureError(path, std::string("cannot open image: ") + std::strerror(errno));
        throw CaptureError(path,
                           "cannot read this image: this build reads OpenEXR files only (configured with "
                           "PACIFICA_CAPTURE_OPENEXR=ON, without OpenImageIO)");
    }
    return openexr::read(path);
}
#else
Image readImage(const std::filesystem::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) {
        throw CaptureError(path, "cannot open image: " + OIIO::geterror());
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (!samplesWithinLimit(spec.width, spec.height, spec.nchannels))
        throw CaptureError(
            path, "the header declares " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                      " pixels of " + std::to_string(spec.nchannels) + " channels; at most " +
                      std::to_string(MAX_READ_SAMPLES) + " samples (16384 x 8192 RGBA) are read; refused");

    Image image;
    image.width = spec.width;
    image.height = spec.height;
    image.channels = spec.nchannels;
    const size_t rowSamples = static_cast<size_t>(spec.width) * static_cast<size_t>(spec.nchannels);
    const size_t samples = rowSamples * static_cast<size_t>(spec.height);
    auto fail = [&](const std::string& reason) {
        in->close();
        in->geterror();
        return CaptureError(path, "cannot read pixels: " + reason);
    };
    if (spec.tile_width > 0) { // tiled: the whole image at once
        image.pixels.resize(samples);
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
            throw fail(in->geterror());
    } else {
        // Scanlines, a band at a time, appended to reserved (not yet touched) memory: a file whose header
        // declares a large image but whose data ends early costs what was decoded, not the declared size.
        image.pixels.reserve(samples);
        const int band = static_cast<int>(std::clamp<size_t>((size_t(1) << 20) / rowSamples, 1, 256));
        std::vector<float> rows(rowSamples * static_cast<size_t>(band));
        for (int y = spec.y; y < spec.y + spec.height; y += band) {
            const int end = std::min(y + band, spec.y + spec.height);
            if (!in->read_scanlines(0, 0, y, end, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, rows.data()))
                throw fail(in->geterror());
            image.pixels.insert(image.pixels.end(), rows.begin(),
                                rows.begin() + static_cast<std::ptrdiff_t>(rowSamples * size_t(end - y)));
        }
    }

    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        std::string text;
        if (p.nvalues() == 1 && p.type() == OIIO::TypeDesc::DOUBLE) {
            text = shortestText(*static_cast<const double*>(p.data()));
        } else if (p.nvalues() == 1 && p.type() == OIIO::TypeDesc::FLOAT) {
            text = shortestText(*static_cast<const float*>(p.data()));
        } else {
            text = p.get_string(0); // 0: all elements of arrays and aggregates
        }
        image.attributes[p.name().string()] = std::move(text);
    }
    in->close();
    in->geterror();
    return image;
}
#endif

} // namespace pacifica::capture
