// OceanOptions: command-line ocean knobs -> OceanDesc.
#include "OceanOptions.h"

#include "ImageInputs.h"
#include "Replay.h"
#include "ocean/OceanConstants.h"
#include "ocean/Presets.h"
#include "ocean/SeaState.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace pacifica::tools {
namespace {

std::string text(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

/// A set option's value, checked to be finite and in [lo, hi] (either may be infinite); the message names
/// the option: "--fog-noise must be in [0, 1], got 3".
float checked(const std::optional<double>& v, const char* option, double lo, double hi,
              const char* unit = "") {
    if (std::isfinite(*v) && *v >= lo && *v <= hi)
        return static_cast<float>(*v);
    const std::string range = std::isinf(lo) && std::isinf(hi) ? "finite"
                              : std::isinf(hi)                 ? "finite and >= " + text(lo)
                                                               : "in [" + text(lo) + ", " + text(hi) + "]";
    throw UsageError(std::string(option) + " must be " + range + unit + ", got " + text(*v));
}

glm::vec3 parseColor(const std::string& value, const char* option = "--fog-color") {
    auto bad = [&] {
        return UsageError(std::string(option) +
                          ": expected R,G,B with finite scene-linear values >= 0 (e.g. "
                          "0.6,0.7,0.8), got '" +
                          value + "'");
    };
    glm::vec3 c(0.0f);
    size_t pos = 0;
    for (int i = 0; i < 3; ++i) {
        const size_t end = i < 2 ? value.find(',', pos) : value.size();
        if (end == std::string::npos)
            throw bad();
        const std::string field = value.substr(pos, end - pos);
        try {
            size_t used = 0;
            const double v = std::stod(field, &used);
            if (used != field.size() || !std::isfinite(v) || v < 0.0)
                throw bad();
            c[i] = static_cast<float>(v);
        } catch (const std::logic_error&) { // stod: not a number / out of range
            throw bad();
        }
        pos = end + 1;
    }
    return c;
}

/// --moon-*: a moonlit night (ocean::moonlit) from the daylight the other options describe.
void applyMoon(const OceanOptions& o, ocean::LightingDesc& l) {
    if (!o.moonElevationDeg && !o.moonAzimuthDeg && !o.moonPhaseDeg)
        return;
    if (!o.moonElevationDeg)
        throw UsageError("--moon-azimuth/--moon-phase need --moon-elevation");
    if (o.sunElevationDeg || o.sunAzimuthDeg)
        throw UsageError(
            "--moon-elevation cannot be combined with --sun-elevation/--sun-azimuth: on a moonlit "
            "night the moon is the light");
    const double el = checked(o.moonElevationDeg, "--moon-elevation", -90.0, 90.0, " degrees");
    double az = 180.0;
    if (o.moonAzimuthDeg) {
        az = *o.moonAzimuthDeg;
        if (!std::isfinite(az) || az < 0.0 || az >= 360.0)
            throw UsageError("--moon-azimuth must be in [0, 360) degrees clockwise from north, got " +
                             text(az));
    }
    const double phase =
        o.moonPhaseDeg ? checked(o.moonPhaseDeg, "--moon-phase", 0.0, 180.0, " degrees") : 0.0;
    l = ocean::moonlit(l, sunDirectionFromAngles(el, az), phase);
}

/// --sky, --sun-*, --sky-intensity, --fog-*, --foam-*, --normal-tilt onto LightingDesc; then --moon-*.
void applyLighting(const OceanOptions& o, ocean::LightingDesc& l) {
    constexpr double INF = std::numeric_limits<double>::infinity();
    if (o.sunElevationDeg || o.sunAzimuthDeg) {
        // The default direction's angles for whichever of the two is not given.
        const glm::dvec3 d = glm::normalize(l.sunDirection);
        const double rad = 180.0 / std::numbers::pi;
        double el = std::asin(d.z) * rad, az = std::atan2(d.x, d.y) * rad;
        if (o.sunElevationDeg)
            el = checked(o.sunElevationDeg, "--sun-elevation", -90.0, 90.0, " degrees");
        if (o.sunAzimuthDeg) {
            az = *o.sunAzimuthDeg;
            if (!std::isfinite(az) || az < 0.0 || az >= 360.0)
                throw UsageError("--sun-azimuth must be in [0, 360) degrees clockwise from north, got " +
                                 text(az));
        }
        l.sunDirection = sunDirectionFromAngles(el, az);
    }
    if (!o.sky.empty()) {
        if (o.sky == "physical")
            l.sky = ocean::LightingDesc::Sky::Physical;
        else if (o.sky == "gradient")
            l.sky = ocean::LightingDesc::Sky::Gradient;
        else
            throw UsageError("--sky must be physical or gradient; got '" + o.sky + "'");
    }
    if (o.sunIntensity)
        l.sunIntensity = checked(o.sunIntensity, "--sun-intensity", 0.0, INF);
    if (o.skyIntensity)
        l.skyIntensity = checked(o.skyIntensity, "--sky-intensity", 0.0, INF);
    if (o.fogDensity)
        l.fogDensity = checked(o.fogDensity, "--fog-density", 0.0, INF, " per metre");
    if (o.fogHeightFalloff)
        l.fogHeightFalloff = checked(o.fogHeightFalloff, "--fog-height-falloff", 0.0, INF, " metres");
    if (o.fogNoise)
        l.fogNoise = checked(o.fogNoise, "--fog-noise", 0.0, 1.0);
    if (!o.fogColor.empty())
        l.fogColor = parseColor(o.fogColor);
    if (!o.waterColor.empty())
        l.waterColor = parseColor(o.waterColor, "--water-color");
    if (o.foamHeightStart)
        l.foamHeightStart = checked(o.foamHeightStart, "--foam-height-start", -INF, INF, " metres");
    if (o.foamHeightFull)
        l.foamHeightFull = checked(o.foamHeightFull, "--foam-height-full", -INF, INF, " metres");
    if (l.foamHeightFull <= l.foamHeightStart)
        throw UsageError("--foam-height-full (" + text(l.foamHeightFull) +
                         " m) must be > --foam-height-start (" + text(l.foamHeightStart) + " m)");
    if (o.foamJacobian)
        l.foamJacobianThreshold = checked(o.foamJacobian, "--foam-jacobian", -INF, INF);
    if (o.foamIntensity)
        l.foamIntensity = checked(o.foamIntensity, "--foam-intensity", 0.0, INF);
    if (o.normalTilt)
        l.normalTilt = checked(o.normalTilt, "--normal-tilt", 0.0, 1.0);
    if (o.subsurface)
        l.subsurface = checked(o.subsurface, "--subsurface", 0.0, 10.0);
    applyMoon(o, l);
    try {
        ocean::validateLighting(l); // the checks above name the options; this is the library's own
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("lighting options: ") + e.what());
    }
}

/// --height-map FILE...: one file per octave from octave 0 on; all of one size and frame count (a still
/// map may join animated ones), which become HeightOctavesDesc.mapSize and .frames.
void applyHeightMaps(const OceanOptions& o, ocean::OceanDesc& d) {
    if (o.heightMaps.empty())
        return;
    if (d.model != ocean::SurfaceKind::Octaves)
        throw UsageError("--height-map applies to --model octaves only, got --model " + o.model);
    auto& oct = d.octaves;
    if (o.heightMaps.size() > oct.octaves.size())
        throw UsageError("--height-map given " + std::to_string(o.heightMaps.size()) +
                         " times; the octave sea of --quality " + o.quality + " has " +
                         std::to_string(oct.octaves.size()) + " octaves");
    oct.images.assign(oct.octaves.size(), {});
    int frames = 0;
    std::string first;
    for (size_t i = 0; i < o.heightMaps.size(); ++i) {
        ocean::OctaveImage img = loadHeightMap(o.heightMaps[i]);
        if (i == 0) {
            oct.mapSize = img.size;
            first = o.heightMaps[i];
        } else if (img.size != oct.mapSize) {
            throw UsageError("--height-map: every map must have one size: " + o.heightMaps[i] + " is " +
                             std::to_string(img.size) + " wide, " + first + " is " +
                             std::to_string(oct.mapSize));
        }
        if (img.frames > 1) {
            if (frames != 0 && img.frames != frames)
                throw UsageError("--height-map: animated maps must have one frame count: " + o.heightMaps[i] +
                                 " has " + std::to_string(img.frames) + ", another has " +
                                 std::to_string(frames));
            frames = img.frames;
        }
        oct.images[i] = std::move(img);
    }
    if (frames > 1)
        oct.frames = frames; // still maps repeat over any frame count; generated octaves keep theirs
}

} // namespace

glm::dvec3 sunDirectionFromAngles(double elevationDeg, double azimuthDeg) {
    const double el = elevationDeg * std::numbers::pi / 180.0, az = azimuthDeg * std::numbers::pi / 180.0;
    return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

namespace {
void addLightingOptions(CLI::App& app, OceanOptions& o);
} // namespace

void addOceanOptions(CLI::App& app, OceanOptions& o) {
    app.add_option("--quality", o.quality, "quality preset: low, medium, high, reference (docs/ACCURACY.md)")
        ->default_val("high");
    app.add_option("--model", o.model, "surface model: octaves (GPU Gems 2 height maps), gerstner, fft")
        ->default_val("octaves");
    app.add_option("--grid-rings", o.rings, "radial grid rings N (default 256)");
    app.add_option("--grid-segments", o.segments, "radial grid segments M (default 512)");
    app.add_option("--min-ring-pixels", o.minRingPixels,
                   "radial grid: skip rings closer than this many pixels on screen to the last drawn one "
                   "(0 = draw every ring; docs/PERFORMANCE.md)");
    app.add_option("--gerstner-steepness", o.steepness,
                   "Gerstner steepness scale (clamped to the fold limit)");
    app.add_option("--grid", o.grid, "grid: radial (GPU Gems 2 §18.2.3) or projected (Johanson 2004)")
        ->default_val("radial");
    app.add_option("--vertex-filter", o.vertexFilter,
                   "octave vertex filter: nearest, bilinear, hardware-bilinear, packed-4tap, trilinear")
        ->default_val("bilinear");
    app.add_flag("--combined", o.combined, "octaves: combine displaced octaves in a compute pass first");
    app.add_flag("--no-cull", o.noCull, "displace every vertex (no per-vertex frustum test)");
    app.add_flag(
        "--forward-shading", o.forwardShading,
        "light the sea in the grids' fragment stage instead of one compute pass (docs/PERFORMANCE.md)");
    app.add_option("--shade-tiles", o.shadeTiles,
                   "compute shading by 8x8 tiles sorted by what they hold: auto (on for software renderers "
                   "such as llvmpipe), on, off; the same pixels (docs/PERFORMANCE.md)")
        ->default_val("auto");
    app.add_flag("--no-view-sector", o.noViewSector, "tessellate the full circle, not just the view sector");
    app.add_option(
        "--octaves", o.octaveCount,
        "octaves: use the first N height-map octaves (GPU Gems 2 §18.2.1; default: all of the preset's)");
    app.add_option(
        "--displaced-octaves", o.displacedOctaves,
        "octaves: how many leading octaves displace the vertices (the rest only light; default 3)");
    app.add_option("--fft-size", o.fftSize, "FFT grid N (power of two, 16..1024)");
    app.add_option("--fft-spectrum", o.fftSpectrum, "FFT spectrum: phillips or jonswap (default jonswap)");
    app.add_option("--sea-state", o.seaState,
                   "wind speed U10 in m/s (1..30) setting every model's wave height, whitecap coverage "
                   "(Monahan) and sub-grid slopes (Cox-Munk): ocean/SeaState.h; other options override it");
    app.add_option("--beaufort", o.beaufort, "the same as --sea-state from a Beaufort force 1..11");
    app.add_option("--wind-speed", o.windSpeed, "FFT: wind speed U10, m/s (default 12)");
    app.add_option("--wind-direction", o.windDirectionDeg,
                   "FFT and octaves: compass direction the wind blows toward, degrees (default 60)");
    app.add_option("--fetch", o.fetch, "FFT (JONSWAP): fetch, m (default 200000)");
    app.add_option("--choppiness", o.choppiness,
                   "FFT: horizontal displacement scale lambda, 0..3 (default 1)");
    app.add_option("--fft-tile", o.fftTile, "FFT: metres per tile of the largest cascade (default 2000)");
    app.add_option("--fft-cascades", o.fftCascades,
                   "FFT: tiles of tile / 7.37^c, each its band of the spectrum, 1..4 (default 4)");
    app.add_flag(
        "--no-fft-mix", o.noFftMix,
        "FFT: one draw per cascade instead of two mixed so that no tile repeats (FftDesc::aperiodic)");
    app.add_option("--height-map", o.heightMaps,
                   "octaves: painted height map image for the next octave (repeat: octave 0, 1, ...); W x W, "
                   "or W x (W * frames) for an animated map")
        ->allow_extra_args(false);
    addLightingOptions(app, o);
}

namespace {

/// The lighting options of addOceanOptions (in --help after the surface's).
void addLightingOptions(CLI::App& app, OceanOptions& o) {
    app.add_option("--sun-elevation", o.sunElevationDeg, "sun elevation above the horizon, degrees");
    app.add_option("--sun-azimuth", o.sunAzimuthDeg, "sun azimuth, degrees clockwise from north");
    app.add_option("--sky", o.sky,
                   "sky without --env: physical (precomputed scattering, sunlight reddened by the air; the "
                   "default) or gradient (the older zenith-to-horizon gradient)");
    app.add_option("--sun-intensity", o.sunIntensity,
                   "the sun's irradiance, scene-linear; scales the physical sky too (default 20)");
    app.add_option("--sky-intensity", o.skyIntensity, "scale of the procedural sky (default 1)");
    app.add_option("--fog-density", o.fogDensity, "fog extinction at sea level, 1/m (default 3e-5)");
    app.add_option("--fog-height-falloff", o.fogHeightFalloff,
                   "fog scale height, m; 0 = uniform (default 600)");
    app.add_option("--fog-noise", o.fogNoise, "fog density noise amplitude, 0..1 (default 0.2)");
    app.add_option("--fog-color", o.fogColor, "fog colour R,G,B scene-linear (default: the sky's horizon)");
    app.add_option("--water-color", o.waterColor,
                   "water body colour R,G,B scene-linear, straight down (default 0.0045,0.019,0.032)");
    app.add_option("--foam-height-start", o.foamHeightStart, "foam starts at this height, m (default 1.6)");
    app.add_option("--foam-height-full", o.foamHeightFull, "foam is full at this height, m (default 3.2)");
    app.add_option("--foam-jacobian", o.foamJacobian, "folding foam below this Jacobian (default 0.3)");
    app.add_option("--foam-intensity", o.foamIntensity, "foam coverage scale; 0 = no foam (default 1)");
    app.add_option("--normal-tilt", o.normalTilt, "tilt of the lighting normal toward the viewer, 0..1");
    app.add_option("--subsurface", o.subsurface,
                   "scale of the sunlight scattered out of thin lit crests, 0..10; 0 = off (default 1)");
    app.add_option(
        "--moon-elevation", o.moonElevationDeg,
        "a moonlit night: the moon, at this elevation in degrees, lights the sea instead of the sun "
        "(Krisciunas & Schaefer's brightness; pair with --exposure)");
    app.add_option("--moon-azimuth", o.moonAzimuthDeg,
                   "moon azimuth, degrees clockwise from north (default 180)");
    app.add_option("--moon-phase", o.moonPhaseDeg,
                   "moon phase angle, degrees: 0 full .. 180 new (default 0)");
}

} // namespace

namespace {

double requireRange(const std::optional<double>& v, const char* option, double lo, double hi, bool loOpen) {
    const double x = *v;
    if (!std::isfinite(x) || x > hi || (loOpen ? x <= lo : x < lo)) {
        std::ostringstream m;
        m << option << " must be in " << (loOpen ? "(" : "[") << lo << ", " << hi << "], got " << x;
        throw UsageError(m.str());
    }
    return x;
}

/// --fft-spectrum, --wind-speed, --wind-direction, --fetch, --choppiness, --fft-tile (ocean/FftOcean.h
/// FftDesc; the wind direction also turns the octave maps' waves).
void applyFftSpectrum(const OceanOptions& o, ocean::OceanDesc& d) {
    if (!o.fftSpectrum.empty()) {
        if (o.fftSpectrum == "phillips")
            d.fft.spectrum = ocean::Spectrum::Phillips;
        else if (o.fftSpectrum == "jonswap")
            d.fft.spectrum = ocean::Spectrum::Jonswap;
        else
            throw UsageError("--fft-spectrum must be phillips or jonswap; got '" + o.fftSpectrum + "'");
    }
    if (o.windSpeed)
        d.fft.windSpeed = requireRange(o.windSpeed, "--wind-speed", 0.0, 60.0, true);
    if (o.windDirectionDeg) {
        d.fft.windDirectionDeg = requireRange(o.windDirectionDeg, "--wind-direction", -360.0, 360.0, false);
        d.octaves.windDirectionDeg = d.fft.windDirectionDeg;
    }
    if (o.fetch)
        d.fft.fetch = requireRange(o.fetch, "--fetch", 0.0, 1.0e7, true);
    if (o.choppiness)
        d.fft.choppiness = requireRange(o.choppiness, "--choppiness", 0.0, 3.0, false);
    if (o.fftTile)
        d.fft.tileSize = requireRange(o.fftTile, "--fft-tile", 0.0, 1.0e5, true);
}

/// --octaves, --displaced-octaves.
void applyOctaveCounts(const OceanOptions& o, ocean::OceanDesc& d) {
    if (o.octaveCount != 0) {
        const int available = static_cast<int>(d.octaves.octaves.size());
        if (o.octaveCount < 1 || o.octaveCount > available)
            throw UsageError("--octaves must be in [1, " + std::to_string(available) + "], got " +
                             std::to_string(o.octaveCount));
        d.octaves.octaves.resize(static_cast<size_t>(o.octaveCount));
        d.octaves.displacedOctaves = std::min(d.octaves.displacedOctaves, o.octaveCount);
    }
    if (o.displacedOctaves >= 0) {
        const int count = static_cast<int>(d.octaves.octaves.size());
        if (o.displacedOctaves > count)
            throw UsageError("--displaced-octaves must be in [0, " + std::to_string(count) + "], got " +
                             std::to_string(o.displacedOctaves));
        d.octaves.displacedOctaves = o.displacedOctaves;
    }
}

/// --fft-size, --fft-cascades, --no-fft-mix.
void applyFftMakeUp(const OceanOptions& o, ocean::OceanDesc& d) {
    if (o.fftSize != 0)
        d.fft.size = o.fftSize;
    if (o.fftCascades) {
        if (*o.fftCascades < 1 || *o.fftCascades > ocean::FFT_MAX_CASCADES)
            throw UsageError("--fft-cascades must be in [1, " + std::to_string(ocean::FFT_MAX_CASCADES) +
                             "], got " + std::to_string(*o.fftCascades));
        d.fft.cascades = *o.fftCascades;
    }
    if (o.noFftMix)
        d.fft.aperiodic = false;
}

/// --sea-state or --beaufort: ocean::applySeaState.
void applySeaStateOption(const OceanOptions& o, ocean::OceanDesc& d) {
    if (o.seaState && o.beaufort)
        throw UsageError("--sea-state and --beaufort both set the wind: give one");
    if (o.beaufort && (*o.beaufort < 1 || *o.beaufort > 11))
        throw UsageError("--beaufort must be a force in [1, 11], got " + std::to_string(*o.beaufort));
    if (o.seaState || o.beaufort) {
        const double u = o.seaState ? *o.seaState : ocean::beaufortWindSpeed(*o.beaufort);
        if (!(std::isfinite(u) && u >= ocean::SEA_STATE_MIN_WIND && u <= ocean::SEA_STATE_MAX_WIND))
            throw UsageError("--sea-state must be a wind speed in [1, 30] m/s, got " + std::to_string(u));
        d = ocean::applySeaState(d, {u, o.windDirectionDeg.value_or(d.octaves.windDirectionDeg)});
    }
}

} // namespace

ocean::OceanDesc toOceanDesc(const OceanOptions& o) {
    ocean::OceanDesc d;
    try {
        d = ocean::oceanPreset(ocean::parseQuality(o.quality));
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--quality: ") + e.what());
    }
    if (o.model == "octaves")
        d.model = ocean::SurfaceKind::Octaves;
    else if (o.model == "gerstner")
        d.model = ocean::SurfaceKind::Gerstner;
    else if (o.model == "fft")
        d.model = ocean::SurfaceKind::Fft;
    else
        throw UsageError("--model must be one of octaves, gerstner, fft; got '" + o.model + "'");
    if (o.grid == "radial")
        d.gridKind = ocean::GridKind::Radial;
    else if (o.grid == "projected")
        d.gridKind = ocean::GridKind::Projected;
    else
        throw UsageError("--grid must be radial or projected; got '" + o.grid + "'");
    bool filterFound = false;
    for (ocean::VertexFilter f :
         {ocean::VertexFilter::Nearest, ocean::VertexFilter::Bilinear, ocean::VertexFilter::HardwareBilinear,
          ocean::VertexFilter::Packed4Tap, ocean::VertexFilter::Trilinear}) {
        if (o.vertexFilter == ocean::toString(f)) {
            d.octaves.vertexFilter = f;
            filterFound = true;
        }
    }
    if (!filterFound)
        throw UsageError("--vertex-filter must be one of nearest, bilinear, hardware-bilinear, packed-4tap, "
                         "trilinear; got '" +
                         o.vertexFilter + "'");
    d.octaves.combinedDisplacement = o.combined;
    d.cullVertices = !o.noCull;
    if (o.forwardShading)
        d.computeShading = false;
    if (o.shadeTiles == "auto")
        d.shadeTiles = ocean::OceanDesc::ShadeTiles::Auto;
    else if (o.shadeTiles == "on")
        d.shadeTiles = ocean::OceanDesc::ShadeTiles::On;
    else if (o.shadeTiles == "off")
        d.shadeTiles = ocean::OceanDesc::ShadeTiles::Off;
    else
        throw UsageError("--shade-tiles must be auto, on or off; got '" + o.shadeTiles + "'");
    d.viewSector = !o.noViewSector;
    applyOctaveCounts(o, d);
    // The FFT sea's make-up before the sea state, whose foam thresholds are solved over that sea.
    applyFftMakeUp(o, d);
    applySeaStateOption(o, d);
    applyFftSpectrum(o, d);
    if (o.rings != 0)
        d.grid.rings = o.rings;
    if (o.segments != 0)
        d.grid.segments = o.segments;
    if (o.minRingPixels >= 0.0)
        d.grid.minRingPixels = o.minRingPixels;
    if (o.steepness >= 0.0)
        d.gerstner.steepnessScale = o.steepness;
    applyLighting(o, d.lighting);
    applyHeightMaps(o, d);
    try {
        ocean::RadialGrid::validate(d.grid); // here, so the message names the option
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--grid-rings/--grid-segments/--min-ring-pixels: ") + e.what());
    }
    return d;
}

} // namespace pacifica::tools
