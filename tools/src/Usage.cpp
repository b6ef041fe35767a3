// Usage: the CLI's shared option parsing (Usage.h) and the replay options' own checks (Replay.h).
#include "Usage.h"

#include "Replay.h"

#include <cctype>
#include <cmath>

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

FrameRange parseFrameRange(const std::string& text) {
    auto bad = [&] {
        return UsageError("--frames: expected I-J, the 0-based first and last frame with 0 <= I <= J (e.g. "
                          "0-99), or one frame I, got '" +
                          text + "'");
    };
    auto number = [&](const std::string& part) {
        if (part.empty() || part.size() > 12 || part.find_first_not_of("0123456789") != std::string::npos)
            throw bad();
        return std::stoll(part);
    };
    const size_t dash = text.find('-');
    FrameRange r;
    r.first = number(text.substr(0, dash));
    r.last = dash == std::string::npos ? r.first : number(text.substr(dash + 1));
    if (r.last < r.first)
        throw bad();
    return r;
}

void checkReplayOptions(const ReplayOptions& o) {
    if (!std::isfinite(o.fps) || o.fps <= 0.0 || o.fps > 1000.0)
        throw UsageError("--fps must be in (0, 1000], got " + std::to_string(o.fps));
    if (!std::isfinite(o.fovYDeg) || o.fovYDeg < 1.0f || o.fovYDeg > 170.0f)
        throw UsageError("--fov must be in [1, 170] degrees, got " + std::to_string(o.fovYDeg));
    if (!std::isfinite(o.speed) || o.speed <= 0.0 || o.speed > 1e6)
        throw UsageError("--speed must be in (0, 1e6], got " + std::to_string(o.speed));
    if (o.maxFrames < 1)
        throw UsageError("--max-frames must be >= 1, got " + std::to_string(o.maxFrames));
    if (o.outDir.empty() && !o.video)
        throw UsageError("--out: an output directory is required (or --video FILE alone)");
    if ((o.eglDevice >= 0 || o.eglDeviceAuto) && !o.cudaDevice.empty())
        throw UsageError("--egl-device and --cuda-device name the device twice: give one");
    if (o.frames && o.video)
        throw UsageError("--frames renders a chunk of the run's frames into --out; --video needs the whole "
                         "run (encode the chunks' PNGs once they are all there)");
}

std::string fileSlug(const std::string& name) {
    std::string out;
    for (char c : name)
        out += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '-';
    return out;
}

} // namespace pacifica::tools
