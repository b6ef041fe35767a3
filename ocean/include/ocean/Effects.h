// Effects: local perturbations of the sea (GPU Gems 2 §18.3) — explosions and ship trails — as ECS
// components created by events. The GPU evaluates all of them once a frame into the effects field, a
// camera-centred clipmap (EffectFieldLayout) that every grid reads; the effects large on screen also get a
// secondary radial grid centred at the effect (§18.3) for their geometry. The CPU height queries include
// them: the analytic field (effectsAt, oceanHeightAt) or exactly what the GPU draws (sampleEffectField).
//
// STEP BY STEP (a host game)
//   1. pacifica::ocean::EffectsSystem effects(registry, events);   // subscribes to the spawn events
//   2. Explosions: events.enqueue(SpawnExplosion{{x, y}, time, strength});
//      Ships: give the ship entity a Ship component (update Ship::position every frame), then
//      events.enqueue(AttachShipTrail{shipEntity});
//   3. Every frame, after events.dispatch(): effects.update(simTime, cameraWorld); then
//      OceanRenderer::render() draws the active effects (nothing at all when there are none).
//   4. CPU queries including the effects: oceanHeightAt(registry, oceanEntity, {x, y}, simTime).
//   5. Subscribe to EffectEnded to learn when an effect faded out.
//
// The effects' data and maths (no ECS) are in EffectTypes.h; this header adds the events, the system that
// turns them into components, and the registry adapters.
#pragma once

#include "engine/Ecs.h"
#include "engine/Events.h"
#include "ocean/EffectTypes.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace pacifica::ocean {

// ---- Events ---------------------------------------------------------------------------------------------

struct SpawnExplosion {
    glm::dvec2 position{0.0};
    double time = 0.0;
    double strength = 1.0;
};
struct AttachShipTrail {
    ecs::Entity ship;
    WakeParams params;
};
/// An effect faded under EffectsDesc::endAmplitude (explosion entity destroyed; trail went quiet), or was
/// dropped by a cap (dropped = true).
struct EffectEnded {
    EffectKind kind = EffectKind::Explosion;
    ecs::Entity entity;
    double time = 0.0;
    bool dropped = false;
};

// ---- The system -----------------------------------------------------------------------------------------

/// Bounds on spawn data: a SpawnExplosion outside them is rejected (EffectCounters::rejected), like NaN.
inline constexpr double MAX_EFFECT_DISTANCE = 1e9;    ///< metres from the world origin, |x| and |y|
inline constexpr double MAX_EXPLOSION_STRENGTH = 1e6; ///< 1 = the nominal 500 kg charge
inline constexpr double MAX_SPAWN_LEAD = 3600.0;      ///< seconds a spawn may start after the frame

struct EffectsDesc {
    int maxExplosions = 1024;   ///< cap; policy: drop the least visible (see EffectsSystem)
    int maxWakes = 256;         ///< cap on trails drawn per frame; the least visible are skipped
    double endAmplitude = 0.01; ///< metres: an effect whose peak height falls below ends
};

/// Per-frame counters: what the effects cost and did. Render counters are filled by OceanRenderer
/// (OceanStats::effects), the rest by EffectsSystem::update().
struct EffectCounters {
    int activeExplosions = 0, activeWakes = 0;
    int spawned = 0;                             ///< explosions created this frame
    int ended = 0;                               ///< effects that faded out this frame
    int droppedExplosions = 0, droppedWakes = 0; ///< dropped by the caps this frame
    long long totalDroppedExplosions = 0;        ///< since the system started
    int rejected = 0; ///< spawn events with bad data (NaN, strength <= 0, beyond the MAX_* bounds)
};

/// Turns events into effect components, records ship paths, ends faded effects and applies the caps.
/// Cap policy: when a spawn would exceed maxExplosions, the least visible explosion (of the active ones and
/// the new one) is dropped: visibility = amplitude * radius / max(distance to camera, radius). Trails
/// beyond maxWakes are not drawn that frame (least visible first) and count as dropped. Bad spawn data
/// never throws: it is counted as rejected and logged.
class EffectsSystem {
public:
    EffectsSystem(ecs::Registry& registry, ecs::EventQueue& events, EffectsDesc desc = {});
    ~EffectsSystem();
    EffectsSystem(const EffectsSystem&) = delete;
    EffectsSystem& operator=(const EffectsSystem&) = delete;

    /// Once per frame after events.dispatch(): applies the queued spawns, records ship positions, ends
    /// faded effects (EffectEnded events), applies the caps.
    void update(double time, const glm::dvec3& cameraWorld);
    const EffectCounters& counters() const { return mCounters; }
    const EffectsDesc& desc() const { return mDesc; }

private:
    // The stages of update(), in order.
    void applySpawns(double time, const glm::dvec2& camera, double camHeight);
    void attachTrails();
    void endFadedExplosions(double time);
    void updateWakes(double time, const glm::dvec2& camera, double camHeight);

    ecs::Registry& mRegistry;
    ecs::EventQueue& mEvents;
    EffectsDesc mDesc;
    std::vector<SpawnExplosion> mPendingExplosions;
    std::vector<AttachShipTrail> mPendingTrails;
    ecs::EventQueue::SubscriptionId mSubExplosion = 0, mSubTrail = 0;
    EffectCounters mCounters;
    long long mTotalDropped = 0;
};

/// The effects step of a host's frame, the same in every host (replay, game, benches): step(t) moves the
/// ships it tracks to where their tracks put them at t, spawns the scheduled explosions whose time has come
/// (in time order), dispatches the event queue and updates the system. A host that moves its ships itself
/// (the game's world) adds none and calls step() after moving them. warmUp() steps the time before the first
/// frame, so that ships which sailed before it have their wakes.
class EffectsTimeline {
public:
    static constexpr double WARM_UP_STEP = 0.5; ///< s between warm-up steps (a wake point every 0.5 s)
    using Track = std::function<glm::dvec2(double time)>;

    EffectsTimeline(ecs::Registry& registry, ecs::EventQueue& events, EffectsSystem& system);
    /// A ship of `length` metres at `position` whose centre follows `track` from the next step on; its trail
    /// is attached (AttachShipTrail) by the next dispatch.
    ecs::Entity addShip(const glm::dvec2& position, double length, Track track, WakeParams wake = {});
    /// Explosions spawned by the first step at or after their time; any order (kept stable within a time).
    void scheduleExplosions(std::vector<SpawnExplosion> explosions);
    void step(double time, const glm::dvec3& cameraWorld);
    /// Steps from `from` (included) to `to` (excluded) every WARM_UP_STEP seconds; `beforeStep(t)`, when
    /// given, runs first at each (the game places its ships and records them there).
    void warmUp(double from, double to, const glm::dvec3& cameraWorld,
                const std::function<void(double)>& beforeStep = {});
    const std::vector<ecs::Entity>& ships() const { return mShips; }
    size_t explosionsSpawned() const { return mNextExplosion; }

private:
    ecs::Registry& mRegistry;
    ecs::EventQueue& mEvents;
    EffectsSystem& mSystem;
    std::vector<ecs::Entity> mShips;
    std::vector<Track> mTracks;
    std::vector<SpawnExplosion> mExplosions;
    size_t mNextExplosion = 0;
};

/// The effects of a registry as plain spans (EffectsView), for the span-taking queries and the renderer:
/// every Explosion (copied) and every Ship with a ShipTrail, in the registry's view order, less those with a
/// non-finite centre, start or position (EffectsSystem::update() counts a ship's as rejected; the ship is
/// back, its path kept, once its position is finite again).
class RegistryEffects {
public:
    explicit RegistryEffects(ecs::Registry& registry);
    EffectsView view() const { return {mExplosions, mWakes}; }

private:
    std::vector<Explosion> mExplosions;
    std::vector<WakeRef> mWakes;
};

// The queries of EffectTypes.h over a registry's effects (RegistryEffects; one gather per call).
glm::dvec3 effectsAt(ecs::Registry& registry, const glm::dvec2& xy, double t, double kMax = EFFECT_K_MAX);
double effectsFoamAt(ecs::Registry& registry, const glm::dvec2& xy, double t);
glm::dvec4 effectsFieldAt(ecs::Registry& registry, const glm::dvec2& xy, double t, double kMax = EFFECT_K_MAX,
                          double foamFilter2 = 0.0);
glm::dvec4 sampleEffectField(ecs::Registry& registry, const EffectFieldLayout& layout, const glm::dvec2& xy,
                             double t);
/// Height of the sea at world point xy: the ocean's surface (SurfaceModel::heightAt) plus the effects.
/// Throws std::invalid_argument if the entity has no OceanComponent.
double oceanHeightAt(ecs::Registry& registry, ecs::Entity ocean, const glm::dvec2& xy, double t);

} // namespace pacifica::ocean
