// pacifica-bench-queries: what the sea's CPU queries cost, with Google Benchmark -- points per second
// (items_per_second) of the Eulerian height for the octaves, Gerstner and FFT models point by point (the FFT
// by its direct sum, the reference, and by the sampled tiles, FftSampled.h, bilinear and bicubic), the FFT's
// sampling of every tile at one time, and the batched queries (SeaQuery.h) per model: heights alone or every
// field (height, normal, displacement, velocity), on 1 or 2 threads, without and with 8 explosions. The
// error of each path is in docs/ACCURACY.md ("The sea's CPU queries"). 4096 random points over +-5 km.
// `./pacifica bench queries [--benchmark_* options]`.
#include "ocean/FftSampled.h"
#include "ocean/GerstnerWaves.h"
#include "ocean/HeightOctaves.h"
#include "ocean/SeaQuery.h"

#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace pacifica::ocean;

constexpr double T = 12.5;

std::vector<glm::dvec2> points(size_t count) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-5000.0, 5000.0);
    std::vector<glm::dvec2> p(count);
    for (glm::dvec2& q : p)
        q = {u(rng), u(rng)};
    return p;
}

const FftCascades& fftSea() {
    static const FftCascades sea{FftDesc{}};
    return sea;
}

void heights(benchmark::State& state, const SurfaceModel& model, size_t count) {
    const std::vector<glm::dvec2> p = points(count);
    size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(model.heightAt(p[i], T));
        i = (i + 1) % p.size();
    }
    state.SetItemsProcessed(state.iterations());
}

void BM_OctavesHeight(benchmark::State& state) {
    static const HeightOctaves sea{HeightOctavesDesc{}};
    heights(state, sea, 4096);
}

void BM_GerstnerHeight(benchmark::State& state) {
    static const GerstnerWaves sea{GerstnerDesc{}};
    heights(state, sea, 4096);
}

void BM_FftDirectSumHeight(benchmark::State& state) {
    heights(state, fftSea(), 64);
}

void BM_FftSampledHeight(benchmark::State& state) {
    const auto interpolation = static_cast<FftSampledSea::Interpolation>(state.range(0));
    const FftSampledSea sampled(fftSea(), T, interpolation);
    const std::vector<glm::dvec2> p = points(4096);
    size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(sampled.heightAt(p[i]));
        i = (i + 1) % p.size();
    }
    state.SetItemsProcessed(state.iterations());
    state.SetLabel(interpolation == FftSampledSea::Interpolation::Bilinear ? "bilinear" : "bicubic");
}

/// Transforming every tile at a new time into the buffers it has (FftSampledSea::resample, as SeaQuery does
/// each step) on a pool of `threads`.
void BM_FftSampleTiles(benchmark::State& state) {
    double t = T;
    ThreadPool pool(static_cast<unsigned>(state.range(0)));
    FftSampledSea sampled(fftSea(), FftSampledSea::Interpolation::Bicubic, false);
    for (auto _ : state) {
        sampled.resample(t, pool.jobs());
        benchmark::DoNotOptimize(sampled.displacementAt({0.0, 0.0}));
        t += 1.0 / 60.0;
    }
}

/// Advancing the sampled tiles by their time derivative (FftSampledSea::extrapolateTo) instead of
/// transforming them again, one thread; and a transform with the derivative's two extra planes per tile.
void BM_FftExtrapolate(benchmark::State& state) {
    FftSampledSea sampled(fftSea(), FftSampledSea::Interpolation::Bicubic, true);
    sampled.resample(T);
    double t = T;
    for (auto _ : state) {
        t += 1.0 / 120.0;
        sampled.extrapolateTo(t);
        benchmark::DoNotOptimize(sampled.displacementAt({0.0, 0.0}));
    }
}

void BM_FftSampleTilesWithVelocity(benchmark::State& state) {
    FftSampledSea sampled(fftSea(), FftSampledSea::Interpolation::Bicubic, true);
    double t = T;
    for (auto _ : state) {
        sampled.resample(t);
        benchmark::DoNotOptimize(sampled.displacementAt({0.0, 0.0}));
        t += 1.0 / 60.0;
    }
}

/// SeaQuery over 4096 points a call. Arguments: model (0 octaves, 1 Gerstner, 2 FFT sampled bicubic), all
/// fields (0: heights alone), threads, explosions (0 or 8, within the points' square).
void BM_SeaQuery(benchmark::State& state) {
    const auto model = static_cast<SurfaceKind>(state.range(0));
    const bool all = state.range(1) != 0;
    const auto threads = static_cast<unsigned>(state.range(2));
    OceanDesc desc;
    desc.model = model;
    OceanComponent ocean;
    if (Status s = makeOcean(desc, ocean); !s) {
        state.SkipWithError(s.message.c_str());
        return;
    }
    std::vector<Explosion> explosions;
    for (int i = 0; i < state.range(3); ++i) {
        Explosion e;
        e.center = {-4000.0 + 1000.0 * i, 500.0 * (i % 3)};
        e.startTime = T - 5.0;
        e.params = explosionParams(1.0);
        explosions.push_back(e);
    }
    const unsigned fields = all ? SeaField::All : SeaField::Height;
    SeaQuery query;
    if (Status s = query.init(ocean, {.fields = fields, .threads = threads}); !s) {
        state.SkipWithError(s.message.c_str());
        return;
    }
    if (Status s = query.update(T, {explosions, {}}); !s) {
        state.SkipWithError(s.message.c_str());
        return;
    }
    const std::vector<glm::dvec2> p = points(4096);
    std::vector<SeaSample> out(p.size());
    std::vector<double> h(p.size());
    for (auto _ : state) {
        const Status s = all ? query.sample(p, out, fields) : query.heights(p, h);
        if (!s)
            state.SkipWithError(s.message.c_str());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(p.size()));
    state.SetLabel(std::string(toString(model)) + (all ? " all fields" : " heights") + ", " +
                   std::to_string(threads) + " thread(s), " + std::to_string(explosions.size()) +
                   " explosions");
}

} // namespace

BENCHMARK(BM_OctavesHeight);
BENCHMARK(BM_GerstnerHeight);
BENCHMARK(BM_FftDirectSumHeight);
BENCHMARK(BM_FftSampledHeight)->Arg(0)->Arg(1)->ArgName("interpolation");
BENCHMARK(BM_FftSampleTiles)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_FftExtrapolate)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FftSampleTilesWithVelocity)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SeaQuery)
    ->ArgsProduct({{0, 1, 2}, {0, 1}, {1, 2}, {0, 8}})
    ->ArgNames({"model", "all", "threads", "explosions"})
    ->UseRealTime();
BENCHMARK_MAIN();
