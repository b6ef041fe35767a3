// BenchText: number and CSV formatting, the report date and --size parsing shared by the benchmark report
// writers (bench_accuracy.cpp, bench_effects.cpp, bench_frame.cpp). Header-only.
#pragma once

#include <cmath>
#include <cstdio>
#include <ctime>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

namespace pacifica::bench {

/// `precision` significant digits; "nan", "inf", "-inf" spelled out.
inline std::string num(double v, int precision = 6) {
    if (std::isnan(v))
        return "nan";
    if (std::isinf(v))
        return v > 0 ? "inf" : "-inf";
    std::ostringstream s;
    s << std::setprecision(precision) << v;
    return s.str();
}

/// A CSV field in double quotes, inner quotes doubled (RFC 4180).
inline std::string csvQuote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"')
            out += '"';
        out += c;
    }
    return out + "\"";
}

/// "YYYY-MM-DD HH:MM:SS UTC" of now, for report headers.
inline std::string utcNow() {
    const std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
    return date;
}

/// "WxH" (or "WXH") with both sides in 16..8192, else nullopt.
inline std::optional<std::pair<int, int>> parseSize(const std::string& s) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(s.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 16 ||
        h < 16 || w > 8192 || h > 8192)
        return std::nullopt;
    return std::pair{w, h};
}

} // namespace pacifica::bench
