// pacifica-bench-queries: what the sea's CPU height queries cost, with Google Benchmark -- points per second
// (items_per_second) of the Eulerian height for the octaves, Gerstner and FFT models, the FFT by its direct
// sum (the reference) and by the sampled tiles (FftSampled.h, bilinear and bicubic), and the FFT's sampling
// of every tile at one time. The error of each FFT variant is in docs/ACCURACY.md ("The FFT sea's CPU
// queries"). One thread, 4096 random points over +-5 km. `./pacifica bench queries [--benchmark_* options]`.
#include "ocean/FftSampled.h"
#include "ocean/GerstnerWaves.h"
#include "ocean/HeightOctaves.h"

#include <benchmark/benchmark.h>

#include <memory>
#include <random>
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

void BM_FftSampleTiles(benchmark::State& state) {
    double t = T;
    const auto threads = static_cast<unsigned>(state.range(0));
    for (auto _ : state) {
        FftSampledSea sampled(fftSea(), t, FftSampledSea::Interpolation::Bicubic, threads);
        benchmark::DoNotOptimize(sampled.displacementAt({0.0, 0.0}));
        t += 1.0 / 60.0;
    }
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
BENCHMARK_MAIN();
