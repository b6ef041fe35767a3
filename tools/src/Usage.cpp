// Usage: the CLI's shared option parsing (Usage.h).
#include "Usage.h"

namespace pacifica::tools {

void parseSize(const std::string& text, int& width, int& height) {
    const size_t x = text.find('x');
    auto bad = [&] {
        return UsageError("--size: expected WxH with 16 <= W,H <= 8192 (e.g. 640x360), got '" + text + "'");
    };
    if (x == std::string::npos)
        throw bad();
    try {
        size_t used = 0;
        width = std::stoi(text.substr(0, x), &used);
        if (used != x)
            throw bad();
        height = std::stoi(text.substr(x + 1), &used);
        if (used != text.size() - x - 1)
            throw bad();
    } catch (const std::logic_error&) {
        throw bad();
    }
    if (width < 16 || height < 16 || width > 8192 || height > 8192)
        throw bad();
}

} // namespace pacifica::tools
