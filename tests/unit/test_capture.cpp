// Unit tests for pacifica::capture: half-float EXR round trips with metadata, the frame hash (what it covers
// and that it moves when one pixel does), float->half rounding, 8-bit PNG quantisation and clamping, atomic
// writes (no temp files left behind, nothing written on failure) and error messages that name the file; the
// OpenEXR-only backend (engine/capture/OpenExr.h) and the build's readImage()/writeExrHalf() read each
// other's files with the same pixels, attributes and compression.
#include <engine/capture/Capture.h>
#include <engine/capture/OpenExr.h>

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using pacifica::capture::CaptureError;
using pacifica::capture::Image;
using pacifica::capture::Metadata;

// A fresh directory per test, removed afterwards.
class CaptureTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::random_device rd;
        mDir = fs::temp_directory_path() /
               ("pacifica-test-capture-" + std::to_string(::getpid()) + "-" + std::to_string(rd()));
        fs::create_directories(mDir);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(mDir, ignored);
    }

    // Names in the directory that look like leftover temp files.
    std::vector<std::string> tempFiles() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(mDir)) {
            const std::string name = entry.path().filename().string();
            if (name.find(".tmp") != std::string::npos) {
                names.push_back(name);
            }
        }
        return names;
    }

    fs::path mDir;
};

// A 5x3 RGBA test pattern with values across the half range: small, fractional, large, negative.
std::vector<float> testPattern(int width, int height, int channels) {
    std::vector<float> px(static_cast<size_t>(width * height * channels));
    for (size_t i = 0; i < px.size(); ++i) {
        const float t = static_cast<float>(i);
        px[i] = (i % 3 == 0) ? 0.001f * t + 0.1f : (i % 3 == 1) ? 37.3f * t - 100.0f : 1.0f / (t + 1.0f);
    }
    return px;
}

TEST(CaptureHalf, RoundsToNearestEven) {
    const float values[] = {1.0f,
                            1.0f + 0x1p-11f,        // halfway between 1 and 1+2^-10: ties to even (down)
                            1.0f + 3.0f * 0x1p-11f, // halfway between 1+2^-10 and 1+2^-9: ties to even (up)
                            1.0f + 0x1p-11f + 0x1p-20f, // just above halfway: up
                            -2.0f,
                            65504.0f, // largest finite half
                            65520.0f, // rounds to infinity
                            0.0f};
    const std::vector<uint16_t> h = pacifica::capture::toHalf(values, std::size(values));
    EXPECT_EQ(h[0], 0x3C00);
    EXPECT_EQ(h[1], 0x3C00);
    EXPECT_EQ(h[2], 0x3C02);
    EXPECT_EQ(h[3], 0x3C01);
    EXPECT_EQ(h[4], 0xC000);
    EXPECT_EQ(h[5], 0x7BFF);
    EXPECT_EQ(h[6], 0x7C00);
    EXPECT_EQ(h[7], 0x0000);

    const float nan = std::numeric_limits<float>::quiet_NaN();
    const uint16_t nanBits = pacifica::capture::toHalf(&nan, 1)[0];
    EXPECT_EQ(nanBits & 0x7C00, 0x7C00); // exponent all ones...
    EXPECT_NE(nanBits & 0x03FF, 0);      // ...and a non-zero mantissa: still NaN
}

TEST(CaptureHash, IsXxh64SeedZeroOverTheRawBits) {
    // Reference value of XXH64 for empty input with seed 0 (xxHash's published test vector).
    EXPECT_EQ(pacifica::capture::hashHalfPixels(nullptr, 0), 0xEF46DB3751D8E999ull);
    const uint16_t a[] = {0x3C00, 0x0000};
    const uint16_t b[] = {0x0000, 0x3C00};
    EXPECT_NE(pacifica::capture::hashHalfPixels(a, 2), pacifica::capture::hashHalfPixels(b, 2));
    EXPECT_NE(pacifica::capture::hashHalfPixels(a, 2), pacifica::capture::hashHalfPixels(a, 1));
}

TEST_F(CaptureTest, ExrRoundTripKeepsHalfValuesAndMetadata) {
    const int w = 5, h = 3, c = 4;
    const std::vector<float> px = testPattern(w, h, c);
    Metadata meta;
    meta.strings.push_back({"flight", "demo_flight.csv"});
    meta.numbers.push_back({"time_s", 12.5});
    meta.numbers.push_back({"pi", 3.141592653589793});

    const fs::path file = mDir / "frame.exr";
    const uint64_t hash = pacifica::capture::writeExrHalf(file, w, h, c, px.data(), meta);
    ASSERT_TRUE(fs::exists(file));
    EXPECT_TRUE(tempFiles().empty()) << tempFiles().front();

    const Image img = pacifica::capture::readImage(file);
    ASSERT_EQ(img.width, w);
    ASSERT_EQ(img.height, h);
    ASSERT_EQ(img.channels, c);
    ASSERT_EQ(img.pixels.size(), px.size());
    // Half has an 11-bit significand: relative rounding error <= 2^-11 ~ 4.9e-4, so 1e-3 is a safe bound.
    for (size_t i = 0; i < px.size(); ++i) {
        EXPECT_NEAR(img.pixels[i], px[i], 1e-3 * std::abs(px[i])) << "at " << i;
    }
    // And exactly the half values written: re-converting the read-back floats gives the same bits.
    EXPECT_EQ(pacifica::capture::toHalf(img.pixels.data(), img.pixels.size()),
              pacifica::capture::toHalf(px.data(), px.size()));
    // Top-down order: the first pixel read is the first pixel written.
    EXPECT_NEAR(img.pixels[0], px[0], 1e-3 * std::abs(px[0]));

    ASSERT_TRUE(img.attributes.count("pacifica:flight"));
    EXPECT_EQ(img.attributes.at("pacifica:flight"), "demo_flight.csv");
    ASSERT_TRUE(img.attributes.count("pacifica:time_s"));
    EXPECT_EQ(std::stod(img.attributes.at("pacifica:time_s")), 12.5);
    ASSERT_TRUE(img.attributes.count("pacifica:pi"));
    EXPECT_EQ(std::stod(img.attributes.at("pacifica:pi")), 3.141592653589793); // stored as double
    ASSERT_TRUE(img.attributes.count("compression"));
    EXPECT_EQ(img.attributes.at("compression"), "zip");

    // The hash is of exactly the half data written.
    const std::vector<uint16_t> halves = pacifica::capture::toHalf(px.data(), px.size());
    EXPECT_EQ(hash, pacifica::capture::hashHalfPixels(halves.data(), halves.size()));
}

TEST_F(CaptureTest, ExrHashIsStableAndChangesWithOnePixel) {
    const int w = 4, h = 4, c = 3;
    std::vector<float> px = testPattern(w, h, c);
    const uint64_t first = pacifica::capture::writeExrHalf(mDir / "a.exr", w, h, c, px.data(), {});
    const uint64_t again =
        pacifica::capture::writeExrHalf(mDir / "a.exr", w, h, c, px.data(), {}); // overwrite
    EXPECT_EQ(first, again);

    px[static_cast<size_t>(2 * w * c + 1 * c + 1)] += 1.0f; // one channel of pixel (1, 2)
    const uint64_t changed = pacifica::capture::writeExrHalf(mDir / "b.exr", w, h, c, px.data(), {});
    EXPECT_NE(first, changed);

    const Image img = pacifica::capture::readImage(mDir / "b.exr");
    EXPECT_EQ(img.channels, 3);
    EXPECT_TRUE(tempFiles().empty());
}

TEST_F(CaptureTest, FastCompressionIsLosslessAndOnlyLessCompressed) {
    // A 256x128 smooth image with fine detail (as a rendered sea): Compression::Fast (zlib level 1) must give
    // exactly the pixels of Small (level 6), as ZIP, in more bytes (it trades size for encoding time).
    const int w = 256, h = 128;
    std::vector<float> px(static_cast<size_t>(w * h * 4));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c)
                px[(static_cast<size_t>(y) * w + x) * 4 + c] =
                    c == 3 ? 1.0f
                           : 0.4f +
                                 0.3f * std::sin(0.05f * float(x) + 0.7f * float(c)) *
                                     std::cos(0.08f * float(y)) +
                                 0.02f * std::sin(1.7f * float(x * y % 97));
    using pacifica::capture::Compression;
    const uint64_t small = pacifica::capture::writeExrHalf(mDir / "small.exr", w, h, 4, px.data(), {});
    const uint64_t fast =
        pacifica::capture::writeExrHalf(mDir / "fast.exr", w, h, 4, px.data(), {}, Compression::Fast);
    EXPECT_EQ(small, fast);
    const Image a = pacifica::capture::readImage(mDir / "small.exr"),
                b = pacifica::capture::readImage(mDir / "fast.exr");
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(b.attributes.at("compression"), "zip");
    EXPECT_GT(fs::file_size(mDir / "fast.exr"), fs::file_size(mDir / "small.exr"));

    pacifica::capture::writePng8(mDir / "small.png", w, h, 4, px.data());
    pacifica::capture::writePng8(mDir / "fast.png", w, h, 4, px.data(), Compression::Fast);
    EXPECT_EQ(pacifica::capture::readImage(mDir / "small.png").pixels,
              pacifica::capture::readImage(mDir / "fast.png").pixels);
    EXPECT_GT(fs::file_size(mDir / "fast.png"), fs::file_size(mDir / "small.png"));
    EXPECT_TRUE(tempFiles().empty());
}

TEST_F(CaptureTest, PngClampsAndQuantises) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    // 2x2 RGB, row 0 then row 1.
    const std::vector<float> px = {0.5f, -0.25f, 2.0f, nan,  1.0f, 0.0f, //
                                   0.2f, 0.8f,   1.0f, 0.0f, 0.0f, 0.0f};
    const fs::path file = mDir / "frame.png";
    pacifica::capture::writePng8(file, 2, 2, 3, px.data());
    EXPECT_TRUE(tempFiles().empty());

    const Image img = pacifica::capture::readImage(file);
    ASSERT_EQ(img.width, 2);
    ASSERT_EQ(img.height, 2);
    ASSERT_EQ(img.channels, 3);
    const float step = 1.0f / 255.0f;
    EXPECT_NEAR(img.pixels[0], 128.0f / 255.0f, step); // round(0.5 * 255) = round(127.5) = 128
    EXPECT_EQ(img.pixels[1], 0.0f);                    // negative -> 0
    EXPECT_EQ(img.pixels[2], 1.0f);                    // 2.0 -> 1
    EXPECT_EQ(img.pixels[3], 0.0f);                    // NaN -> 0
    EXPECT_EQ(img.pixels[4], 1.0f);
    EXPECT_NEAR(img.pixels[6], 51.0f / 255.0f, 1e-6f); // 0.2 * 255 = 51 exactly representable as a code
    EXPECT_NEAR(img.pixels[7], 204.0f / 255.0f, 1e-6f);
    // Exact code check: 0.5 must land on 128, not 127.
    EXPECT_EQ(std::lround(img.pixels[0] * 255.0f), 128);
    ASSERT_TRUE(img.attributes.count("oiio:ColorSpace"));
    EXPECT_EQ(img.attributes.at("oiio:ColorSpace"), "sRGB");
}

TEST_F(CaptureTest, WritingIntoAMissingDirectoryThrowsAndLeavesNothing) {
    const fs::path dir = mDir / "no-such-dir";
    const std::vector<float> px = testPattern(2, 2, 4);
    for (const fs::path& file : {dir / "frame.exr", dir / "frame.png"}) {
        try {
            if (file.extension() == ".exr") {
                pacifica::capture::writeExrHalf(file, 2, 2, 4, px.data(), {});
            } else {
                pacifica::capture::writePng8(file, 2, 2, 4, px.data());
            }
            ADD_FAILURE() << "expected CaptureError for " << file;
        } catch (const CaptureError& e) {
            EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
            EXPECT_EQ(e.file(), file);
        }
        EXPECT_FALSE(fs::exists(file));
    }
    EXPECT_FALSE(fs::exists(dir));
    EXPECT_TRUE(fs::is_empty(mDir));
}

TEST_F(CaptureTest, FailedRenameRemovesTheTempFile) {
    // The final name is taken by a non-empty directory: the temp file is written fine, the rename fails.
    const fs::path taken = mDir / "taken.exr";
    fs::create_directories(taken / "inside");
    const std::vector<float> px = testPattern(2, 2, 3);
    try {
        pacifica::capture::writeExrHalf(taken, 2, 2, 3, px.data(), {});
        ADD_FAILURE() << "expected CaptureError";
    } catch (const CaptureError& e) {
        EXPECT_NE(std::string(e.what()).find("cannot rename"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(tempFiles().empty());
    EXPECT_TRUE(fs::is_directory(taken / "inside")); // the existing entry is untouched
}

TEST_F(CaptureTest, BadArgumentsThrowNamingTheFile) {
    const std::vector<float> px = testPattern(2, 2, 4);
    const fs::path file = mDir / "bad.exr";
    try {
        pacifica::capture::writeExrHalf(file, 2, 2, 5, px.data(), {});
        ADD_FAILURE() << "expected CaptureError";
    } catch (const CaptureError& e) {
        EXPECT_EQ(std::string(e.what()), file.string() + ": writeExrHalf(): expected 3 to 4 channels, got 5");
    }
    EXPECT_THROW(pacifica::capture::writePng8(mDir / "bad.png", 0, 2, 3, px.data()), CaptureError);
    EXPECT_THROW(pacifica::capture::writePng8(mDir / "bad.png", 2, 2, 3, nullptr), CaptureError);
    EXPECT_TRUE(fs::is_empty(mDir));
}

TEST_F(CaptureTest, ReadingAMissingFileThrowsNamingIt) {
    const fs::path file = mDir / "missing.exr";
    try {
        pacifica::capture::readImage(file);
        ADD_FAILURE() << "expected CaptureError";
    } catch (const CaptureError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(file.string() + ": cannot open image", 0), 0u) << e.what();
    }
}

// The OpenEXR-only backend's file, read by this build's readImage() (OpenImageIO in the default build):
// the same half values, metadata and compression name as writeExrHalf() gives.
TEST_F(CaptureTest, OpenExrBackendFileReadsBackLikeCapturesOwn) {
    const int w = 7, h = 5, c = 4;
    const std::vector<float> px = testPattern(w, h, c);
    const std::vector<uint16_t> halves = pacifica::capture::toHalf(px.data(), px.size());
    Metadata meta;
    meta.strings.push_back({"flight", "batumi.acmi"});
    meta.numbers.push_back({"time_s", 1e6 + 0.25});
    const fs::path file = mDir / "openexr.exr";
    pacifica::capture::openexr::writeHalf(file, file, w, h, c, halves.data(), meta,
                                          pacifica::capture::Compression::Small);
    EXPECT_TRUE(pacifica::capture::openexr::isOpenExr(file));

    const Image img = pacifica::capture::readImage(file);
    ASSERT_EQ(img.width, w);
    ASSERT_EQ(img.height, h);
    ASSERT_EQ(img.channels, c);
    EXPECT_EQ(pacifica::capture::toHalf(img.pixels.data(), img.pixels.size()), halves);
    EXPECT_EQ(img.attributes.at("pacifica:flight"), "batumi.acmi");
    EXPECT_EQ(std::stod(img.attributes.at("pacifica:time_s")), 1e6 + 0.25);
    EXPECT_EQ(img.attributes.at("compression"), "zip");
}

// writeExrHalf()'s file read by the OpenEXR-only backend, RGB and RGBA, both compression levels.
TEST_F(CaptureTest, OpenExrBackendReadsCapturesFiles) {
    for (const int c : {3, 4}) {
        for (const auto level :
             {pacifica::capture::Compression::Small, pacifica::capture::Compression::Fast}) {
            const int w = 9,
                      h = 300; // 300 rows: more than one band of rows when read, and several ZIP blocks
            const std::vector<float> px = testPattern(w, h, c);
            Metadata meta;
            meta.numbers.push_back({"pi", 3.141592653589793});
            const fs::path file = mDir / ("capture-" + std::to_string(c) + ".exr");
            const uint64_t hash = pacifica::capture::writeExrHalf(file, w, h, c, px.data(), meta, level);

            const Image img = pacifica::capture::openexr::read(file);
            ASSERT_EQ(img.width, w);
            ASSERT_EQ(img.height, h);
            ASSERT_EQ(img.channels, c);
            const std::vector<uint16_t> back =
                pacifica::capture::toHalf(img.pixels.data(), img.pixels.size());
            EXPECT_EQ(pacifica::capture::hashHalfPixels(back.data(), back.size()), hash);
            EXPECT_EQ(std::stod(img.attributes.at("pacifica:pi")), 3.141592653589793);
            EXPECT_EQ(img.attributes.at("compression"), "zip");
        }
    }
}

// The two backends compress alike: the same zlib level gives files within 1 % of each other's size (they
// differ only in header attributes; levels 3, 5 and 6 differ from level 4 by 2.5-6.5 % on this image), and
// level 1 is larger than level 4.
TEST_F(CaptureTest, OpenExrBackendCompressesAtCapturesLevels) {
    const int w = 256, h = 128, c = 4;
    std::vector<float> px(static_cast<size_t>(w * h * c));
    for (size_t i = 0; i < px.size(); ++i) // smooth with a little noise, like a rendered sea
        px[i] = 0.5f + 0.4f * std::sin(0.01f * static_cast<float>(i)) + 0.001f * static_cast<float>(i % 7);
    const std::vector<uint16_t> halves = pacifica::capture::toHalf(px.data(), px.size());
    for (const auto level : {pacifica::capture::Compression::Small, pacifica::capture::Compression::Fast}) {
        const fs::path mine = mDir / "mine.exr";
        const fs::path theirs = mDir / "theirs.exr";
        pacifica::capture::openexr::writeHalf(mine, mine, w, h, c, halves.data(), {}, level);
        pacifica::capture::writeExrHalf(theirs, w, h, c, px.data(), {}, level);
        const double ratio = double(fs::file_size(mine)) / double(fs::file_size(theirs));
        EXPECT_NEAR(ratio, 1.0, 0.01) << fs::file_size(mine) << " vs " << fs::file_size(theirs);
    }
    const fs::path small = mDir / "small.exr";
    const fs::path fast = mDir / "fast.exr";
    pacifica::capture::openexr::writeHalf(small, small, w, h, c, halves.data(), {},
                                          pacifica::capture::Compression::Small);
    pacifica::capture::openexr::writeHalf(fast, fast, w, h, c, halves.data(), {},
                                          pacifica::capture::Compression::Fast);
    EXPECT_GT(fs::file_size(fast), fs::file_size(small));
}

// Bad files: not an EXR, truncated, missing; each a CaptureError naming the file. A write into a missing
// folder is reported under the final name.
TEST_F(CaptureTest, OpenExrBackendRefusesBadFilesNamingThem) {
    const std::vector<float> px = testPattern(64, 64, 4);
    const fs::path good = mDir / "good.exr";
    pacifica::capture::writeExrHalf(good, 64, 64, 4, px.data(), {});
    const fs::path cut = mDir / "cut.exr";
    fs::copy_file(good, cut);
    fs::resize_file(cut, fs::file_size(good) / 2);
    const fs::path text = mDir / "text.exr";
    { std::ofstream(text) << "not an image\n"; }
    for (const fs::path& file : {cut, text, mDir / "missing.exr"}) {
        try {
            pacifica::capture::openexr::read(file);
            ADD_FAILURE() << "expected CaptureError for " << file;
        } catch (const CaptureError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(file.string() + ": cannot read the OpenEXR file: ", 0), 0u)
                << e.what();
            EXPECT_EQ(e.file(), file);
        }
    }
    EXPECT_TRUE(pacifica::capture::openexr::isOpenExr(cut));
    EXPECT_FALSE(pacifica::capture::openexr::isOpenExr(text));
    try {
        const std::vector<uint16_t> halves = pacifica::capture::toHalf(px.data(), px.size());
        pacifica::capture::openexr::writeHalf(mDir / "no-dir" / "x.exr", good, 64, 64, 4, halves.data(), {},
                                              pacifica::capture::Compression::Small);
        ADD_FAILURE() << "expected CaptureError";
    } catch (const CaptureError& e) {
        EXPECT_EQ(e.file(), good); // reported under the final name, not the temp file's
    }
}

// The size limit is checked factor by factor: headers that declare sizes whose product overflows 64 bits
// (2^31 x 2^31 x 2^31) or wraps to a small number are refused, and the largest allowed image passes.
TEST(CaptureLimits, SampleLimitNeverOverflows) {
    using pacifica::capture::MAX_READ_SAMPLES;
    using pacifica::capture::samplesWithinLimit;
    EXPECT_TRUE(samplesWithinLimit(16384, 8192, 4));
    EXPECT_FALSE(samplesWithinLimit(16384, 8192, 5));
    EXPECT_TRUE(samplesWithinLimit(MAX_READ_SAMPLES, 1, 1));
    EXPECT_FALSE(samplesWithinLimit(MAX_READ_SAMPLES + 1, 1, 1));
    EXPECT_FALSE(samplesWithinLimit(int64_t(1) << 31, int64_t(1) << 31, int64_t(1) << 31));
    EXPECT_FALSE(samplesWithinLimit(int64_t(1) << 30, int64_t(1) << 30, 16)); // 2^64: wraps to 0
    EXPECT_FALSE(samplesWithinLimit(65535, 65535, 4));
    EXPECT_FALSE(samplesWithinLimit(0, 10, 4));
    EXPECT_FALSE(samplesWithinLimit(10, -1, 4));
    EXPECT_FALSE(samplesWithinLimit(10, 10, 0));
}

} // namespace
