// OpenExr implementation (OpenExr.h): Imf::OutputFile / Imf::InputFile with interleaved half or float
// slices. OpenEXR reports failures by throwing Iex exceptions (std::exception); each is caught here and
// carried into a CaptureError naming the file.
#include <engine/capture/OpenExr.h>

#include "ShortestText.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

namespace pacifica::capture::openexr {

namespace {

namespace fs = std::filesystem;

constexpr std::array<const char*, 4> RGBA = {"R", "G", "B", "A"};

// OpenImageIO's names for OpenEXR's compression methods, so either backend reports the same attribute.
std::string compressionName(Imf::Compression c) {
    switch (c) {
    case Imf::NO_COMPRESSION:
        return "none";
    case Imf::RLE_COMPRESSION:
        return "rle";
    case Imf::ZIPS_COMPRESSION:
        return "zips";
    case Imf::ZIP_COMPRESSION:
        return "zip";
    case Imf::PIZ_COMPRESSION:
        return "piz";
    case Imf::PXR24_COMPRESSION:
        return "pxr24";
    case Imf::B44_COMPRESSION:
        return "b44";
    case Imf::B44A_COMPRESSION:
        return "b44a";
    case Imf::DWAA_COMPRESSION:
        return "dwaa";
    case Imf::DWAB_COMPRESSION:
        return "dwab";
    default:
        return "unknown";
    }
}

// The channels to read, in the order readImage() returns them (OpenExr.h).
std::vector<std::string> channelOrder(const Imf::ChannelList& list) {
    std::vector<std::string> names;
    for (auto it = list.begin(); it != list.end(); ++it)
        names.emplace_back(it.name());
    const bool rgb = list.findChannel("R") && list.findChannel("G") && list.findChannel("B");
    if (!rgb)
        return names;
    std::vector<std::string> ordered;
    for (const char* c : RGBA)
        if (list.findChannel(c))
            ordered.emplace_back(c);
    for (const std::string& n : names)
        if (std::find(ordered.begin(), ordered.end(), n) == ordered.end())
            ordered.push_back(n);
    return ordered;
}

std::map<std::string, std::string> attributeTexts(const Imf::Header& header) {
    std::map<std::string, std::string> out;
    for (auto it = header.begin(); it != header.end(); ++it) {
        const Imf::Attribute& a = it.attribute();
        if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a))
            out[it.name()] = s->value();
        else if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&a))
            out[it.name()] = shortestText(d->value());
        else if (const auto* f = dynamic_cast<const Imf::FloatAttribute*>(&a))
            out[it.name()] = shortestText(f->value());
        else if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&a))
            out[it.name()] = shortestText(i->value());
    }
    out["compression"] = compressionName(header.compression());
    return out;
}

} // namespace

void writeHalf(const fs::path& file, const fs::path& reportAs, int width, int height, int channels,
               const uint16_t* halfBitsTopDown, const Metadata& metadata, Compression compression) {
    try {
        Imf::Header header(width, height);
        header.compression() = Imf::ZIP_COMPRESSION;
        // zlib level 4 (OpenEXR's default, which OpenImageIO's "zip" keeps) or 1 ("zip:1"), regardless of
        // the process-wide default (Imf::setDefaultZipCompressionLevel).
        header.zipCompressionLevel() = compression == Compression::Fast ? 1 : 4;
        for (int c = 0; c < channels; ++c)
            header.channels().insert(RGBA[static_cast<size_t>(c)], Imf::Channel(Imf::HALF));
        for (const auto& [name, value] : metadata.strings)
            header.insert("pacifica:" + name, Imf::StringAttribute(value));
        for (const auto& [name, value] : metadata.numbers)
            header.insert("pacifica:" + name, Imf::DoubleAttribute(value));

        const size_t pixel = sizeof(uint16_t) * static_cast<size_t>(channels);
        const size_t row = pixel * static_cast<size_t>(width);
        Imf::FrameBuffer frame;
        // OpenEXR slices take a non-const base pointer but only read through it when writing.
        char* base = reinterpret_cast<char*>(const_cast<uint16_t*>(halfBitsTopDown));
        for (int c = 0; c < channels; ++c)
            frame.insert(RGBA[static_cast<size_t>(c)],
                         Imf::Slice(Imf::HALF, base + sizeof(uint16_t) * static_cast<size_t>(c), pixel, row));
        // The stream is ours: OutputFile's destructor writes the line-offset table and swallows any error
        // doing so, so the stream's state after it is the only word on whether the file is whole.
        std::ofstream os(file, std::ios::binary | std::ios::trunc);
        if (!os)
            throw CaptureError(reportAs, "cannot open " + file.string() + " for writing");
        {
            Imf::StdOFStream stream(os, file.c_str());
            Imf::OutputFile out(stream, header);
            out.setFrameBuffer(frame);
            out.writePixels(height);
        }
        os.close();
        if (!os)
            throw CaptureError(reportAs, "cannot finish writing " + file.string() + " (disk full?)");
    } catch (const CaptureError&) {
        throw;
    } catch (const std::exception& e) {
        throw CaptureError(reportAs, std::string("cannot write the OpenEXR file: ") + e.what());
    }
}

bool isOpenExr(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::array<unsigned char, 4> magic{};
    in.read(reinterpret_cast<char*>(magic.data()), magic.size());
    return in.gcount() == 4 && magic == std::array<unsigned char, 4>{0x76, 0x2f, 0x31, 0x01};
}

Image read(const fs::path& file) {
    try {
        Imf::InputFile in(file.c_str());
        const Imath::Box2i window = in.header().dataWindow();
        const int64_t width = int64_t(window.max.x) - window.min.x + 1;
        const int64_t height = int64_t(window.max.y) - window.min.y + 1;
        const std::vector<std::string> names = channelOrder(in.header().channels());
        const auto channels = static_cast<int64_t>(names.size());
        if (!samplesWithinLimit(width, height, channels))
            throw CaptureError(file, "the header declares " + std::to_string(width) + " x " +
                                         std::to_string(height) + " pixels of " + std::to_string(channels) +
                                         " channels; at most " + std::to_string(MAX_READ_SAMPLES) +
                                         " samples (16384 x 8192 RGBA) are read; refused");
        Image image;
        image.width = static_cast<int>(width);
        image.height = static_cast<int>(height);
        image.channels = static_cast<int>(channels);
        image.attributes = attributeTexts(in.header());

        // A band of rows at a time, appended to reserved memory: a file that ends early costs what was
        // decoded.
        const size_t rowSamples = static_cast<size_t>(width * channels);
        image.pixels.reserve(rowSamples * static_cast<size_t>(height));
        const int band = static_cast<int>(std::clamp<size_t>((size_t(1) << 20) / rowSamples, 1, 256));
        std::vector<float> rows(rowSamples * static_cast<size_t>(band));
        for (int y = window.min.y; y <= window.max.y; y += band) {
            const int end = std::min(y + band - 1, window.max.y);
            // Slice::Make maps pixel (window.min.x, y) of this band onto rows[0].
            const size_t pixel = sizeof(float) * static_cast<size_t>(channels);
            Imf::FrameBuffer frame;
            for (size_t c = 0; c < names.size(); ++c)
                frame.insert(names[c],
                             Imf::Slice::Make(Imf::FLOAT, rows.data() + c, Imath::V2i(window.min.x, y), width,
                                              band, pixel, pixel * static_cast<size_t>(width)));
            in.setFrameBuffer(frame);
            in.readPixels(y, end);
            image.pixels.insert(image.pixels.end(), rows.begin(),
                                rows.begin() + static_cast<std::ptrdiff_t>(rowSamples * size_t(end - y + 1)));
        }
        return image;
    } catch (const CaptureError&) {
        throw;
    } catch (const std::exception& e) {
        throw CaptureError(file, std::string("cannot read the OpenEXR file: ") + e.what());
    }
}

} // namespace pacifica::capture::openexr
