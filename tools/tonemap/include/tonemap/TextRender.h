// Text on float RGB images from a real font (FreeType 2 rasterising DejaVu Sans from Debian's
// fonts-dejavu-core): the labels of contact sheets and reports. Antialiased coverage is blended over the
// pixels; UTF-8 is decoded (Latin and Greek from DejaVu cover every label the tools write).
//
// STEP BY STEP
//   1. TextRenderer text(defaultFontPath(), 14);          // throws std::runtime_error naming a missing font
//   2. text.draw(rgb, width, height, x, baselineY, "AgX base", {1, 1, 1});
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace pacifica::tonemap {

/// DejaVu Sans as Debian installs it (fonts-dejavu-core).
std::filesystem::path defaultFontPath();

class TextRenderer {
public:
    /// Loads `font` at `pixelSize` pixels per em. Throws std::runtime_error naming the file when it is
    /// missing or not a font FreeType reads.
    TextRenderer(const std::filesystem::path& font, int pixelSize);
    ~TextRenderer();
    TextRenderer(const TextRenderer&) = delete;
    TextRenderer& operator=(const TextRenderer&) = delete;

    /// Advance width of `text` in pixels.
    int width(const std::string& utf8) const;
    /// Line height (ascender - descender) in pixels.
    int lineHeight() const;
    /// Ascender in pixels: the baseline sits this far below the top of a line.
    int ascender() const;
    /// Draws `utf8` with its baseline at y, starting at x, clipped to the image; returns the pen's end x.
    int draw(std::vector<float>& rgb, int width, int height, int x, int y, const std::string& utf8,
             const std::array<float, 3>& colour) const;

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

} // namespace pacifica::tonemap
