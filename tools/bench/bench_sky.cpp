// pacifica-bench-sky: what the physical clear sky (ocean/Atmosphere.h) costs on the CPU, with Google
// Benchmark: precomputing its tables (once per haze, when a renderer first draws it) and one lat-long map
// (once per camera altitude level and sun direction) at each quality setting of ClearSkyQuality. The error
// of each setting is measured by test_atmosphere and listed beside these timings in docs/LOOK.md ("The
// clear sky"). `./pacifica bench sky [--benchmark_* options]`.
#include "ocean/Atmosphere.h"

#include <benchmark/benchmark.h>

#include <cmath>

namespace {

using pacifica::ocean::AtmosphereDesc;
using pacifica::ocean::ClearSky;
using pacifica::ocean::ClearSkyQuality;

/// The renderer's default atmosphere: Earth's with the default fog (3e-5 /m, 600 m) as its haze.
AtmosphereDesc defaultAir() {
    AtmosphereDesc a;
    a.hazeExtinction = 3.0e-5;
    a.hazeScaleHeight = 600.0;
    return a;
}

void tables(benchmark::State& state) {
    for (auto _ : state) {
        ClearSky sky(defaultAir());
        benchmark::DoNotOptimize(sky.transmittanceToSpace(0.0, 1.0));
    }
}

/// Arguments: map width, view steps, table azimuths (= elevations).
void skyMap(benchmark::State& state) {
    static const ClearSky sky(defaultAir());
    ClearSkyQuality q;
    q.mapWidth = static_cast<int>(state.range(0));
    q.viewSteps = static_cast<int>(state.range(1));
    q.tableAzimuths = q.tableElevations = static_cast<int>(state.range(2));
    const double el = 30.0 * M_PI / 180.0;
    const glm::dvec3 sun(std::cos(el), 0.0, std::sin(el));
    for (auto _ : state)
        benchmark::DoNotOptimize(sky.skyMap(1000.0, sun, q).rgb.data());
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
