// pacifica-bench-storms: what the effects system's CPU update costs under storms, with Google Benchmark --
// one frame's EffectsSystem::update() (events dispatched) when that frame brings `spawns` explosions to a
// system already holding 1024 (its cap: each spawn then drops the least visible), and with 1000 ships whose
// 1000 wakes the 256-wake cap sorts by visibility. The state is rebuilt outside the timing for every frame.
// `./pacifica bench storms [--benchmark_* options]`; docs/RELIABILITY.md ("Storms") has the figures.
#include "engine/Ecs.h"
#include "ocean/Effects.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <vector>

namespace {

using namespace pacifica;
using namespace pacifica::ocean;

struct Scene {
    ecs::Registry registry;
    ecs::EventQueue events;
    EffectsSystem effects{registry, events};
};

glm::dvec2 scattered(int k) {
    return {std::fmod(k * 37.0, 4000.0) - 2000.0, std::fmod(k * 91.0, 4000.0) - 2000.0};
}

void BM_ExplosionStormFrame(benchmark::State& state) {
    const int spawns = static_cast<int>(state.range(0));
    for (auto _ : state) {
        state.PauseTiming();
        auto scene = std::make_unique<Scene>();
        for (int k = 0; k < EffectsDesc{}.maxExplosions; ++k)
            scene->events.enqueue(SpawnExplosion{scattered(k), 0.0, 1.0 + k % 5});
        scene->events.dispatch();
        scene->effects.update(0.0, {0.0, 0.0, 300.0});
        for (int k = 0; k < spawns; ++k)
            scene->events.enqueue(SpawnExplosion{scattered(100000 + k), 0.5, 1.0 + k % 3});
        state.ResumeTiming();
        scene->events.dispatch();
        scene->effects.update(0.5, {0.0, 0.0, 300.0});
        benchmark::DoNotOptimize(scene->effects.counters().droppedExplosions);
        state.PauseTiming();
        scene.reset();
        state.ResumeTiming();
    }
    state.SetItemsProcessed(state.iterations() * spawns);
}

void BM_ShipStormFrame(benchmark::State& state) {
    Scene scene;
    std::vector<ecs::Entity> ships;
    for (int i = 0; i < 1000; ++i) {
        ships.push_back(scene.registry.create());
        scene.registry.emplace<Ship>(ships.back(), Ship{{(i % 40) * 100.0, (i / 40) * 100.0}, 60.0});
        scene.events.enqueue(AttachShipTrail{ships.back(), WakeParams{}});
    }
    double t = 0.0;
    for (auto _ : state) {
        t += 1.0 / 60.0;
        for (ecs::Entity s : ships)
            scene.registry.get<Ship>(s).position.x += 0.2;
        scene.events.dispatch();
        scene.effects.update(t, {0.0, 0.0, 300.0});
    }
    state.counters["wakes_dropped"] = scene.effects.counters().droppedWakes;
}

} // namespace

BENCHMARK(BM_ExplosionStormFrame)->Arg(167)->Arg(10000)->ArgName("spawns")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShipStormFrame)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
