// LandMask: is a point on land or on water? From GSHHG shorelines (Wessel & Smith 1996, "A global,
// self-consistent, hierarchical, high-resolution shoreline database", JGR 101(B4)), as Debian's gmt-gshhg-*
// packages ship them: GMT's binned netCDF files (binned_GSHHS_{c,l,i,h,f}.nc). Each bin stores the hierarchy
// level of its corners (0 ocean, 1 land, 2 lake, 3 island in a lake, 4 pond) and the shoreline pieces
// crossing it. A point's level is its bin's south-west corner level plus one per shoreline crossed on the
// straight way from that corner, so land is an odd level and water an even one (lakes are water).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace pacifica::recording {

class LandMask {
public:
    /// Reads one binned GSHHG file. Throws RecordingError naming the file if it cannot be read.
    explicit LandMask(const std::filesystem::path& file);

    /// The best installed resolution: $PACIFICA_GSHHG_DIR, then /usr/share/gmt-gshhg; intermediate, low,
    /// crude. nullopt when none is installed (callers then fall back to altitude-only rules, and say so).
    static std::optional<LandMask> loadDefault();

    /// True on land (levels 1 and 3), false on the sea, lakes and ponds. lon any, lat in [-90, 90].
    bool isLand(double latDeg, double lonDeg) const;
    const std::string& source() const { return mSource; }

private:
    std::string mSource;
    double mBinDeg = 0.0;
    int mNx = 0, mNy = 0;
    std::vector<int> mFirstSeg, mSegInfo, mSegStart;
    std::vector<short> mBinSegs, mBinInfo;
    std::vector<short> mDx,
        mDy; // unsigned 16-bit offsets from the bin's south-west corner (1/65535 of a bin)
};

} // namespace pacifica::recording
