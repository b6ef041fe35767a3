// LandMask: GSHHG binned shorelines through libnetcdf (LandMask.h). Variable names and bit layouts as GMT
// writes them (gmt_shore.c): bin corner levels in Embedded_node_levels_in_a_bin (south-west corner in bits
// 9-11), segment point count in bits 9+ and level in bits 6-8 of
// Embedded_npts_levels_exit_entry_for_a_segment.
#include "recording/LandMask.h"

#include "recording/Recording.h"

#include <netcdf.h>

#include <cmath>
#include <cstdlib>

namespace pacifica::recording {

namespace {

struct NcFile {
    int id = -1;
    ~NcFile() {
        if (id >= 0)
            nc_close(id);
    }
};

template <typename T, typename Getter>
std::vector<T> readVar(int nc, const char* name, size_t n, Getter get, const std::string& file) {
    int var = 0;
    std::vector<T> out(n);
    if (nc_inq_varid(nc, name, &var) != NC_NOERR || (n > 0 && get(nc, var, out.data()) != NC_NOERR))
        throw RecordingError(file, 0, name, "cannot read this GSHHG variable");
    return out;
}

int readScalar(int nc, const char* name, const std::string& file) {
    int var = 0, v = 0;
    size_t start = 0;
    if (nc_inq_varid(nc, name, &var) != NC_NOERR || nc_get_var1_int(nc, var, &start, &v) != NC_NOERR)
        throw RecordingError(file, 0, name, "cannot read this GSHHG variable");
    return v;
}

/// Whether segments (a, b) and (c, d) properly cross (shared end points do not count twice: half-open rule).
bool crosses(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy) {
    auto side = [](double px, double py, double qx, double qy, double rx, double ry) {
        return (qx - px) * (ry - py) - (qy - py) * (rx - px);
    };
    const double d1 = side(ax, ay, bx, by, cx, cy), d2 = side(ax, ay, bx, by, dx, dy);
    if ((d1 > 0.0) == (d2 > 0.0) || d1 == d2) // c and d on the same side (or both on the line)
        return false;
    const double d3 = side(cx, cy, dx, dy, ax, ay), d4 = side(cx, cy, dx, dy, bx, by);
    return (d3 > 0.0) != (d4 > 0.0) && d3 != d4;
}

} // namespace

LandMask::LandMask(const std::filesystem::path& file) : mSource(file.string()) {
    NcFile nc;
    if (nc_open(file.c_str(), NC_NOWRITE, &nc.id) != NC_NOERR)
        throw RecordingError(mSource, 0, "", "cannot open the GSHHG shoreline file");
    const int binMinutes = readScalar(nc.id, "Bin_size_in_minutes", mSource);
    mNx = readScalar(nc.id, "N_bins_in_360_longitude_range", mSource);
    mNy = readScalar(nc.id, "N_bins_in_180_degree_latitude_range", mSource);
    const int nBins = readScalar(nc.id, "N_bins_in_file", mSource);
    const int nSegs = readScalar(nc.id, "N_segments_in_file", mSource);
    const int nPts = readScalar(nc.id, "N_points_in_file", mSource);
    if (binMinutes <= 0 || mNx <= 0 || mNy <= 0 || nBins != mNx * mNy || nSegs < 0 || nPts < 0)
        throw RecordingError(mSource, 0, "", "inconsistent GSHHG bin layout");
    mBinDeg = binMinutes / 60.0;
    const auto n = [](int v) { return static_cast<size_t>(v); };
    mFirstSeg = readVar<int>(nc.id, "Id_of_first_segment_in_a_bin", n(nBins), nc_get_var_int, mSource);
    mBinSegs = readVar<short>(nc.id, "N_segments_in_a_bin", n(nBins), nc_get_var_short, mSource);
    mBinInfo = readVar<short>(nc.id, "Embedded_node_levels_in_a_bin", n(nBins), nc_get_var_short, mSource);
    mSegInfo = readVar<int>(nc.id, "Embedded_npts_levels_exit_entry_for_a_segment", n(nSegs), nc_get_var_int,
                            mSource);
    mSegStart = readVar<int>(nc.id, "Id_of_first_point_in_a_segment", n(nSegs), nc_get_var_int, mSource);
    mDx =
        readVar<short>(nc.id, "Relative_longitude_from_SW_corner_of_bin", n(nPts), nc_get_var_short, mSource);
    mDy =
        readVar<short>(nc.id, "Relative_latitude_from_SW_corner_of_bin", n(nPts), nc_get_var_short, mSource);
    for (int b = 0; b < nBins; ++b) // every index used later stays inside the arrays
        if (mFirstSeg[n(b)] < 0 || mBinSegs[n(b)] < 0 || mFirstSeg[n(b)] + mBinSegs[n(b)] > nSegs)
            throw RecordingError(mSource, 0, "",
                                 "GSHHG bin " + std::to_string(b) + " points outside the segments");
    for (int s = 0; s < nSegs; ++s) {
        const int count = mSegInfo[n(s)] >> 9;
        if (mSegStart[n(s)] < 0 || count < 0 || mSegStart[n(s)] + count > nPts)
            throw RecordingError(mSource, 0, "",
                                 "GSHHG segment " + std::to_string(s) + " points outside the points");
    }
}

std::optional<LandMask> LandMask::loadDefault() {
    std::vector<std::filesystem::path> dirs;
    if (const char* env = std::getenv("PACIFICA_GSHHG_DIR"))
        dirs.emplace_back(env);
    dirs.emplace_back("/usr/share/gmt-gshhg");
    for (const auto& dir : dirs)
        for (const char* res : {"i", "l", "c"}) {
            const std::filesystem::path f = dir / (std::string("binned_GSHHS_") + res + ".nc");
            std::error_code ec;
            if (std::filesystem::is_regular_file(f, ec))
                return LandMask(f);
        }
    return std::nullopt;
}

bool LandMask::isLand(double lat, double lon) const {
    if (!std::isfinite(lat) || !std::isfinite(lon))
        return false;
    lon = std::fmod(lon, 360.0);
    if (lon < 0.0)
        lon += 360.0;
    lat = std::clamp(lat, -90.0, 90.0);
    const int col = std::min(static_cast<int>(lon / mBinDeg), mNx - 1);
    const int row =
        std::clamp(static_cast<int>((90.0 - lat) / mBinDeg), 0, mNy - 1); // row 0 at the north pole
    const size_t b = static_cast<size_t>(row) * static_cast<size_t>(mNx) + static_cast<size_t>(col);
    const double lonSw = col * mBinDeg, latSw = 90.0 - (row + 1) * mBinDeg;
    // The point in the bin's 1/65535 units; the way from the south-west corner (0, 0) to it.
    const double px = (lon - lonSw) / mBinDeg * 65535.0, py = (lat - latSw) / mBinDeg * 65535.0;
    int level = (static_cast<unsigned short>(mBinInfo[b]) >> 9) & 7;
    const int first = mFirstSeg[b];
    for (int s = first; s < first + mBinSegs[b]; ++s) {
        const size_t start = static_cast<size_t>(mSegStart[static_cast<size_t>(s)]);
        const int count = mSegInfo[static_cast<size_t>(s)] >> 9;
        for (int k = 0; k + 1 < count; ++k) {
            const size_t i = start + static_cast<size_t>(k);
            const double ax = static_cast<unsigned short>(mDx[i]), ay = static_cast<unsigned short>(mDy[i]);
            const double bx = static_cast<unsigned short>(mDx[i + 1]),
                         by = static_cast<unsigned short>(mDy[i + 1]);
            if (crosses(0.0, 0.0, px, py, ax, ay, bx, by))
                ++level;
        }
    }
    return level % 2 == 1;
}

} // namespace pacifica::recording
