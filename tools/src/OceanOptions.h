// OceanOptions: the command-line knobs that select and tune the ocean (surface model, grid, quality), shared
// by `pacifica replay` and the benchmarks, mapped onto ocean::OceanDesc.
#pragma once

#include "ocean/Ocean.h"

#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace pacifica::tools {

struct OceanOptions {
    std::string quality = "high"; ///< low | medium | high | reference (ocean/Presets.h); other knobs override
    std::string model = "octaves"; ///< octaves | gerstner | fft
    int rings = 0;                 ///< 0 = the default radial grid
    int segments = 0;
    double minRingPixels = -1.0; ///< --min-ring-pixels; < 0 = the preset's
    double steepness = -1.0;     ///< Gerstner steepness scale; < 0 = default
    std::string grid = "radial"; ///< radial | projected
    std::string vertexFilter =
        "bilinear";        ///< octaves: nearest | bilinear | hardware-bilinear | packed-4tap | trilinear
    bool combined = false; ///< octaves: sum the displaced octaves in a compute pass first (§18.2.5)
    bool noCull = false;   ///< disable the per-vertex frustum test (§18.2.5)
    bool forwardShading = false;     ///< light in the grids' fragment stage (OceanDesc::computeShading off)
    std::string shadeTiles = "auto"; ///< auto | on | off: compute shading by tiles (OceanDesc::shadeTiles)
    bool noViewSector = false;       ///< tessellate the full circle instead of the view sector
    int fftSize = 0;                 ///< 0 = default N
    int octaveCount = 0;             ///< octaves: how many of the preset's octaves to use (1..count); 0 = all
    int displacedOctaves = -1; ///< octaves: how many leading octaves displace vertices; < 0 = the preset's
    // FFT spectrum (ocean::FftDesc); unset = the FftDesc default.
    std::string sky;                        ///< physical | gradient; empty = default (physical)
    std::string fftSpectrum;                ///< phillips | jonswap; empty = default (JONSWAP)
    std::optional<double> seaState;         ///< --sea-state U10, m/s: every model's sea (ocean/SeaState.h)
    std::optional<int> beaufort;            ///< --beaufort N: the same from a Beaufort force
    std::optional<double> windSpeed;        ///< U10, m/s, (0, 60]
    std::optional<double> windDirectionDeg; ///< compass direction the wind blows toward (FFT and octaves)
    std::optional<double> fetch;            ///< metres, > 0 (JONSWAP)
    std::optional<double> choppiness;       ///< lambda, [0, 3]
    std::optional<double> fftTile;          ///< metres per FFT tile, > 0
    std::optional<int> fftCascades;         ///< FFT tiles, [1, FFT_MAX_CASCADES] (FftDesc::cascades)
    bool noFftMix = false;                  ///< one draw per FFT cascade (FftDesc::aperiodic off)
    /// octaves: painted height maps, one file per octave from octave 0 (the swell) on (ImageInputs.h)
    std::vector<std::string> heightMaps;

    // Lighting (ocean::LightingDesc); unset = the LightingDesc default.
    std::optional<double> sunElevationDeg; ///< degrees above the horizon, [-90, 90]
    std::optional<double> sunAzimuthDeg;   ///< compass degrees clockwise from north, [0, 360)
    std::optional<double> sunIntensity, skyIntensity;
    std::optional<double> fogDensity;       ///< 1/m at sea level
    std::optional<double> fogHeightFalloff; ///< scale height, m (0 = uniform)
    std::optional<double> fogNoise;         ///< [0, 1]
    std::string fogColor;                   ///< "R,G,B" scene-linear; empty = the sky's horizon
    std::string waterColor;                 ///< "R,G,B" scene-linear; empty = DEEP_WATER_COLOR
    std::optional<double> foamHeightStart, foamHeightFull, foamJacobian, foamIntensity;
    std::optional<double> normalTilt; ///< [0, 1]
    std::optional<double> subsurface; ///< [0, 10]
    /// A moonlit night (ocean::moonlit): the moon's elevation [-90, 90] and azimuth [0, 360) in degrees and
    /// its phase angle [0, 180] (0 full); applied after the other lighting options (they scale daylight).
    std::optional<double> moonElevationDeg, moonAzimuthDeg, moonPhaseDeg;
};

/// Adds --model, --grid, --grid-rings, --grid-segments, --vertex-filter, --combined, --no-cull,
/// --forward-shading, --shade-tiles,
/// --no-view-sector, --gerstner-steepness, --octaves, --displaced-octaves, --sea-state, --beaufort,
/// --fft-size, --fft-spectrum,
/// --wind-speed, --wind-direction,
/// --fetch,
/// --choppiness, --fft-tile, --height-map and the lighting options --sun-elevation,
/// --sun-azimuth, --sun-intensity, --sky-intensity, --fog-density, --fog-height-falloff, --fog-noise,
/// --fog-color, --foam-height-start, --foam-height-full, --foam-jacobian, --foam-intensity, --normal-tilt,
/// --subsurface, --moon-elevation, --moon-azimuth, --moon-phase to a (sub)command.
void addOceanOptions(CLI::App& app, OceanOptions& options);

/// The OceanDesc the options describe; reads the --height-map files. Throws UsageError (Replay.h) naming
/// the option for bad values, std::runtime_error "FILE: ..." for a height map that cannot be used.
ocean::OceanDesc toOceanDesc(const OceanOptions& options);

/// Sun direction (towards the sun, world ENU: x east, y north, z up) from elevation above the horizon and
/// compass azimuth clockwise from north, degrees: (sin az cos el, cos az cos el, sin el).
glm::dvec3 sunDirectionFromAngles(double elevationDeg, double azimuthDeg);

} // namespace pacifica::tools
