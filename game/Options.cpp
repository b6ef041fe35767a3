// Options: pacifica-game's command line (Options.h).
#include "Options.h"

#include <ocean/Presets.h>
#include <ocean/SurfaceModel.h>

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>

namespace pacifica::game {

const char* toString(CameraMode m) {
    switch (m) {
    case CameraMode::Cockpit:
        return "cockpit";
    case CameraMode::Chase:
        return "chase";
    case CameraMode::Orbit:
        return "orbit";
    case CameraMode::Weapon:
        return "weapon";
    case CameraMode::Ship:
        return "ship";
    }
    return "?";
}

namespace {

CameraMode parseCamera(const std::string& camera) {
    if (camera == "cockpit")
        return CameraMode::Cockpit;
    if (camera == "chase")
        return CameraMode::Chase;
    if (camera == "orbit")
        return CameraMode::Orbit;
    if (camera == "weapon")
        return CameraMode::Weapon;
    if (camera == "ship")
        return CameraMode::Ship;
    throw UsageError("--camera: unknown camera '" + camera +
                     "' (valid: cockpit, chase, orbit, weapon, ship)");
}

/// "WxH", 64..8192 each (a window smaller than 64 has no room for the HUD).
void parseWindowSize(const std::string& size, Options& o) {
    const size_t x = size.find('x');
    int w = 0, h = 0;
    if (x == std::string::npos || std::from_chars(size.data(), size.data() + x, w).ptr != size.data() + x ||
        std::from_chars(size.data() + x + 1, size.data() + size.size(), h).ptr != size.data() + size.size() ||
        w < 64 || h < 64 || w > 8192 || h > 8192)
        throw UsageError("--size must be WxH with 64 <= W, H <= 8192, got '" + size + "'");
    o.width = w;
    o.height = h;
}

/// "T:FILE" pairs, T seconds of game time >= 0.
void parseScreenshots(const std::vector<std::string>& shots, Options& o) {
    for (const std::string& s : shots) {
        const size_t c = s.find(':');
        double t = 0.0;
        if (c == std::string::npos || c + 1 >= s.size() ||
            std::from_chars(s.data(), s.data() + c, t).ptr != s.data() + c || !std::isfinite(t) || t < 0.0)
            throw UsageError("--screenshot must be T:FILE with T >= 0 seconds of game time, got '" + s + "'");
        o.screenshots.emplace_back(t, s.substr(c + 1));
    }
}

/// Every value in range, named in the error when it is not.
void checkRanges(Options& o) {
    if (o.frames < 0)
        throw UsageError("--frames must be >= 0, got " + std::to_string(o.frames));
    if (!(std::isfinite(o.fps) && o.fps >= 1.0 && o.fps <= 1000.0))
        throw UsageError("--fps must be in [1, 1000]");
    if (!(std::isfinite(o.sea.windSpeed) && o.sea.windSpeed >= 2.0 && o.sea.windSpeed <= 25.0))
        throw UsageError("--wind must be a wind speed in [2, 25] m/s");
    if (!(std::isfinite(o.wipePosition) && o.wipePosition >= 0.0 && o.wipePosition <= 1.0))
        throw UsageError("--wipe-position must be in [0, 1]");
}

} // namespace

Options parseOptions(int argc, char** argv) {
    Options o;
    CLI::App app{
        "pacifica-game: take off from the carrier, sink the three target ships, don't fly into the sea",
        "pacifica-game"};
    std::string camera = "chase", size = "1280x720";
    std::vector<std::string> shots;
    app.add_flag("--autopilot", o.autopilot, "the autopilot flies the sortie (scripted input)");
    app.add_option("--frames", o.frames, "stop after N frames (scripted stepping)");
    app.add_option("--fps", o.fps, "scripted runs: frames per game second (default 30)");
    app.add_option("--screenshot", shots, "T:FILE.png: write the window (HUD included) at game time T s")
        ->allow_extra_args(false);
    app.add_option("--record", o.record, "write the session as Tacview ACMI 2.2 (for pacifica replay)");
    app.add_option("--summary", o.summary, "write what happened as JSON at exit");
    app.add_option("--bench", o.bench, "time the autopilot's sortie at each quality preset into FILE.json");
    app.add_option("--camera", camera, "cockpit | chase | orbit | weapon | ship (C cycles)");
    app.add_option("--quality", o.sea.quality, "low | medium | high | reference (default medium)");
    app.add_option("--model", o.sea.model, "octaves | gerstner | fft");
    app.add_option("--wind", o.sea.windSpeed, "sea state: wind speed U10 in m/s, 2..25 (default 12)");
    app.add_flag("--night", o.sea.night,
                 "a night sortie: a moonlit, hazy sea and the carrier's floodlights and searchlight");
    app.add_option("--view", o.view, "OCIO view (default: the config's)");
    app.add_option("--wipe", o.wipeView, "split screen: this second OCIO view right of the wipe line");
    app.add_option("--wipe-position", o.wipePosition, "the wipe line, fraction of the width (0..1)");
    app.add_option("--size", size, "window size WxH (default 1280x720)");
    // A plain bool: a flag with a callback took "--no-hud=x" to std::stoll, which threw past CLI11's errors.
    bool noHud = false;
    app.add_flag("--no-hud", noHud, "hide the HUD (F1 toggles)");
    app.add_flag("--headless", o.headless, "no window: EGL, offscreen (benchmarks)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        std::printf("%s", app.help().c_str());
        o.help = true;
        return o;
    } catch (const CLI::ParseError& e) {
        throw UsageError(e.what());
    }
    o.hud = !noHud;
    checkRanges(o);
    o.camera = parseCamera(camera);
    try {
        ocean::parseQuality(o.sea.quality);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--quality: ") + e.what());
    }
    parseSurfaceModelIndex(o.sea.model);
    parseWindowSize(size, o);
    parseScreenshots(shots, o);
    if (!o.bench.empty() && o.frames <= 0)
        o.frames = 120;
    if (o.bench.empty() && o.headless && o.frames <= 0)
        throw UsageError("--headless needs --frames N (nothing can close a window that is not there)");
    return o;
}

int parseSurfaceModelIndex(const std::string& name) {
    if (name == "octaves")
        return static_cast<int>(ocean::SurfaceKind::Octaves);
    if (name == "gerstner")
        return static_cast<int>(ocean::SurfaceKind::Gerstner);
    if (name == "fft")
        return static_cast<int>(ocean::SurfaceKind::Fft);
    throw UsageError("--model: unknown surface model '" + name + "' (valid: octaves, gerstner, fft)");
}

} // namespace pacifica::game
