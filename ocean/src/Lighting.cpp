// Lighting: the CPU side of the shading — validation of LightingDesc and environment maps, the fog and
// foam formulas the shaders mirror (fogOpticalDepth, foamAlpha), and the procedural fog-noise and foam
// textures, generated once and uploaded by LightingGpu. Plain C++: no GL, no image files.
#include "ocean/Lighting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace pacifica::ocean {

namespace {

constexpr double PI = std::numbers::pi;

std::string pixelName(int x, int y) {
    return "pixel (" + std::to_string(x) + "," + std::to_string(y) + ")";
}

/// 32-bit integer hash (Wellons' "lowbias32"): decorrelates lattice coordinates for noise and cells.
uint32_t hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

uint32_t hash4(int a, int b, int c, uint32_t seed) {
    return hash32(static_cast<uint32_t>(a) * 0x9E3779B1U ^
                  hash32(static_cast<uint32_t>(b) * 0x85EBCA77U ^ hash32(static_cast<uint32_t>(c) ^ seed)));
}

double unit(uint32_t h) { // [0, 1)
    return static_cast<double>(h >> 8) / 16777216.0;
}

int wrapIndex(int i, int n) {
    const int m = i % n;
    return m < 0 ? m + n : m;
}

/// Periodic 3D gradient noise (Perlin 2002 "Improving noise": quintic fade, 12 edge gradients), periods
/// `period` lattice cells along each axis, evaluated at lattice coordinates p.
double periodicPerlin(const glm::dvec3& p, const glm::ivec3& period, uint32_t seed) {
    static constexpr double G[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                                        {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                                        {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};
    const glm::dvec3 f = glm::floor(p);
    const glm::dvec3 r = p - f;
    const glm::dvec3 w = r * r * r * (r * (r * 6.0 - 15.0) + 10.0);
    const int x0 = static_cast<int>(f.x), y0 = static_cast<int>(f.y), z0 = static_cast<int>(f.z);
    double corner[8];
    for (int c = 0; c < 8; ++c) {
        const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
        const uint32_t h = hash4(wrapIndex(x0 + dx, period.x), wrapIndex(y0 + dy, period.y),
                                 wrapIndex(z0 + dz, period.z), seed) %
                           12U;
        corner[c] = G[h][0] * (r.x - dx) + G[h][1] * (r.y - dy) + G[h][2] * (r.z - dz);
    }
    auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
    const double x00 = lerp(corner[0], corner[1], w.x), x10 = lerp(corner[2], corner[3], w.x);
    const double x01 = lerp(corner[4], corner[5], w.x), x11 = lerp(corner[6], corner[7], w.x);
    return lerp(lerp(x00, x10, w.y), lerp(x01, x11, w.y), w.z);
}

double periodicPerlin(const glm::dvec3& p, int period, uint32_t seed) {
    return periodicPerlin(p, glm::ivec3(period), seed);
}

/// Distances to the nearest and second-nearest feature point of a periodic jittered grid of cells.x x
/// cells.y points over the unit square (Worley 1996), in cell units.
glm::dvec2 periodicWorley(const glm::dvec2& uv, const glm::ivec2& cells, uint32_t seed) {
    const glm::dvec2 p = uv * glm::dvec2(cells);
    const glm::dvec2 c = glm::floor(p);
    double f1 = 1e9, f2 = 1e9;
    for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) {
            const int cx = static_cast<int>(c.x) + i, cy = static_cast<int>(c.y) + j;
            const uint32_t h = hash4(wrapIndex(cx, cells.x), wrapIndex(cy, cells.y), 0, seed);
            const glm::dvec2 feature(cx + 0.1 + 0.8 * unit(h), cy + 0.1 + 0.8 * unit(hash32(h)));
            const double d = glm::length(feature - p);
            if (d < f1) {
                f2 = f1;
                f1 = d;
            } else if (d < f2) {
                f2 = d;
            }
        }
    return {f1, f2};
}

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

void normaliseToUnitRange(std::vector<float>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    const float a = *lo, span = std::max(*hi - *lo, 1e-12f);
    for (float& x : v)
        x = (x - a) / span;
}

} // namespace

EnvironmentMap makeEnvironmentMap(int width, int height, std::vector<float> rgb) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw EnvironmentMapError("size " + std::to_string(width) + "x" + std::to_string(height) +
                                  " is outside [1, 16384] x [1, 16384]");
    const size_t expected = static_cast<size_t>(width) * static_cast<size_t>(height) * 3;
    if (rgb.size() != expected)
        throw EnvironmentMapError("expected " + std::to_string(expected) +
                                  " floats (width * height * 3), got " + std::to_string(rgb.size()));
    for (size_t i = 0; i < rgb.size(); ++i) {
        const float v = rgb[i];
        if (std::isfinite(v) && v >= 0.0f)
            continue;
        const int pixel = static_cast<int>(i / 3);
        const int x = pixel % width, y = pixel / width;
        if (std::isnan(v))
            throw EnvironmentMapError(pixelName(x, y) + " is NaN", x, y);
        if (std::isinf(v))
            throw EnvironmentMapError(pixelName(x, y) + " is infinite", x, y);
        char value[32];
        std::snprintf(value, sizeof value, "%g", static_cast<double>(v));
        throw EnvironmentMapError(pixelName(x, y) + " is negative (" + value + ")", x, y);
    }
    EnvironmentMap map;
    map.width = width;
    map.height = height;
    map.rgb = std::move(rgb);
    return map;
}

glm::dvec3 environmentDirection(double u, double v) {
    const double heading = 2.0 * PI * (u - 0.5);
    const double elevation = PI * (0.5 - v);
    return {std::sin(heading) * std::cos(elevation), std::cos(heading) * std::cos(elevation),
            std::sin(elevation)};
}

glm::dvec2 environmentUv(const glm::dvec3& direction) {
    const glm::dvec3 d = glm::normalize(direction);
    double u = std::atan2(d.x, d.y) / (2.0 * PI) + 0.5;
    if (u >= 1.0)
        u -= 1.0;
    return {u, 0.5 - std::asin(std::clamp(d.z, -1.0, 1.0)) / PI};
}

glm::dvec3 environmentBrightestDirection(const EnvironmentMap& map) {
    auto luminance = [&](size_t p) {
        return 0.2126 * map.rgb[p * 3] + 0.7152 * map.rgb[p * 3 + 1] + 0.0722 * map.rgb[p * 3 + 2];
    };
    const size_t n = static_cast<size_t>(map.width) * static_cast<size_t>(map.height);
    double peak = 0.0;
    for (size_t p = 0; p < n; ++p)
        peak = std::max(peak, luminance(p));
    if (peak <= 0.0)
        return {0.0, 0.0, 1.0};
    glm::dvec3 sum(0.0);
    for (size_t p = 0; p < n; ++p) {
        const double l = luminance(p);
        if (l < 0.5 * peak)
            continue;
        const double u = (static_cast<double>(p % map.width) + 0.5) / map.width;
        const double v = (static_cast<double>(p / map.width) + 0.5) / map.height;
        const double solidAngle = std::cos(PI * (0.5 - v)); // lat-long texel area ~ cos(elevation)
        sum += l * solidAngle * environmentDirection(u, v);
    }
    return glm::length(sum) > 0.0 ? glm::normalize(sum) : glm::dvec3(0.0, 0.0, 1.0);
}

namespace {

double pixelLuminance(const float* p) {
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

/// The sun cap: 16x the median luminance of the upper hemisphere (sampled on a sparse grid: exact order
/// statistics of a million pixels are not needed for a cap).
double sunCap(const EnvironmentMap& m) {
    std::vector<double> l;
    const int rows = std::max(m.height / 2, 1);
    const int step = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(rows) * m.width / 65536.0)));
    for (int y = 0; y < rows; y += step)
        for (int x = 0; x < m.width; x += step)
            l.push_back(pixelLuminance(&m.rgb[(static_cast<size_t>(y) * m.width + x) * 3]));
    std::nth_element(l.begin(), l.begin() + static_cast<std::ptrdiff_t>(l.size() / 2), l.end());
    return std::max(16.0 * l[l.size() / 2], 1e-6);
}

/// Pixel (x, y) with its luminance capped at `cap` (hue kept).
glm::dvec3 cappedPixel(const EnvironmentMap& m, int x, int y, double cap) {
    const float* p = &m.rgb[(static_cast<size_t>(y) * m.width + x) * 3];
    const double l = pixelLuminance(p);
    const double k = l > cap ? cap / l : 1.0;
    return k * glm::dvec3(p[0], p[1], p[2]);
}

} // namespace

glm::vec3 environmentIrradiance(const EnvironmentMap& m) {
    // E = sum L sin(e) dOmega over the upper hemisphere; lat-long texel dOmega = (2 pi / w)(pi / h) cos(e).
    const double cap = sunCap(m);
    const double dOmega = (2.0 * PI / m.width) * (PI / m.height);
    glm::dvec3 e(0.0);
    for (int y = 0; y < m.height; ++y) {
        const double elevation = PI * (0.5 - (y + 0.5) / m.height);
        if (elevation <= 0.0)
            break;
        const double w = std::sin(elevation) * std::cos(elevation) * dOmega;
        for (int x = 0; x < m.width; ++x)
            e += w * cappedPixel(m, x, y, cap);
    }
    return glm::vec3(e);
}

std::vector<glm::vec3> environmentHorizonBand(const EnvironmentMap& m) {
    const int bins = ENVIRONMENT_HORIZON_BINS;
    const double cap = sunCap(m);
    std::vector<glm::dvec3> sum(bins, glm::dvec3(0.0));
    std::vector<double> weight(bins, 0.0);
    for (int y = 0; y < m.height; ++y) {
        const double elevation = PI * (0.5 - (y + 0.5) / m.height);
        if (elevation < 0.0 || elevation > 20.0 * PI / 180.0)
            continue;
        const double w = std::cos(elevation);
        for (int x = 0; x < m.width; ++x) {
            const int bin = std::min(bins - 1, static_cast<int>((x + 0.5) / m.width * bins));
            sum[bin] += w * cappedPixel(m, x, y, cap);
            weight[bin] += w;
        }
    }
    // A map too small to have a row in the band: use the row nearest the horizon.
    if (weight[0] == 0.0) {
        const int y = std::clamp(m.height / 2 - 1, 0, m.height - 1);
        for (int x = 0; x < m.width; ++x) {
            const int bin = std::min(bins - 1, static_cast<int>((x + 0.5) / m.width * bins));
            sum[bin] += cappedPixel(m, x, y, cap);
            weight[bin] += 1.0;
        }
    }
    std::vector<glm::dvec3> mean(bins);
    for (int i = 0; i < bins; ++i) // bins without a column (maps narrower than 64): nearest filled bin
        mean[i] = weight[i] > 0.0 ? sum[i] / weight[i] : glm::dvec3(-1.0);
    for (int i = 0; i < bins; ++i)
        for (int d = 1; mean[i].x < 0.0 && d < bins; ++d)
            if (weight[(i + d) % bins] > 0.0)
                mean[i] = sum[(i + d) % bins] / weight[(i + d) % bins];
    std::vector<glm::vec3> out(bins);
    static constexpr double K[5] = {1.0 / 16, 4.0 / 16, 6.0 / 16, 4.0 / 16, 1.0 / 16};
    for (int i = 0; i < bins; ++i) {
        glm::dvec3 c(0.0);
        for (int k = -2; k <= 2; ++k)
            c += K[k + 2] * mean[((i + k) % bins + bins) % bins];
        out[i] = glm::vec3(c);
    }
    return out;
}

void validateLighting(const LightingDesc& l) {
    auto finite = [](double v) { return std::isfinite(v); };
    auto fail = [](const std::string& what) { throw std::invalid_argument("OceanDesc.lighting." + what); };
    if (!finite(l.sunDirection.x) || !finite(l.sunDirection.y) || !finite(l.sunDirection.z) ||
        glm::length(l.sunDirection) < 1e-9)
        fail("sunDirection must be finite and non-zero");
    if (!finite(l.sunIntensity) || l.sunIntensity < 0.0f)
        fail("sunIntensity must be finite and >= 0, got " + std::to_string(l.sunIntensity));
    if (!finite(l.skyIntensity) || l.skyIntensity < 0.0f)
        fail("skyIntensity must be finite and >= 0, got " + std::to_string(l.skyIntensity));
    if (!finite(l.fogDensity) || l.fogDensity < 0.0f)
        fail("fogDensity must be finite and >= 0, got " + std::to_string(l.fogDensity));
    for (int i = 0; i < 3; ++i)
        if (!finite(l.waterColor[i]) || l.waterColor[i] < 0.0f)
            fail("waterColor must be finite and >= 0 in each channel, got " +
                 std::to_string(l.waterColor[i]));
    if (!finite(l.normalTilt) || l.normalTilt < 0.0f || l.normalTilt > 1.0f)
        fail("normalTilt must be in [0, 1], got " + std::to_string(l.normalTilt));
    if (!finite(l.subsurface) || l.subsurface < 0.0f || l.subsurface > 10.0f)
        fail("subsurface must be in [0, 10], got " + std::to_string(l.subsurface));
    if (!finite(l.microSlopeVariance) || l.microSlopeVariance < 0.0f || l.microSlopeVariance > 1.0f)
        fail("microSlopeVariance must be in [0, 1], got " + std::to_string(l.microSlopeVariance));
    if (l.environment) {
        const EnvironmentMap& e = *l.environment;
        if (e.width < 1 || e.height < 1 ||
            e.rgb.size() != static_cast<size_t>(e.width) * static_cast<size_t>(e.height) * 3)
            fail("environment must come from makeEnvironmentMap() (size and data disagree)");
        if (!finite(e.intensity) || e.intensity < 0.0f)
            fail("environment->intensity must be finite and >= 0, got " + std::to_string(e.intensity));
    }
    if (!finite(l.fogHeightFalloff) || l.fogHeightFalloff < 0.0f)
        fail("fogHeightFalloff must be finite and >= 0 (0 = uniform), got " +
             std::to_string(l.fogHeightFalloff));
    if (!finite(l.fogNoise) || l.fogNoise < 0.0f || l.fogNoise > 1.0f)
        fail("fogNoise must be in [0, 1], got " + std::to_string(l.fogNoise));
    if (!finite(l.fogWind.x) || !finite(l.fogWind.y))
        fail("fogWind must be finite");
    if (l.fogColor && (!finite(l.fogColor->r) || !finite(l.fogColor->g) || !finite(l.fogColor->b) ||
                       l.fogColor->r < 0.0f || l.fogColor->g < 0.0f || l.fogColor->b < 0.0f))
        fail("fogColor must be finite and >= 0");
    if (!finite(l.foamHeightStart) || !finite(l.foamHeightFull) || l.foamHeightFull <= l.foamHeightStart)
        fail("foamHeightFull must be finite and > foamHeightStart, got " + std::to_string(l.foamHeightFull) +
             " <= " + std::to_string(l.foamHeightStart));
    if (!finite(l.foamJacobianThreshold))
        fail("foamJacobianThreshold must be finite");
    if (!finite(l.foamIntensity) || l.foamIntensity < 0.0f)
        fail("foamIntensity must be finite and >= 0, got " + std::to_string(l.foamIntensity));
    if (l.spotScatterSamples < 0 || l.spotScatterSamples > 64)
        fail("spotScatterSamples must be in [0, 64], got " + std::to_string(l.spotScatterSamples));
    if (!std::isfinite(l.windDirectionDeg))
        fail("windDirectionDeg must be finite");
}

double fogOpticalDepth(double z0, double z1, double distance, const LightingDesc& l) {
    const double rho0 = l.fogDensity, h = l.fogHeightFalloff;
    if (h <= 0.0)
        return rho0 * distance;
    // rho0 H (e^(-z0/H) - e^(-z1/H)) / ((z1 - z0) / d) = rho0 d e^(-min/H) (1 - e^(-delta)) / delta.
    const double delta = std::abs(z1 - z0) / h;
    const double shape = delta < 1e-4 ? 1.0 - delta * (0.5 - delta / 6.0) : -std::expm1(-delta) / delta;
    return rho0 * distance * std::exp(-std::min(z0, z1) / h) * shape;
}

void validateSpotLight(const SpotLight& s, size_t index) {
    const std::string name = "spots[" + std::to_string(index) + "].";
    auto finite3 = [](const auto& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
    };
    if (!finite3(s.position))
        throw std::invalid_argument(name + "position must be finite");
    if (!finite3(s.direction) || glm::length(s.direction) < 1e-9)
        throw std::invalid_argument(name + "direction must be finite and non-zero");
    if (!(s.frustumDeg > 0.0 && s.frustumDeg <= 90.0))
        throw std::invalid_argument(name + "frustumDeg must be in (0, 90], got " +
                                    std::to_string(s.frustumDeg));
    if (!finite3(s.color) || s.color.x < 0.0f || s.color.y < 0.0f || s.color.z < 0.0f)
        throw std::invalid_argument(name + "color must be finite and >= 0");
    if (!(std::isfinite(s.intensity) && s.intensity >= 0.0f))
        throw std::invalid_argument(name + "intensity must be finite and >= 0");
    const double brightest = std::max({s.color.x, s.color.y, s.color.z}) * static_cast<double>(s.intensity);
    if (!(brightest <= MAX_SPOT_INTENSITY))
        throw std::invalid_argument(name + "color x intensity must be <= 1e12, got " +
                                    std::to_string(brightest));
    if (!(std::isfinite(s.range) && s.range > 0.0))
        throw std::invalid_argument(name + "range must be finite and > 0");
}

double moonIlluminanceLux(double phaseDeg) {
    if (!(phaseDeg >= 0.0 && phaseDeg <= 180.0))
        throw std::invalid_argument("moon phase angle must be in [0, 180] degrees, got " +
                                    std::to_string(phaseDeg));
    const double m = -12.73 + 0.026 * phaseDeg + 4e-9 * std::pow(phaseDeg, 4.0);
    constexpr double LUX_PER_FOOT_CANDLE = 10.764;
    return std::pow(10.0, -0.4 * (m + 16.57)) * LUX_PER_FOOT_CANDLE;
}

LightingDesc moonlit(LightingDesc l, const glm::dvec3& moonDirection, double phaseDeg) {
    const double len = glm::length(moonDirection);
    if (!(std::isfinite(len) && len > 1e-9))
        throw std::invalid_argument("moon direction must be finite and non-zero");
    const double scale = moonIlluminanceLux(phaseDeg) / SUN_ILLUMINANCE_LUX;
    l.sunDirection = moonDirection / len;
    l.sunIntensity = static_cast<float>(l.sunIntensity * scale);
    if (l.sky == LightingDesc::Sky::Gradient) // the physical sky already follows sunIntensity
        l.skyIntensity = static_cast<float>(l.skyIntensity * scale);
    if (l.environment) { // a photographed sky, dimmed as the Moon lights it (its own sun becomes the Moon)
        auto map = std::make_shared<EnvironmentMap>(*l.environment);
        map->intensity = static_cast<float>(map->intensity * scale);
        l.environment = std::move(map);
    }
    if (l.fogColor)
        *l.fogColor *= static_cast<float>(scale);
    return l;
}

LightingDesc exposed(LightingDesc l, double ev) {
    if (!(std::isfinite(ev) && std::abs(ev) <= 40.0))
        throw std::invalid_argument("exposure must be finite and within +-40 stops, got " +
                                    std::to_string(ev));
    const float scale = static_cast<float>(std::exp2(ev));
    l.sunIntensity *= scale;
    if (l.sky == LightingDesc::Sky::Gradient)
        l.skyIntensity *= scale;
    if (l.environment) {
        auto map = std::make_shared<EnvironmentMap>(*l.environment);
        map->intensity *= scale;
        l.environment = std::move(map);
    }
    if (l.fogColor)
        *l.fogColor *= scale;
    return l;
}

double spotFalloff(double theta, double frustum) {
    return std::clamp(frustum / std::max(theta, 0.5 * frustum) - 1.0, 0.0, 1.0);
}

glm::dvec3 spotIrradiance(const SpotLight& s, const glm::dvec3& p) {
    const glm::dvec3 toPoint = p - s.position;
    const double d = glm::length(toPoint);
    if (!(d < s.range))
        return glm::dvec3(0.0);
    const glm::dvec3 axis = glm::normalize(s.direction);
    const double c = d > 0.0 ? glm::dot(axis, toPoint / d) : 1.0;
    const double theta = std::acos(std::clamp(c, -1.0, 1.0));
    const double q = d / s.range, q2 = q * q;
    const double window = (1.0 - q2 * q2) * (1.0 - q2 * q2);
    const double r = std::max(d, SPOT_MIN_DISTANCE);
    return glm::dvec3(s.color) *
           (static_cast<double>(s.intensity) * spotFalloff(theta, s.frustumDeg * std::numbers::pi / 180.0) *
            window / (r * r));
}

bool spotConeInterval(const SpotLight& spot, const glm::dvec3& origin, const glm::dvec3& dir, double& t0,
                      double& t1) {
    // From the ray's point nearest the apex (t = shift), as spot.glsl must in float.
    const double shift = -glm::dot(origin - spot.position, dir);
    const glm::dvec3 w = origin - spot.position + shift * dir;
    const double disc = spot.range * spot.range - glm::dot(w, w);
    if (disc <= 0.0)
        return false;
    const double s = std::sqrt(disc);
    t0 = std::max(t0 - shift, -s);
    t1 = std::min(t1 - shift, s);
    if (!(t0 < t1))
        return false;
    const glm::dvec3 axis = glm::normalize(spot.direction);
    const double cosF = std::cos(spot.frustumDeg * std::numbers::pi / 180.0);
    const double da = glm::dot(dir, axis), wa = glm::dot(w, axis), k2 = cosF * cosF;
    const double a = da * da - k2, bq = 2.0 * da * wa, c = wa * wa - k2 * glm::dot(w, w);
    // The crossings (t1 where there is none), clamped into [t0, t1] and sorted: the ray between consecutive
    // ones is wholly in or out.
    double r[3] = {t1, t1, t1};
    const double qd = bq * bq - 4.0 * a * c;
    if (std::abs(a) > 1e-6 && qd >= 0.0) { // Numerical Recipes' form: no cancellation
        const double q = -0.5 * (bq + std::copysign(std::sqrt(qd), bq));
        if (q != 0.0) {
            r[0] = q / a;
            r[1] = c / q;
        }
    } else if (std::abs(a) <= 1e-6 && bq != 0.0) {
        r[0] = -c / bq;
    }
    if (da != 0.0)
        r[2] = -wa / da;
    for (double& x : r)
        x = std::clamp(x, t0, t1);
    std::sort(std::begin(r), std::end(r));
    const double from[4] = {t0, r[0], r[1], r[2]}, to[4] = {r[0], r[1], r[2], t1};
    double lo = t1, hi = t0;
    for (int j = 0; j < 4; ++j) {
        if (!(to[j] > from[j]))
            continue;
        const glm::dvec3 p = w + 0.5 * (from[j] + to[j]) * dir;
        const double pa = glm::dot(p, axis);
        if (pa >= 0.0 && pa * pa >= k2 * glm::dot(p, p)) {
            lo = std::min(lo, from[j]);
            hi = std::max(hi, to[j]);
        }
    }
    t0 = lo + shift;
    t1 = hi + shift;
    return lo < hi;
}

glm::dvec3 spotInScatter(const SpotLight& spot, const LightingDesc& l, const glm::dvec3& eye,
                         const glm::dvec3& dir, double tMax, int samples) {
    double t0 = 0.0, t1 = tMax;
    if (samples <= 0 || l.fogDensity <= 0.0f || !spotConeInterval(spot, eye, dir, t0, t1))
        return glm::dvec3(0.0);
    const glm::dvec3 c = spot.position - eye;
    const glm::dvec3 axis = glm::normalize(spot.direction);
    const double frustum = spot.frustumDeg * std::numbers::pi / 180.0, g = SPOT_FOG_PHASE_G;
    const double delta = glm::dot(c, dir);
    const double big = std::max(glm::length(c - delta * dir), SPOT_MIN_DISTANCE);
    const double a0 = std::atan((t0 - delta) / big), a1 = std::atan((t1 - delta) / big);
    const double h = l.fogHeightFalloff;
    double sum = 0.0;
    for (int k = 0; k < samples; ++k) {
        const double a = a0 + (a1 - a0) * (k + 0.5) / samples;
        const double t = delta + big * std::tan(a);
        const glm::dvec3 toX = t * dir - c;
        const double d = glm::length(toX);
        const glm::dvec3 light = d > 0.0 ? toX / d : axis; // the light's direction of travel
        const double theta = std::acos(std::clamp(glm::dot(axis, light), -1.0, 1.0));
        const double r = std::max(d, SPOT_MIN_DISTANCE);
        const double jacobian = (big * big + (t - delta) * (t - delta)) / (big * r * r);
        const double hg = 1.0 + g * g - 2.0 * g * glm::dot(light, -dir);
        const double phase = (1.0 - g * g) / (4.0 * std::numbers::pi * hg * std::sqrt(hg));
        const double z = eye.z + t * dir.z;
        const double sigma = h > 0.0 ? l.fogDensity * std::exp(-z / h) : l.fogDensity;
        const double tau = fogOpticalDepth(eye.z, z, t, l) + fogOpticalDepth(spot.position.z, z, d, l);
        const double q = d / spot.range, q2 = q * q, window = std::max(1.0 - q2 * q2, 0.0);
        sum += sigma * phase * spotFalloff(theta, frustum) * window * window * std::exp(-tau) * jacobian;
    }
    return glm::dvec3(spot.color) *
           (SUN_DIFFUSE_SCALE * static_cast<double>(spot.intensity) * sum * (a1 - a0) / samples);
}

double foamAlpha(double height, const LightingDesc& l) {
    const double h0 = l.foamHeightStart, hmax = l.foamHeightFull;
    if (hmax <= h0)
        return height >= h0 ? 1.0 : 0.0;
    return std::clamp((height - h0) / (hmax - h0), 0.0, 1.0);
}

double foamAlphaJacobian(double jacobian, const LightingDesc& l) {
    const double j0 = l.foamJacobianThreshold;
    if (j0 <= 0.0)
        return 0.0;
    return std::clamp((j0 - jacobian) / j0, 0.0, 1.0);
}

std::vector<float> makeFogNoise(int size, uint32_t seed) {
    if (size < 4)
        throw std::invalid_argument("makeFogNoise(): size must be >= 4, got " + std::to_string(size));
    const size_t n = static_cast<size_t>(size);
    std::vector<float> v(n * n * n);
    // Octaves with lattice periods dividing `size` so the sum tiles; weights halve per octave.
    const int periods[3] = {std::max(size / 8, 1), std::max(size / 4, 2), std::max(size / 2, 4)};
    const double weights[3] = {1.0, 0.5, 0.25};
    for (int z = 0; z < size; ++z)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                double s = 0.0;
                for (int o = 0; o < 3; ++o) {
                    const double k = static_cast<double>(periods[o]) / size;
                    // A fractional shift per octave keeps the octaves' lattice zeros from coinciding.
                    const glm::dvec3 shift(0.31 + 0.17 * o, 0.53 + 0.11 * o, 0.71 + 0.07 * o);
                    s += weights[o] * periodicPerlin(glm::dvec3(x, y, z) * k + shift, periods[o],
                                                     seed + 101U * static_cast<uint32_t>(o));
                }
                v[(static_cast<size_t>(z) * n + y) * n + x] = static_cast<float>(s);
            }
    // Binomial (1,2,1)/4 blur along each axis, wrapping (as De Sylva's fog noise: Pascal-triangle blur,
    // mod-wrapped).
    std::vector<float> tmp(v.size());
    const size_t stride[3] = {1, n, n * n};
    for (int axis = 0; axis < 3; ++axis) {
        for (size_t i = 0; i < v.size(); ++i) {
            const size_t coord = (i / stride[axis]) % n;
            const size_t base = i - coord * stride[axis];
            const size_t prev = base + ((coord + n - 1) % n) * stride[axis];
            const size_t next = base + ((coord + 1) % n) * stride[axis];
            tmp[i] = 0.25f * v[prev] + 0.5f * v[i] + 0.25f * v[next];
        }
        v.swap(tmp);
    }
    normaliseToUnitRange(v);
    return v;
}

namespace {

/// Replaces each value by its rank (ties by index) through the normal quantile: a standard normal sample
/// whatever the shapes (foamCover's threshold needs that marginal).
void gaussianise(std::vector<float>& v) {
    std::vector<size_t> order(v.size());
    for (size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return v[a] < v[b]; });
    for (size_t k = 0; k < order.size(); ++k)
        v[order[k]] = static_cast<float>(
            normalQuantile((static_cast<double>(k) + 0.5) / static_cast<double>(order.size())));
}

/// Periodic fBm of `octaves` octaves of gradient noise with FOAM_STREAK_ASPECT times more cells across (y)
/// than along (x), the first octave `cells` cells along: streaks drawn out along x.
double streakNoise(const glm::dvec2& uv, int cells, int octaves, uint32_t seed) {
    double sum = 0.0, amplitude = 1.0;
    for (int o = 0; o < octaves; ++o) {
        const glm::ivec2 period(cells << o, FOAM_STREAK_ASPECT * (cells << o));
        sum += amplitude * periodicPerlin(glm::dvec3(uv * glm::dvec2(period), 0.5 + o),
                                          glm::ivec3(period, 64), seed + 31U * static_cast<uint32_t>(o));
        amplitude *= 0.6;
    }
    return sum;
}

/// A size x size pattern of value(uv) at the texel centres, gaussianised (the foam patterns' common frame).
template <class Value>
std::vector<float> normalPattern(const char* what, int size, Value value) {
    if (size < 8)
        throw std::invalid_argument(std::string(what) + "(): size must be >= 8, got " + std::to_string(size));
    std::vector<float> v(static_cast<size_t>(size) * size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            v[static_cast<size_t>(y) * size + x] =
                static_cast<float>(value(glm::dvec2((x + 0.5) / size, (y + 0.5) / size)));
    gaussianise(v);
    return v;
}

} // namespace

std::vector<float> makeFoamPattern(int size, uint32_t seed) {
    return normalPattern("makeFoamPattern", size, [seed](const glm::dvec2& uv) {
        // Lace: the walls between cellular (Worley 1996) bubbles at two scales, cells stretched along the
        // wind; the larger cells' centres open holes in the foam. Over them, fine streaks. Nothing coarser
        // than 1/16 of the tile: coarser shapes would repeat with the tile where its detail is not resolved
        // (a 7 m lattice over a wake from 600 m).
        const glm::dvec2 large = periodicWorley(uv, {20, 32}, seed + 7U);
        const glm::dvec2 small = periodicWorley(uv, {48, 64}, seed + 8U);
        const double hole = 1.0 - smoothstep(0.1, 0.45, large.x);
        const double lace = 1.0 - smoothstep(0.0, 0.15, large.y - large.x);
        const double film = 1.0 - smoothstep(0.0, 0.12, small.y - small.x);
        const double streaks = streakNoise(uv, 16, 2, seed);
        return 0.6 * streaks + 0.4 * lace + 0.2 * film - 0.35 * hole;
    });
}

std::vector<float> makeFoamStreaks(int size, uint32_t seed) {
    return normalPattern("makeFoamStreaks", size,
                         [seed](const glm::dvec2& uv) { return streakNoise(uv, 2, 5, seed); });
}

double normalCdf(double x) {
    // Abramowitz & Stegun, "Handbook of Mathematical Functions", 7.1.26: erf(z) = 1 - (a1 t + ... + a5 t^5)
    // e^(-z^2), t = 1 / (1 + p z), z >= 0, |error| <= 1.5e-7; Phi(x) = (1 + erf(x / sqrt 2)) / 2.
    const double z = std::abs(x) / std::numbers::sqrt2;
    const double t = 1.0 / (1.0 + ERF_AS_P * z);
    const double poly =
        t * (ERF_AS_A[0] + t * (ERF_AS_A[1] + t * (ERF_AS_A[2] + t * (ERF_AS_A[3] + t * ERF_AS_A[4]))));
    const double erf = 1.0 - poly * std::exp(-z * z);
    return 0.5 * (1.0 + (x < 0.0 ? -erf : erf));
}

double normalQuantile(double p) {
    // Phi^-1(p) = sqrt 2 erfinv(2p - 1), erfinv by M. Giles, "Approximating the erfinv function" (GPU
    // Computing Gems, 2011), its single-precision polynomials in w = -ln(1 - x^2): central (w < 5) and tail.
    const double x = 2.0 * std::clamp(p, FOAM_SHARE_MIN, 1.0 - FOAM_SHARE_MIN) - 1.0;
    double w = -std::log((1.0 - x) * (1.0 + x)), q;
    if (w < 5.0) {
        w -= 2.5;
        q = ERFINV_CENTRAL[0];
        for (int i = 1; i < 9; ++i)
            q = ERFINV_CENTRAL[i] + q * w;
    } else {
        w = std::sqrt(w) - 3.0;
        q = ERFINV_TAIL[0];
        for (int i = 1; i < 9; ++i)
            q = ERFINV_TAIL[i] + q * w;
    }
    return std::numbers::sqrt2 * q * x;
}

double foamCover(double mean, double variance, double share, double softness) {
    if (share <= 0.0)
        return 0.0;
    if (share >= 1.0)
        return 1.0;
    const double threshold = normalQuantile(1.0 - share) * std::sqrt(1.0 + softness);
    return normalCdf((mean - threshold) / std::sqrt(std::max(variance + softness, FOAM_MIN_VARIANCE)));
}

double meanFoamOpacity(double coverage) {
    // E over r ~ U(0, 1) of clamp((r - t0) / e, 0, 1), t0 = 1 - c (1 + e): with lo, hi = t0, t0 + e clamped
    // to [0, 1], the ramp's part inside plus the full part above it.
    const double c = std::clamp(coverage, 0.0, 1.0), e = FOAM_EDGE;
    const double t0 = 1.0 - c * (1.0 + e);
    const double lo = std::clamp(t0, 0.0, 1.0), hi = std::clamp(t0 + e, 0.0, 1.0);
    return (1.0 - hi) + ((hi - t0) * (hi - t0) - (lo - t0) * (lo - t0)) / (2.0 * e);
}

} // namespace pacifica::ocean
