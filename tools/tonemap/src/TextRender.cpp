// FreeType 2 text on float RGB images (TextRender.h).
#include "tonemap/TextRender.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <stdexcept>

namespace pacifica::tonemap {

namespace {

/// Decodes one UTF-8 code point at s[i], advancing i; malformed bytes become U+FFFD.
char32_t nextCodePoint(const std::string& s, size_t& i) {
    const auto b = static_cast<unsigned char>(s[i++]);
    if (b < 0x80)
        return b;
    const int extra = b >= 0xF0 ? 3 : b >= 0xE0 ? 2 : b >= 0xC0 ? 1 : -1;
    if (extra < 0 || i + static_cast<size_t>(extra) > s.size())
        return 0xFFFD;
    char32_t cp = b & (0x3F >> extra);
    for (int k = 0; k < extra; ++k) {
        const auto c = static_cast<unsigned char>(s[i++]);
        if ((c & 0xC0) != 0x80)
            return 0xFFFD;
        cp = (cp << 6) | (c & 0x3F);
    }
    return cp;
}

} // namespace

std::filesystem::path defaultFontPath() {
    return "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
}

struct TextRenderer::Impl {
    FT_Library library = nullptr;
    FT_Face face = nullptr;
};

TextRenderer::TextRenderer(const std::filesystem::path& font, int pixelSize) : mImpl(new Impl) {
    if (FT_Init_FreeType(&mImpl->library) != 0)
        throw std::runtime_error("FreeType could not start");
    if (FT_New_Face(mImpl->library, font.c_str(), 0, &mImpl->face) != 0) {
        FT_Done_FreeType(mImpl->library);
        throw std::runtime_error(
            font.string() + ": cannot load the font (install Debian's fonts-dejavu-core: ./pacifica deps)");
    }
    FT_Set_Pixel_Sizes(mImpl->face, 0, static_cast<FT_UInt>(std::max(pixelSize, 4)));
}

TextRenderer::~TextRenderer() {
    FT_Done_Face(mImpl->face);
    FT_Done_FreeType(mImpl->library);
}

int TextRenderer::lineHeight() const {
    return static_cast<int>((mImpl->face->size->metrics.ascender - mImpl->face->size->metrics.descender) >>
                            6);
}

int TextRenderer::ascender() const {
    return static_cast<int>(mImpl->face->size->metrics.ascender >> 6);
}

int TextRenderer::width(const std::string& utf8) const {
    int pen = 0;
    for (size_t i = 0; i < utf8.size();) {
        const char32_t cp = nextCodePoint(utf8, i);
        if (FT_Load_Char(mImpl->face, cp, FT_LOAD_DEFAULT) == 0)
            pen += static_cast<int>(mImpl->face->glyph->advance.x >> 6);
    }
    return pen;
}

int TextRenderer::draw(std::vector<float>& rgb, int width, int height, int x, int y, const std::string& utf8,
                       const std::array<float, 3>& colour) const {
    int pen = x;
    for (size_t i = 0; i < utf8.size();) {
        const char32_t cp = nextCodePoint(utf8, i);
        if (FT_Load_Char(mImpl->face, cp, FT_LOAD_RENDER) != 0)
            continue;
        const FT_GlyphSlot g = mImpl->face->glyph;
        const FT_Bitmap& bm = g->bitmap;
        for (unsigned row = 0; row < bm.rows; ++row)
            for (unsigned col = 0; col < bm.width; ++col) {
                const int px = pen + g->bitmap_left + static_cast<int>(col);
                const int py = y - g->bitmap_top + static_cast<int>(row);
                if (px < 0 || py < 0 || px >= width || py >= height)
                    continue;
                const float a =
                    static_cast<float>(bm.buffer[row * static_cast<unsigned>(bm.pitch) + col]) / 255.0f;
                float* p =
                    &rgb[(static_cast<size_t>(py) * static_cast<size_t>(width) + static_cast<size_t>(px)) *
                         3];
                for (int k = 0; k < 3; ++k)
                    p[k] = p[k] * (1.0f - a) + colour[static_cast<size_t>(k)] * a;
            }
        pen += static_cast<int>(g->advance.x >> 6);
    }
    return pen;
}

} // namespace pacifica::tonemap
