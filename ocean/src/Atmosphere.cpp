// Atmosphere: the precomputed clear sky (Bruneton & Neyret 2008; multiple scattering after Hillaire 2020).
// See ocean/include/ocean/Atmosphere.h for the model and docs/LOOK.md ("The clear sky") for its tests.
#include "ocean/Atmosphere.h"

#include "ocean/OceanConstants.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pacifica::ocean {

namespace {

constexpr double PI = std::numbers::pi;
constexpr int TRANSMITTANCE_MU = 256, TRANSMITTANCE_R = 64; // Bruneton 2017's table size
constexpr int TRANSMITTANCE_STEPS = 200;
constexpr int MULTIPLE_MU = 32, MULTIPLE_R = 32; // Hillaire 2020, sec. 5.5: 32 x 32
constexpr int MULTIPLE_DIRECTIONS = 64, MULTIPLE_STEPS = 20;

double clamp01(double x) {
    return std::clamp(x, 0.0, 1.0);
}

double smoothstep(double e0, double e1, double x) {
    const double t = clamp01((x - e0) / (e1 - e0));
    return t * t * (3.0 - 2.0 * t);
}

/// Distance from radius r along a ray of cosine mu (with the vertical) to the sphere of radius `radius`
/// (outward root; the ray starts inside it). Bruneton 2017, DistanceToTopAtmosphereBoundary.
double distanceOut(double r, double mu, double radius) {
    const double disc = r * r * (mu * mu - 1.0) + radius * radius;
    return std::max(-r * mu + std::sqrt(std::max(disc, 0.0)), 0.0);
}

/// Distance to the sea sphere (the nearer root), for a ray that hits it (rayHitsGround).
double distanceToGround(double r, double mu, double bottom) {
    const double disc = r * r * (mu * mu - 1.0) + bottom * bottom;
    return std::max(-r * mu - std::sqrt(std::max(disc, 0.0)), 0.0);
}

bool rayHitsGround(double r, double mu, double bottom) {
    return mu < 0.0 && r * r * (mu * mu - 1.0) + bottom * bottom >= 0.0;
}

/// Bilinear read of a table of nx x ny nodes (x fastest) at continuous node coordinates (fx, fy).
glm::dvec3 bilinear(const std::vector<glm::dvec3>& t, int nx, int ny, double fx, double fy) {
    fx = std::clamp(fx, 0.0, static_cast<double>(nx - 1));
    fy = std::clamp(fy, 0.0, static_cast<double>(ny - 1));
    const int x0 = std::min(static_cast<int>(fx), nx - 2), y0 = std::min(static_cast<int>(fy), ny - 2);
    const double ax = fx - x0, ay = fy - y0;
    const auto at = [&](int x, int y) { return t[static_cast<size_t>(y) * nx + x]; };
    return (at(x0, y0) * (1.0 - ax) + at(x0 + 1, y0) * ax) * (1.0 - ay) +
           (at(x0, y0 + 1) * (1.0 - ax) + at(x0 + 1, y0 + 1) * ax) * ay;
}

/// Rayleigh phase function, 3 (1 + nu^2) / (16 pi).
double rayleighPhase(double nu) {
    return 3.0 / (16.0 * PI) * (1.0 + nu * nu);
}

/// Cornette-Shanks phase function (Bruneton 2008 eq. 4, after Cornette & Shanks 1992).
double miePhase(double g, double nu) {
    const double k = 3.0 / (8.0 * PI) * (1.0 - g * g) / (2.0 + g * g);
    return k * (1.0 + nu * nu) / std::pow(1.0 + g * g - 2.0 * g * nu, 1.5);
}

void require(bool ok, const std::string& what) {
    if (!ok)
        throw std::invalid_argument("AtmosphereDesc." + what);
}

void validate(const AtmosphereDesc& d) {
    require(std::isfinite(d.bottomRadius) && d.bottomRadius > 0.0, "bottomRadius must be finite and > 0");
    require(std::isfinite(d.topRadius) && d.topRadius > d.bottomRadius, "topRadius must be > bottomRadius");
    for (int c = 0; c < 3; ++c) {
        require(std::isfinite(d.rayleighScattering[c]) && d.rayleighScattering[c] >= 0.0,
                "rayleighScattering must be finite and >= 0");
        require(std::isfinite(d.ozoneAbsorption[c]) && d.ozoneAbsorption[c] >= 0.0,
                "ozoneAbsorption must be finite and >= 0");
    }
    require(std::isfinite(d.rayleighScaleHeight) && d.rayleighScaleHeight > 0.0,
            "rayleighScaleHeight must be finite and > 0");
    require(std::isfinite(d.mieScaleHeight) && d.mieScaleHeight > 0.0,
            "mieScaleHeight must be finite and > 0");
    require(std::isfinite(d.mieScattering) && d.mieScattering >= 0.0,
            "mieScattering must be finite and >= 0");
    require(std::isfinite(d.mieExtinction) && d.mieExtinction >= d.mieScattering,
            "mieExtinction must be finite and >= mieScattering");
    require(std::isfinite(d.mieG) && std::abs(d.mieG) < 1.0, "mieG must lie in (-1, 1)");
    require(std::isfinite(d.ozoneCenter) && std::isfinite(d.ozoneHalfWidth) && d.ozoneHalfWidth > 0.0,
            "ozoneCenter/ozoneHalfWidth must be finite, the half width > 0");
    require(std::isfinite(d.hazeExtinction) && d.hazeExtinction >= 0.0,
            "hazeExtinction must be finite and >= 0");
    require(std::isfinite(d.hazeScaleHeight) && d.hazeScaleHeight > 0.0,
            "hazeScaleHeight must be finite and > 0");
    require(std::isfinite(d.hazeAlbedo) && d.hazeAlbedo >= 0.0 && d.hazeAlbedo <= 1.0,
            "hazeAlbedo must lie in [0, 1]");
    require(std::isfinite(d.groundAlbedo) && d.groundAlbedo >= 0.0 && d.groundAlbedo <= 1.0,
            "groundAlbedo must lie in [0, 1]");
    require(std::isfinite(d.sunAngularRadius) && d.sunAngularRadius > 0.0 && d.sunAngularRadius < 0.1,
            "sunAngularRadius must lie in (0, 0.1) rad");
}

/// The scatterers' densities at an altitude (m): Rayleigh and Mie e^(-z/H), ozone a tent.
/// `mie` and `mieExtinction` are the aerosols' (standard and haze together) scattering and extinction
/// coefficients, 1/m.
struct Density {
    double rayleigh, mie, mieExtinction, ozone;
};
Density densityAt(const AtmosphereDesc& d, double z) {
    z = std::max(z, 0.0);
    const double aerosol = std::exp(-z / d.mieScaleHeight);
    const double haze = d.hazeExtinction > 0.0 ? d.hazeExtinction * std::exp(-z / d.hazeScaleHeight) : 0.0;
    return {std::exp(-z / d.rayleighScaleHeight), d.mieScattering * aerosol + d.hazeAlbedo * haze,
            d.mieExtinction * aerosol + haze,
            std::max(0.0, 1.0 - std::abs(z - d.ozoneCenter) / d.ozoneHalfWidth)};
}

/// Horizon-aware table coordinates in [0, 1]^2 of (r, mu) (Bruneton 2017, GetTransmittanceTextureUvFromRMu):
/// x_mu the distance to the top between its least and largest values at r, x_r = rho / H.
glm::dvec2 transmittanceCoords(const AtmosphereDesc& d, double r, double mu) {
    const double H = std::sqrt(d.topRadius * d.topRadius - d.bottomRadius * d.bottomRadius);
    const double rho = std::sqrt(std::max(r * r - d.bottomRadius * d.bottomRadius, 0.0));
    const double dist = distanceOut(r, mu, d.topRadius);
    const double dMin = d.topRadius - r, dMax = rho + H;
    return {dMax > dMin ? (dist - dMin) / (dMax - dMin) : 0.0, rho / H};
}

} // namespace

bool skyHoldsFog(const LightingDesc& l) {
    return l.fogHeightFalloff > 0.0f && !l.fogColor;
}

AtmosphereDesc atmosphereFor(const LightingDesc& l) {
    AtmosphereDesc a;
    if (skyHoldsFog(l)) {
        a.hazeExtinction = l.fogDensity;
        a.hazeScaleHeight = l.fogHeightFalloff;
    }
    return a;
}

ClearSky::ClearSky(const AtmosphereDesc& desc) : mDesc(desc) {
    validate(mDesc);
    buildTransmittance();
    buildMultipleScattering();
}

glm::dvec3 ClearSky::extinctionAt(double altitude) const {
    const Density rho = densityAt(mDesc, altitude);
    return mDesc.rayleighScattering * rho.rayleigh + glm::dvec3(rho.mieExtinction) +
           mDesc.ozoneAbsorption * rho.ozone;
}

glm::dvec3 ClearSky::transmittanceToSpaceIntegrated(double altitude, double mu, int steps) const {
    const double r = mDesc.bottomRadius + std::max(altitude, 0.0);
    mu = std::clamp(mu, -1.0, 1.0);
    if (rayHitsGround(r, mu, mDesc.bottomRadius))
        return glm::dvec3(0.0);
    return glm::exp(-opticalDepth(r, mu, distanceOut(r, mu, mDesc.topRadius), steps));
}

glm::dvec3 ClearSky::opticalDepth(double r, double mu, double distance, int steps) const {
    const double dt = distance / steps;
    glm::dvec3 depth(0.0);
    for (int i = 0; i < steps; ++i) { // midpoint rule; altitude along the ray from the law of cosines
        const double t = (i + 0.5) * dt;
        const double rt = std::sqrt(t * t + 2.0 * r * mu * t + r * r);
        depth += extinctionAt(rt - mDesc.bottomRadius) * dt;
    }
    return depth;
}

void ClearSky::buildTransmittance() {
    const AtmosphereDesc& d = mDesc;
    const double H = std::sqrt(d.topRadius * d.topRadius - d.bottomRadius * d.bottomRadius);
    mTransmittance.resize(static_cast<size_t>(TRANSMITTANCE_MU) * TRANSMITTANCE_R);
    for (int j = 0; j < TRANSMITTANCE_R; ++j)
        for (int i = 0; i < TRANSMITTANCE_MU; ++i) {
            // Inverse of transmittanceCoords (Bruneton 2017, GetRMuFromTransmittanceTextureUv).
            const double xMu = static_cast<double>(i) / (TRANSMITTANCE_MU - 1);
            const double rho = H * static_cast<double>(j) / (TRANSMITTANCE_R - 1);
            const double r = std::sqrt(rho * rho + d.bottomRadius * d.bottomRadius);
            const double dMin = d.topRadius - r, dMax = rho + H;
            const double dist = dMin + xMu * (dMax - dMin);
            const double mu =
                dist <= 0.0 ? 1.0
                            : std::clamp((H * H - rho * rho - dist * dist) / (2.0 * r * dist), -1.0, 1.0);
            // The horizon row (xMu = 1) is the ray tangent to the sea: integrate it, not "hits ground".
            const double muSafe = i == TRANSMITTANCE_MU - 1 ? mu + 1e-12 : mu;
            mTransmittance[static_cast<size_t>(j) * TRANSMITTANCE_MU + i] =
                transmittanceToSpaceIntegrated(r - d.bottomRadius, muSafe, TRANSMITTANCE_STEPS);
        }
}

namespace {
/// The table's transmittance at (r, mu), mu clamped to the horizon (used for the sun near the horizon,
/// whose visible share is applied separately).
glm::dvec3 tableTransmittance(const AtmosphereDesc& d, const std::vector<glm::dvec3>& table, double r,
                              double mu) {
    const glm::dvec2 c = transmittanceCoords(d, r, mu);
    return bilinear(table, TRANSMITTANCE_MU, TRANSMITTANCE_R, clamp01(c.x) * (TRANSMITTANCE_MU - 1),
                    clamp01(c.y) * (TRANSMITTANCE_R - 1));
}

/// The share of the sun's disc above the horizon at radius r for a sun of cosine muSun (Bruneton 2017,
/// GetSunVisibility: a smoothstep over the disc's angular diameter around the horizon's cosine).
double sunVisibility(const AtmosphereDesc& d, double r, double muSun) {
    const double sinH = std::min(d.bottomRadius / r, 1.0);
    const double cosH = -std::sqrt(std::max(1.0 - sinH * sinH, 0.0));
    return smoothstep(-sinH * d.sunAngularRadius, sinH * d.sunAngularRadius, muSun - cosH);
}
} // namespace

glm::dvec3 ClearSky::transmittanceToSpace(double altitude, double mu) const {
    const double r = mDesc.bottomRadius + std::clamp(altitude, 0.0, mDesc.topRadius - mDesc.bottomRadius);
    mu = std::clamp(mu, -1.0, 1.0);
    if (rayHitsGround(r, mu, mDesc.bottomRadius))
        return glm::dvec3(0.0);
    return tableTransmittance(mDesc, mTransmittance, r, mu);
}

glm::dvec3 ClearSky::sunlight(double altitude, const glm::dvec3& sun) const {
    const double r = mDesc.bottomRadius + std::clamp(altitude, 0.0, mDesc.topRadius - mDesc.bottomRadius);
    const double mu = std::clamp(sun.z / std::max(glm::length(sun), 1e-300), -1.0, 1.0);
    return tableTransmittance(mDesc, mTransmittance, r, mu) * sunVisibility(mDesc, r, mu);
}

void ClearSky::buildMultipleScattering() {
    // Hillaire 2020, sec. 5.5: at each (altitude, sun cosine) node, rays in MULTIPLE_DIRECTIONS directions
    // (a Fibonacci sphere: equal solid angles) gather the second order L2 (sunlight scattered once more,
    // isotropically, plus the sea's Lambertian bounce) and f_ms (a unit isotropic source's light scattered
    // back to the point); Psi_ms = L2 / (1 - f_ms) sums all orders (eq. 9).
    const AtmosphereDesc& d = mDesc;
    const double isotropic = 1.0 / (4.0 * PI);
    std::vector<glm::dvec3> dirs(MULTIPLE_DIRECTIONS);
    const double golden = PI * (3.0 - std::sqrt(5.0));
    for (int k = 0; k < MULTIPLE_DIRECTIONS; ++k) {
        const double z = 1.0 - (k + 0.5) * 2.0 / MULTIPLE_DIRECTIONS;
        const double s = std::sqrt(std::max(1.0 - z * z, 0.0));
        dirs[k] = {s * std::cos(golden * k), s * std::sin(golden * k), z};
    }
    mMultiple.resize(static_cast<size_t>(MULTIPLE_MU) * MULTIPLE_R);
    for (int j = 0; j < MULTIPLE_R; ++j)
        for (int i = 0; i < MULTIPLE_MU; ++i) {
            const double muSun = -1.0 + 2.0 * i / (MULTIPLE_MU - 1);
            const double altitude = (d.topRadius - d.bottomRadius) * j / (MULTIPLE_R - 1);
            const double r = d.bottomRadius + altitude;
            const glm::dvec3 sun(std::sqrt(std::max(1.0 - muSun * muSun, 0.0)), 0.0, muSun);
            const glm::dvec3 x(0.0, 0.0, r);
            glm::dvec3 l2(0.0), fms(0.0);
            for (const glm::dvec3& w : dirs) {
                const bool ground = rayHitsGround(r, w.z, d.bottomRadius);
                const double tMax =
                    ground ? distanceToGround(r, w.z, d.bottomRadius) : distanceOut(r, w.z, d.topRadius);
                glm::dvec3 tView(1.0), lum(0.0), transfer(0.0);
                for (int s = 0; s < MULTIPLE_STEPS; ++s) { // quadratic spacing, as in radiance()
                    const double u0 = static_cast<double>(s) / MULTIPLE_STEPS,
                                 u1 = static_cast<double>(s + 1) / MULTIPLE_STEPS;
                    const double dt = tMax * (u1 * u1 - u0 * u0);
                    const glm::dvec3 p = x + w * (tMax * 0.5 * (u0 * u0 + u1 * u1));
                    const double rp = glm::length(p);
                    const double zp = rp - d.bottomRadius;
                    const Density rho = densityAt(d, zp);
                    const glm::dvec3 scattering = d.rayleighScattering * rho.rayleigh + glm::dvec3(rho.mie);
                    const glm::dvec3 ext = extinctionAt(zp);
                    const double muSp = glm::dot(p, sun) / rp;
                    const glm::dvec3 sunT =
                        tableTransmittance(d, mTransmittance, rp, muSp) * sunVisibility(d, rp, muSp);
                    const glm::dvec3 stepT = glm::exp(-ext * dt);
                    // Energy-conserving step: integral of S e^(-ext t) over the step = S (1 - e^(-ext dt)) /
                    // ext (Hillaire 2015, "Physically Based and Unified Volumetric Rendering in Frostbite").
                    const glm::dvec3 absorbed = (glm::dvec3(1.0) - stepT) / glm::max(ext, glm::dvec3(1e-30));
                    lum += tView * scattering * sunT * isotropic * absorbed;
                    transfer += tView * scattering * absorbed;
                    tView *= stepT;
                }
                if (ground) { // the sea's Lambertian bounce of the sunlight reaching it
                    const glm::dvec3 g = x + w * tMax;
                    const double muG = glm::dot(glm::normalize(g), sun);
                    const glm::dvec3 sunT = tableTransmittance(d, mTransmittance, d.bottomRadius, muG) *
                                            sunVisibility(d, d.bottomRadius, muG);
                    lum += tView * sunT * std::max(muG, 0.0) * d.groundAlbedo / PI;
                }
                l2 += lum / static_cast<double>(MULTIPLE_DIRECTIONS); // integral of L p_u over the sphere
                fms += transfer / static_cast<double>(MULTIPLE_DIRECTIONS);
            }
            mMultiple[static_cast<size_t>(j) * MULTIPLE_MU + i] =
                l2 / (glm::dvec3(1.0) - glm::min(fms, glm::dvec3(0.999)));
        }
}

glm::dvec3 ClearSky::multipleScattering(double altitude, double muSun) const {
    const double fx = (std::clamp(muSun, -1.0, 1.0) + 1.0) * 0.5 * (MULTIPLE_MU - 1);
    const double fy =
        std::clamp(altitude / (mDesc.topRadius - mDesc.bottomRadius), 0.0, 1.0) * (MULTIPLE_R - 1);
    return bilinear(mMultiple, MULTIPLE_MU, MULTIPLE_R, fx, fy);
}

glm::dvec3 ClearSky::radiance(double altitude, const glm::dvec3& view, const glm::dvec3& sun,
                              int steps) const {
    // Single scattering (Bruneton 2008 eq. 6 without the sun's disc) plus sigma_s Psi_ms (Hillaire 2020
    // eq. 10), integrated step by step with the energy-conserving rule; steps are spaced quadratically from
    // the eye, t = tMax u^2, where the densest air (the haze, 1.2 km thick) lies for most rays.
    const AtmosphereDesc& d = mDesc;
    const double r = d.bottomRadius + std::clamp(altitude, 0.0, d.topRadius - d.bottomRadius - 1.0);
    const glm::dvec3 v = glm::normalize(view), s = glm::normalize(sun);
    const double mu = v.z;
    const bool ground = rayHitsGround(r, mu, d.bottomRadius);
    const double tMax = ground ? distanceToGround(r, mu, d.bottomRadius) : distanceOut(r, mu, d.topRadius);
    const double nu = glm::dot(v, s);
    const double pR = rayleighPhase(nu), pM = miePhase(d.mieG, nu);
    const glm::dvec3 x(0.0, 0.0, r);
    glm::dvec3 tView(1.0), lum(0.0);
    const int n = std::max(steps, 1);
    for (int i = 0; i < n; ++i) {
        const double u0 = static_cast<double>(i) / n, u1 = static_cast<double>(i + 1) / n;
        const double t = tMax * 0.5 * (u0 * u0 + u1 * u1), dt = tMax * (u1 * u1 - u0 * u0);
        const glm::dvec3 p = x + v * t;
        const double rp = glm::length(p);
        const double zp = rp - d.bottomRadius;
        const Density rho = densityAt(d, zp);
        const glm::dvec3 rayleigh = d.rayleighScattering * rho.rayleigh;
        const double mie = rho.mie;
        const glm::dvec3 ext = extinctionAt(zp);
        const double muSp = glm::dot(p, s) / rp;
        const glm::dvec3 sunT = tableTransmittance(d, mTransmittance, rp, muSp) * sunVisibility(d, rp, muSp);
        const glm::dvec3 source = (rayleigh * pR + glm::dvec3(mie * pM)) * sunT +
                                  (rayleigh + glm::dvec3(mie)) * multipleScattering(zp, muSp);
        const glm::dvec3 stepT = glm::exp(-ext * dt);
        lum += tView * source * (glm::dvec3(1.0) - stepT) / glm::max(ext, glm::dvec3(1e-30));
        tView *= stepT;
    }
    return lum;
}

std::vector<glm::vec3> ClearSky::horizonBand(double altitude, const glm::dvec3& sun, int bins,
                                             int steps) const {
    const double h = std::clamp(altitude, 0.0, mDesc.topRadius - mDesc.bottomRadius - 1.0);
    const double dip = std::acos(std::min(mDesc.bottomRadius / (mDesc.bottomRadius + h), 1.0));
    const double e = -dip + 0.5 * PI / 180.0;
    std::vector<glm::vec3> band(static_cast<size_t>(std::max(bins, 0)));
    for (int i = 0; i < bins; ++i) {
        const double heading = 2.0 * PI * ((i + 0.5) / bins - 0.5); // EnvironmentMap: u = 0.5 looks north
        const glm::dvec3 v(std::cos(e) * std::sin(heading), std::cos(e) * std::cos(heading), std::sin(e));
        band[static_cast<size_t>(i)] = glm::vec3(radiance(h, v, sun, steps));
    }
    return band;
}

namespace {
void validateSkyMapInput(double altitude, const glm::dvec3& sun, const ClearSkyQuality& q) {
    if (!std::isfinite(altitude))
        throw std::invalid_argument("ClearSky::skyMap(): altitude must be finite");
    if (!(glm::length(sun) > 0.0) || !std::isfinite(glm::length(sun)))
        throw std::invalid_argument("ClearSky::skyMap(): the sun direction must be finite and non-zero");
    if (q.viewSteps < 1 || q.viewSteps > 4096)
        throw std::invalid_argument("ClearSkyQuality.viewSteps must lie in [1, 4096]");
    if (q.tableAzimuths < 2 || q.tableAzimuths > 4096 || q.tableElevations < 4 || q.tableElevations > 4096)
        throw std::invalid_argument(
            "ClearSkyQuality.tableAzimuths must lie in [2, 4096] and tableElevations in [4, 4096]");
    if (q.mapWidth < 4 || q.mapWidth > 16384 || q.mapWidth % 2 != 0)
        throw std::invalid_argument("ClearSkyQuality.mapWidth must be even and lie in [4, 16384]");
}
} // namespace

/// The sun-relative sky-view table of one altitude: azimuths from the sun 0..180 degrees (the sky is
/// symmetric about the sun's vertical), elevations spaced quadratically away from the sea's horizon, which
/// lies dip = acos(R / (R + h)) below the horizontal (Hillaire 2020, sec. 5.3), so the bright band and the
/// aureole's foot get most rows. Rows [0, half) lie below the horizon, [half, ne) above it.
struct ClearSky::SkyView {
    double altitude, horizon, sunHeading;
    int na, ne, half;
    std::vector<glm::dvec3> table;

    SkyView(const AtmosphereDesc& d, double h, const glm::dvec3& sun, const ClearSkyQuality& q)
        : altitude(h), horizon(-std::acos(std::min(d.bottomRadius / (d.bottomRadius + h), 1.0))),
          sunHeading(std::abs(sun.x) + std::abs(sun.y) < 1e-12 ? 0.0 : std::atan2(sun.x, sun.y)),
          na(q.tableAzimuths), ne(q.tableElevations), half(q.tableElevations / 2),
          table(static_cast<size_t>(na) * ne) {}

    /// Elevation of the continuous row coordinate fy in [0, ne).
    double elevationOfRow(double fy) const {
        const double v = fy / ne;
        if (v >= 0.5) {
            const double l = (v - 0.5) * 2.0;
            return horizon + (0.5 * PI - horizon) * l * l;
        }
        const double l = (0.5 - v) * 2.0;
        return horizon - (0.5 * PI + horizon) * l * l;
    }
    /// The inverse, as a continuous node coordinate (node j at row coordinate j + 0.5).
    double rowOfElevation(double e) const {
        double v;
        if (e >= horizon)
            v = 0.5 + 0.5 * std::sqrt(clamp01((e - horizon) / (0.5 * PI - horizon)));
        else
            v = 0.5 - 0.5 * std::sqrt(clamp01((horizon - e) / (0.5 * PI + horizon)));
        return v * ne - 0.5;
    }
    /// The direction (ENU) of node (i, j).
    glm::dvec3 direction(int i, int j) const {
        const double heading = sunHeading + PI * i / (na - 1), elevation = elevationOfRow(j + 0.5);
        return {std::cos(elevation) * std::sin(heading), std::cos(elevation) * std::cos(heading),
                std::sin(elevation)};
    }
    glm::dvec3& at(int i, int j) { return table[static_cast<size_t>(j) * na + i]; }
};

void ClearSky::fillAboveHorizon(SkyView& view, const glm::dvec3& sun, int steps) const {
    for (int j = view.half; j < view.ne; ++j)
        for (int i = 0; i < view.na; ++i)
            view.at(i, j) = radiance(view.altitude, view.direction(i, j), sun, steps);
}

void ClearSky::fillBelowHorizon(SkyView& view, const glm::dvec3& sun, int steps) const {
    // The rays end on the sea: the air in between, plus the sea as a flat mirror with Schlick's Fresnel
    // (WATER_F0) reflecting the sky at the mirrored elevation (rows above the horizon, filled first). A
    // stand-in for what steep facets reflect downward and for the map's mip filter near the horizon; the
    // sea pass draws the sea itself.
    const double r = mDesc.bottomRadius + view.altitude;
    for (int j = 0; j < view.half; ++j)
        for (int i = 0; i < view.na; ++i) {
            const glm::dvec3 v = view.direction(i, j);
            const double tHit = distanceToGround(r, v.z, mDesc.bottomRadius);
            // The view ray's transmittance to the sea: T(eye -> space) / T(sea -> space) along the same line
            // cannot be used (the line is blocked), so integrate it (few steps: it is short or thin).
            const glm::dvec3 depth = opticalDepth(r, v.z, tHit, 16);
            const glm::dvec3 hitPoint = glm::dvec3(0.0, 0.0, r) + v * tHit;
            const double cosI = std::max(-glm::dot(v, glm::normalize(hitPoint)), 0.0);
            const double fresnel = WATER_F0 + (1.0 - WATER_F0) * std::pow(1.0 - cosI, 5.0);
            const double e = view.elevationOfRow(j + 0.5);
            const double mirrored = std::min(view.horizon + (view.horizon - e), 0.5 * PI);
            const glm::dvec3 sky =
                bilinear(view.table, view.na, view.ne, static_cast<double>(i),
                         std::max(view.rowOfElevation(mirrored), static_cast<double>(view.half)));
            view.at(i, j) = radiance(view.altitude, v, sun, steps) + glm::exp(-depth) * fresnel * sky;
        }
}

EnvironmentMap ClearSky::resample(const SkyView& view, const glm::dvec3& sun, int width) {
    EnvironmentMap map;
    map.width = width;
    map.height = width / 2;
    map.rgb.resize(static_cast<size_t>(map.width) * map.height * 3);
    const glm::dvec2 sunXY =
        std::abs(sun.x) + std::abs(sun.y) < 1e-12 ? glm::dvec2(0.0, 1.0) : glm::normalize(glm::dvec2(sun));
    for (int row = 0; row < map.height; ++row)
        for (int col = 0; col < map.width; ++col) {
            const glm::dvec3 dir = environmentDirection((col + 0.5) / map.width, (row + 0.5) / map.height);
            const double len = std::hypot(dir.x, dir.y);
            const double cosAz =
                len < 1e-12 ? 1.0 : std::clamp((dir.x * sunXY.x + dir.y * sunXY.y) / len, -1.0, 1.0);
            const double fx = std::acos(cosAz) / PI * (view.na - 1);
            const double fy = view.rowOfElevation(std::asin(std::clamp(dir.z, -1.0, 1.0)));
            const glm::dvec3 c = bilinear(view.table, view.na, view.ne, fx, fy);
            float* out = &map.rgb[(static_cast<size_t>(row) * map.width + col) * 3];
            for (int k = 0; k < 3; ++k)
                out[k] = static_cast<float>(std::max(c[k], 0.0));
        }
    return map;
}

EnvironmentMap ClearSky::skyMap(double altitude, const glm::dvec3& sun, const ClearSkyQuality& q) const {
    validateSkyMapInput(altitude, sun, q);
    const glm::dvec3 s = glm::normalize(sun);
    SkyView view(mDesc, std::clamp(altitude, 0.0, mDesc.topRadius - mDesc.bottomRadius - 1.0), s, q);
    fillAboveHorizon(view, s, q.viewSteps);
    fillBelowHorizon(view, s, q.viewSteps);
    return resample(view, s, q.mapWidth);
}

} // namespace pacifica::ocean
