// Atmosphere: a physically based clear sky, computed on the CPU (no GL) and handed to the renderer as a
// lat-long EnvironmentMap (Lighting.h), so the sky pass, the sea's reflections, the fog colour and the sky's
// irradiance all read one sky.
//
// The model is Bruneton & Neyret's precomputed atmospheric scattering ("Precomputed Atmospheric
// Scattering", EGSR 2008): a spherical Earth in a shell of air whose Rayleigh (molecules) and Mie (aerosols)
// scatterers thin exponentially with altitude, plus an ozone layer that absorbs. Two tables are precomputed
// once per AtmosphereDesc:
//   - the transmittance from any point to the top of the atmosphere (Bruneton 2008 sec. 4, in the
//     horizon-aware parametrisation of Bruneton's 2017 reimplementation, "Precomputed Atmospheric
//     Scattering: a New Implementation", functions GetTransmittanceTextureUvFromRMu and inverse);
//   - all orders of multiple scattering in the isotropic approximation of Hillaire, "A Scalable and
//     Production Ready Sky and Atmosphere Rendering Technique" (EGSR 2020), eqs. 5-9: the second order
//     L2 and the transfer factor f_ms of a unit isotropic source, summed as the geometric series
//     Psi_ms = L2 / (1 - f_ms).
// A view ray is then integrated (single scattering with the Rayleigh and Cornette-Shanks Mie phase
// functions, plus sigma_s Psi_ms: Hillaire 2020 eq. 10) per direction of a small sun-relative sky-view
// table, which is resampled into the lat-long map. Radiances are per unit solar irradiance at the top of the
// atmosphere (the renderer scales them by LightingDesc::sunIntensity), so the sky, the reddened sunlight and
// the sun's glitter share one exposure.
#pragma once

#include "ocean/Lighting.h"

#include <glm/glm.hpp>

#include <vector>

namespace pacifica::ocean {

/// The air. Defaults: Earth's, as in Bruneton 2017's demo (and Hillaire 2020, table 1): sea-level Rayleigh
/// scattering for 680/550/440 nm with an 8 km scale height, a 1.2 km Mie haze with asymmetry 0.8 and
/// single-scattering albedo 0.9, and ozone in a tent 10-40 km high peaking at 25 km.
struct AtmosphereDesc {
    double bottomRadius = 6360000.0;                             ///< m, the sea
    double topRadius = 6420000.0;                                ///< m, where the air ends (60 km up)
    glm::dvec3 rayleighScattering{5.802e-6, 13.558e-6, 33.1e-6}; ///< 1/m at sea level
    double rayleighScaleHeight = 8000.0;                         ///< m
    double mieScattering = 3.996e-6;                             ///< 1/m at sea level
    double mieExtinction = 4.40e-6;                              ///< 1/m at sea level
    double mieScaleHeight = 1200.0;                              ///< m
    double mieG = 0.8;                                           ///< Cornette-Shanks asymmetry
    glm::dvec3 ozoneAbsorption{0.650e-6, 1.881e-6, 0.085e-6};    ///< 1/m at the ozone peak
    double ozoneCenter = 25000.0;                                ///< m above the sea
    double ozoneHalfWidth = 15000.0;                             ///< m: zero outside centre +- this
    /// A low haze layer on top of the standard aerosols (the marine boundary layer): extinction at sea
    /// level (1/m, 0 = none) thinning as e^(-z / hazeScaleHeight), scattering hazeAlbedo of it with the Mie
    /// phase function. The renderer sets it from LightingDesc::fogDensity/fogHeightFalloff, so the sky
    /// holds the same haze that fogs the sea.
    double hazeExtinction = 0.0;
    double hazeScaleHeight = 600.0; ///< m
    double hazeAlbedo = 0.9;
    double groundAlbedo = 0.06;         ///< the sea's diffuse albedo
    double sunAngularRadius = 0.004675; ///< rad
};

/// The sky's resolution and integration: the quality knobs of the physical sky (`pacifica bench accuracy`).
struct ClearSkyQuality {
    int viewSteps = 32;     ///< integration steps along a view ray (quadratically spaced from the eye)
    int tableAzimuths = 64; ///< sky-view table: azimuths from the sun, 0..180 degrees (the sky is symmetric)
    int tableElevations = 64; ///< sky-view table: elevations, dense at the horizon
    int mapWidth = 512;       ///< the lat-long map handed to the renderer (height = width / 2)
};

/// Whether the physical sky holds the fog (LightingDesc::fogDensity, fogHeightFalloff) as its haze layer: a
/// layered fog of the sky's own colour. A uniform fog (H = 0) fogs the sea only; a fog of a given colour
/// (LightingDesc::fogColor) is mixed over the sky instead, since the air would scatter the sunlight's colour.
bool skyHoldsFog(const LightingDesc& lighting);
/// The atmosphere of a lighting: Earth's (AtmosphereDesc defaults), with the fog's layer as its haze when
/// skyHoldsFog(). What the renderer draws the physical sky with.
AtmosphereDesc atmosphereFor(const LightingDesc& lighting);

class ClearSky {
public:
    /// Precomputes the transmittance and multiple-scattering tables (tens of ms). Throws
    /// std::invalid_argument naming a bad field of `desc` (radii, non-finite or negative coefficients).
    explicit ClearSky(const AtmosphereDesc& desc = {});

    const AtmosphereDesc& desc() const { return mDesc; }

    /// Transmittance from altitude `altitude` (m above the sea) along a ray whose cosine with the local
    /// vertical is `mu` to the top of the atmosphere, read from the table (bilinear). 0 where the ray hits
    /// the sea.
    glm::dvec3 transmittanceToSpace(double altitude, double mu) const;
    /// The same by direct numerical integration with `steps` midpoint steps (the table's reference).
    glm::dvec3 transmittanceToSpaceIntegrated(double altitude, double mu, int steps) const;

    /// The sunlight reaching altitude `altitude` per unit solar irradiance: the transmittance toward the sun
    /// times the share of the sun's disc above the horizon there. `sun` is a unit vector, local ENU.
    glm::dvec3 sunlight(double altitude, const glm::dvec3& sun) const;

    /// Sky radiance seen from altitude `altitude` in unit direction `view` (local ENU) with the sun in unit
    /// direction `sun`, per unit solar irradiance: the light the air scatters toward the eye (single
    /// scattering + the multiple-scattering table), integrated over `steps` steps up to the top of the
    /// atmosphere or to the sea. Excludes the sun's disc and the surface's own radiance.
    glm::dvec3 radiance(double altitude, const glm::dvec3& view, const glm::dvec3& sun, int steps = 32) const;

    /// The sky seen from `altitude` as a lat-long map (EnvironmentMap layout, width quality.mapWidth, height
    /// half that), per unit solar irradiance (intensity 1). Directions below the sea's horizon hold the air
    /// between the eye and the sea (the sea itself is the renderer's). Built from a sun-relative sky-view
    /// table of quality.tableAzimuths x quality.tableElevations rays. Throws std::invalid_argument for a
    /// non-finite altitude, a zero sun vector or a quality field out of range.
    EnvironmentMap skyMap(double altitude, const glm::dvec3& sun, const ClearSkyQuality& quality = {}) const;

    /// The fog colour of the physical sky per azimuth (the layout of environmentHorizonBand(): `bins` bins of
    /// heading, bin i centred on u = (i + 0.5) / bins), per unit solar irradiance: the sky half a degree
    /// above the sea's horizon as seen from `altitude`, so the fogged far sea meets the sky there without a
    /// step. (A photographed map's band is a 0-20 degree mean because its horizon holds land and clutter.)
    std::vector<glm::vec3> horizonBand(double altitude, const glm::dvec3& sun, int bins,
                                       int steps = 32) const;

private:
    struct SkyView; // the sun-relative sky-view table of skyMap() (Atmosphere.cpp)
    void fillAboveHorizon(SkyView& view, const glm::dvec3& sun, int steps) const;
    void fillBelowHorizon(SkyView& view, const glm::dvec3& sun, int steps) const;
    static EnvironmentMap resample(const SkyView& view, const glm::dvec3& sun, int width);
    /// Optical depth from radius r over `distance` metres along a ray of cosine mu (midpoint rule).
    glm::dvec3 opticalDepth(double r, double mu, double distance, int steps) const;
    glm::dvec3 extinctionAt(double altitude) const;
    glm::dvec3 multipleScattering(double altitude, double muSun) const;
    void buildTransmittance();
    void buildMultipleScattering();

    AtmosphereDesc mDesc;
    std::vector<glm::dvec3> mTransmittance; ///< TRANSMITTANCE_MU x TRANSMITTANCE_R
    std::vector<glm::dvec3> mMultiple;      ///< MULTIPLE_MU x MULTIPLE_R
};

} // namespace pacifica::ocean
