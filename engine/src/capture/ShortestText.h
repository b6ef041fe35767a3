// ShortestText (internal to capture): a number as the shortest text that reads back to the same value
// (std::to_chars without a precision), how both image backends report numeric attributes.
#pragma once

#include <array>
#include <charconv>
#include <string>

namespace pacifica::capture {

template <class T>
std::string shortestText(T value) {
    std::array<char, 64> buf{};
    const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), value);
    return std::string(buf.data(), res.ptr);
}

} // namespace pacifica::capture
