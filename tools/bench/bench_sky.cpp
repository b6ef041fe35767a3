// pacifica-bench-sky: what the physical clear sky (ocean/Atmosphere.h) costs on the CPU, with Google
// Benchmark: precomputing its tables (once per haze, when a renderer first draws it) and one lat-long map
// (once per camera altitude level and sun direction) at each quality setting of ClearSkyQuality. The error
// of each setting is measured by test_atmosphere and listed beside these timings in docs/LOOK.md ("The
// clear sky"). `./pacifica bench sky [--benchmark_* options]`.
#include "ocean/Atmosphere.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace {

using pacifica::ocean::AtmosphereDesc;
using pacifica::ocean::ClearSky;
using pacifica::ocean::ClearSkyQuality;

/// The renderer's default atmosphere: Earth's with the default fog as its haze.
AtmosphereDesc defaultAir() {
    return pacifica::ocean::atmosphereFor({});
}

void tables(benchmark::State& state) {
    for (auto _ : state) {
        ClearSky sky(defaultAir());
        benchmark::DoNotOptimize(sky.transmittanceToSpace(0.0, 1.0));
    }
}

/// Relative error of `map` against `ref` over the upper hemisphere, on ref's pixels (nearest pixel of `map`,
/// which may be coarser): mean and max over pixels and channels.
std::pair<double, double> relativeError(const pacifica::ocean::EnvironmentMap& map,
                                        const pacifica::ocean::EnvironmentMap& ref) {
    double sum = 0.0, worst = 0.0;
    size_t n = 0;
    for (int row = 0; row < ref.height / 2; ++row)
        for (int col = 0; col < ref.width; ++col) {
            const size_t r = (static_cast<size_t>(row) * ref.width + col) * 3;
            const size_t m = (static_cast<size_t>(row * map.height / ref.height) * map.width +
                              static_cast<size_t>(col * map.width / ref.width)) *
                             3;
            for (size_t c = 0; c < 3; ++c) {
                const double e =
                    std::abs(map.rgb[m + c] - ref.rgb[r + c]) / std::max(double(ref.rgb[r + c]), 1e-9);
                sum += e;
                worst = std::max(worst, e);
                ++n;
            }
        }
    return {sum / static_cast<double>(n), worst};
}

/// Arguments: map width, view steps, table azimuths (= elevations). Counters: the map's mean and max
/// relative error against the reference setting (512 wide, 128 steps, 256 x 256 table) from 1 km with the
/// sun 30 degrees up.
void skyMap(benchmark::State& state) {
    static const ClearSky sky(defaultAir());
    const double el = 30.0 * M_PI / 180.0;
    const glm::dvec3 sun(std::cos(el), 0.0, std::sin(el));
    ClearSkyQuality ref;
    ref.viewSteps = 128;
    ref.tableAzimuths = ref.tableElevations = 256;
    static const pacifica::ocean::EnvironmentMap reference = sky.skyMap(1000.0, sun, ref);
    ClearSkyQuality q;
    q.mapWidth = static_cast<int>(state.range(0));
    q.viewSteps = static_cast<int>(state.range(1));
    q.tableAzimuths = q.tableElevations = static_cast<int>(state.range(2));
    for (auto _ : state)
        benchmark::DoNotOptimize(sky.skyMap(1000.0, sun, q).rgb.data());
    const auto [mean, worst] = relativeError(sky.skyMap(1000.0, sun, q), reference);
    state.counters["err_mean"] = mean;
    state.counters["err_max"] = worst;
}

} // namespace

BENCHMARK(tables)->Name("BM_ClearSkyTables")->Unit(benchmark::kMillisecond);
BENCHMARK(skyMap)
    ->Name("BM_ClearSkyMap")
    ->ArgNames({"width", "steps", "table"})
    ->Args({512, 32, 64}) // the default
    ->Args({512, 16, 64})
    ->Args({512, 32, 32})
    ->Args({256, 32, 64})
    ->Args({512, 128, 256}) // the reference the errors are measured against
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
