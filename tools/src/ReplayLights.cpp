// ReplayLights: --light specs -> spot lights per frame (ReplayLights.h).
#include "ReplayLights.h"

#include "Usage.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace pacifica::tools {

namespace {

double number(const std::string& spec, const std::string& key, const std::string& text, double lo,
              double hi) {
    size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(text, &used);
    } catch (const std::logic_error&) {
        used = 0;
    }
    if (used != text.size() || !std::isfinite(v) || v < lo || v > hi) {
        std::ostringstream m;
        m << "--light '" << spec << "': " << key << " must be a number in [" << lo << ", " << hi << "], got '"
          << text << "'";
        throw UsageError(m.str());
    }
    return v;
}

glm::vec3 colour(const std::string& spec, const std::string& text) {
    glm::vec3 c(0.0f);
    size_t pos = 0;
    for (int i = 0; i < 3; ++i) {
        const size_t end = i < 2 ? text.find(':', pos) : text.size();
        if (end == std::string::npos)
            throw UsageError("--light '" + spec + "': color must be R:G:B, got '" + text + "'");
        c[i] = static_cast<float>(number(spec, "color", text.substr(pos, end - pos), 0.0, 1e6));
        pos = end + 1;
    }
    return c;
}

/// One key=value onto the light.
void applyKey(ReplayLight& l, const std::string& key, const std::string& value, bool& x, bool& y) {
    const std::string& s = l.spec;
    if (key == "height")
        l.height = number(s, key, value, 0.0, 1e4);
    else if (key == "azimuth")
        l.azimuthDeg = number(s, key, value, -360.0, 360.0);
    else if (key == "elevation")
        l.elevationDeg = number(s, key, value, -90.0, 90.0);
    else if (key == "angle")
        l.angleDeg = number(s, key, value, 0.1, 90.0);
    else if (key == "intensity")
        l.intensity = static_cast<float>(number(s, key, value, 0.0, 1e12));
    else if (key == "range")
        l.range = number(s, key, value, 1.0, 1e6);
    else if (key == "color")
        l.color = colour(s, value);
    else if (key == "x" || key == "y") {
        if (l.ship)
            throw UsageError("--light '" + s + "': " + key + "= is for a fixed light (spot:fixed,x=..,y=..)");
        (key == "x" ? l.fixedPosition.x : l.fixedPosition.y) = number(s, key, value, -1e7, 1e7);
        (key == "x" ? x : y) = true;
    } else
        throw UsageError("--light '" + s + "': unknown key '" + key +
                         "' (height, azimuth, elevation, angle, intensity, range, color, x, y)");
}

ReplayLight parseLight(const std::string& spec, const ReplayInput& input) {
    ReplayLight l;
    l.spec = spec;
    if (spec.rfind("spot:", 0) != 0)
        throw UsageError("--light '" + spec +
                         "': expected spot:SHIP[,key=value...] or spot:fixed,x=M,y=M[,...]");
    std::vector<std::string> parts;
    std::stringstream in(spec.substr(5));
    for (std::string p; std::getline(in, p, ',');)
        parts.push_back(p);
    const std::string target = parts.empty() ? std::string() : parts.front();
    if (target != "fixed") {
        for (size_t i = 0; i < input.ships.size(); ++i)
            if (input.ships[i].id == target)
                l.ship = i;
        if (!l.ship) {
            std::string ids;
            for (const ShipTrack& t : input.ships)
                ids += (ids.empty() ? "" : ", ") + t.id;
            throw UsageError("--light '" + spec + "': no ship '" + target +
                             "' in the flight (ships: " + (ids.empty() ? std::string("none") : ids) + ")");
        }
    }
    bool x = false, y = false;
    for (size_t i = 1; i < parts.size(); ++i) {
        const size_t eq = parts[i].find('=');
        if (eq == std::string::npos)
            throw UsageError("--light '" + spec + "': expected key=value, got '" + parts[i] + "'");
        applyKey(l, parts[i].substr(0, eq), parts[i].substr(eq + 1), x, y);
    }
    if (!l.ship && !(x && y))
        throw UsageError("--light '" + spec + "': a fixed light needs x= and y= (metres east, north)");
    return l;
}

} // namespace

std::vector<ReplayLight> parseReplayLights(const std::vector<std::string>& specs, const ReplayInput& input,
                                           double exposureScale) {
    std::vector<ReplayLight> lights;
    for (const std::string& s : specs) {
        lights.push_back(parseLight(s, input));
        const ReplayLight& l = lights.back();
        const double brightest =
            std::max({l.color.r, l.color.g, l.color.b}) * static_cast<double>(l.intensity) * exposureScale;
        if (!(brightest <= ocean::MAX_SPOT_INTENSITY)) {
            std::ostringstream m;
            m << "--light '" << s << "': color x intensity x 2^exposure = " << brightest
              << " exceeds the spot lights' bound " << ocean::MAX_SPOT_INTENSITY;
            throw UsageError(m.str());
        }
    }
    return lights;
}

std::vector<ocean::SpotLight> replayLightsAt(const std::vector<ReplayLight>& lights, const ReplayInput& input,
                                             double t, double exposureScale) {
    std::vector<ocean::SpotLight> out;
    constexpr double DEG = std::numbers::pi / 180.0;
    for (const ReplayLight& l : lights) {
        glm::dvec2 at = l.fixedPosition;
        double azimuth = l.azimuthDeg;
        if (l.ship) {
            const ShipTrack& ship = input.ships[*l.ship];
            if (t < ship.startTime() || t > ship.endTime())
                continue;
            at = ship.positionAt(t);
            azimuth += ship.headingAt(t);
        }
        ocean::SpotLight s;
        s.position = glm::dvec3(at, l.height);
        const double az = azimuth * DEG, el = l.elevationDeg * DEG;
        s.direction = {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
        s.frustumDeg = l.angleDeg;
        s.color = l.color;
        s.intensity = static_cast<float>(l.intensity * exposureScale);
        s.range = l.range;
        out.push_back(s);
    }
    return out;
}

} // namespace pacifica::tools
