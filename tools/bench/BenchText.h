// BenchText: number and CSV formatting shared by the benchmark report writers (bench_accuracy.cpp,
// bench_effects.cpp). Header-only.
#pragma once

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

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

} // namespace pacifica::bench
