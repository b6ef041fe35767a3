// SeaQuery: batched sea queries over a span of points (SeaQuery.h).
#include "ocean/SeaQuery.h"

#include "Guarded.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace pacifica::ocean {

namespace {

constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

/// The effects' dE/dt by central difference (their field has no closed-form time derivative here).
constexpr double EFFECT_RATE_STEP = 1e-3;

} // namespace

struct SeaQuery::Impl {
    std::shared_ptr<const SurfaceModel> surface;
    std::optional<FftSampledSea> sampled; // the FFT sea's sampled tiles (the default FFT path)
    std::unique_ptr<ThreadPool> pool;
    JobSystem jobs;
    SeaQueryDesc desc;
    double time = 0.0;
    bool ready = false; // update() has succeeded
    // The effects at the query's time (and at time -+ EFFECT_RATE_STEP for dE/dt when velocity is asked):
    // every effect's state made once per update(), not per point.
    EffectsSnapshot effects, effectsBefore, effectsAfter;
    SeaQueryCounters counters;

    /// One point's answer into `out` (the asked fields); false for a point that is not finite.
    bool answer(const glm::dvec2& p, unsigned fields, SeaSample& out) const;
};

bool SeaQuery::Impl::answer(const glm::dvec2& p, unsigned fields, SeaSample& out) const {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
        if (fields & SeaField::Height)
            out.height = NaN;
        if (fields & SeaField::Normal)
            out.normal = glm::dvec3(NaN);
        if (fields & SeaField::Displacement)
            out.displacement = glm::dvec2(NaN);
        if (fields & SeaField::Velocity)
            out.velocity = glm::dvec3(NaN);
        return false;
    }
    // The water above p came from grid point x0 (Eulerian to Lagrangian), displaced by d.
    glm::dvec3 d;
    const glm::dvec2 x0 =
        sampled ? sampled->lagrangianPointAt(p, &d) : surface->lagrangianPointAt(p, time, &d);
    glm::dvec3 e(0.0); // the effects' (E, dE/dx, dE/dy)
    const bool withEffects = !effects.empty() && (fields & (SeaField::Height | SeaField::Normal));
    if (withEffects)
        e = effects.at(p);
    if (fields & SeaField::Height)
        out.height = d.z + e.x;
    if (fields & SeaField::Displacement)
        out.displacement = glm::dvec2(d);
    if (fields & SeaField::Normal) {
        const glm::dvec3 n = sampled ? sampled->normalAt(x0) : surface->normalAt(x0, time);
        // The effects' slopes added to the surface's: n ~ (-s_x, -s_y, 1) n_z, written without dividing by
        // n_z so a folded crest's normal (n_z <= 0) stays finite.
        out.normal = withEffects ? glm::normalize(glm::dvec3(n.x - e.y * n.z, n.y - e.z * n.z, n.z)) : n;
    }
    if (fields & SeaField::Velocity) {
        glm::dvec3 v = sampled ? sampled->velocityAt(x0) : surface->velocityAt(x0, time);
        if (!effects.empty())
            v.z += (effectsAfter.at(p).x - effectsBefore.at(p).x) / (2.0 * EFFECT_RATE_STEP);
        out.velocity = v;
    }
    return true;
}

SeaQuery::SeaQuery() noexcept = default;
SeaQuery::~SeaQuery() = default;
SeaQuery::SeaQuery(SeaQuery&&) noexcept = default;
SeaQuery& SeaQuery::operator=(SeaQuery&&) noexcept = default;

Status SeaQuery::init(const OceanComponent& ocean, const SeaQueryDesc& desc) noexcept {
    return guarded([&] {
        if (!ocean.surface)
            throw std::invalid_argument(
                "SeaQuery::init(): the OceanComponent has no surface (made by makeOcean?)");
        if (desc.fields == 0 || (desc.fields & ~SeaField::All) != 0)
            throw std::invalid_argument(
                "SeaQueryDesc.fields must be a non-empty mask of SeaField bits, got " +
                std::to_string(desc.fields));
        if (desc.pointsPerJob == 0)
            throw std::invalid_argument("SeaQueryDesc.pointsPerJob must be >= 1");
        if (!std::isfinite(desc.fftResampleInterval) || desc.fftResampleInterval < 0.0)
            throw std::invalid_argument("SeaQueryDesc.fftResampleInterval must be finite and >= 0, got " +
                                        std::to_string(desc.fftResampleInterval));
        auto impl = std::make_unique<Impl>();
        impl->surface = ocean.surface;
        impl->desc = desc;
        if (ocean.surface->kind() == SurfaceKind::Fft && !desc.fftDirectSum) {
            const auto* cascades = dynamic_cast<const FftCascades*>(ocean.surface.get());
            if (cascades)
                impl->sampled.emplace(*cascades, desc.fftInterpolation,
                                      (desc.fields & SeaField::Velocity) != 0 ||
                                          desc.fftResampleInterval > 0.0);
        }
        if (desc.jobs.parallelFor) {
            impl->jobs = desc.jobs;
        } else if (desc.threads != 1) {
            impl->pool = std::make_unique<ThreadPool>(desc.threads);
            impl->jobs = impl->pool->jobs();
        }
        mImpl = std::move(impl);
    });
}

Status SeaQuery::update(double t, const EffectsView& effects) noexcept {
    return guarded([&] {
        if (!mImpl)
            throw std::invalid_argument("SeaQuery::update(): init() first");
        if (!std::isfinite(t))
            throw std::invalid_argument("SeaQuery::update(): time must be finite, got " + std::to_string(t));
        mImpl->ready = false;
        // The tiles at the time they hold already are the same bits: sample again only for a new time, and
        // within fftResampleInterval of the last transform extrapolate them instead.
        if (FftSampledSea* s = mImpl->sampled ? &*mImpl->sampled : nullptr;
            s && !(s->sampled() && s->time() == t)) {
            if (s->sampled() && std::abs(t - s->sampledTime()) < mImpl->desc.fftResampleInterval)
                s->extrapolateTo(t, mImpl->jobs);
            else
                s->resample(t, mImpl->jobs);
        }
        mImpl->time = t;
        mImpl->effects.update(effects, t);
        if (mImpl->desc.fields & SeaField::Velocity) {
            mImpl->effectsBefore.update(effects, t - EFFECT_RATE_STEP);
            mImpl->effectsAfter.update(effects, t + EFFECT_RATE_STEP);
        }
        mImpl->ready = true;
        ++mImpl->counters.updates;
    });
}

namespace {

/// One sample() or heights() call spread over jobs of `perJob` points.
struct Batch {
    const SeaQuery::Impl* impl;
    std::span<const glm::dvec2> points;
    std::span<SeaSample> samples; // or
    std::span<double> heights;
    unsigned fields;
    size_t perJob;
    std::atomic<uint64_t> rejected{0};
    std::atomic<size_t> firstRejected{std::numeric_limits<size_t>::max()};
    std::atomic<bool> failed{false};

    size_t jobCount() const { return points.empty() ? 0 : (points.size() - 1) / perJob + 1; }
    static void run(void* context, size_t job);
};

} // namespace

void Batch::run(void* context, size_t job) {
    auto* b = static_cast<Batch*>(context);
    const size_t begin = job * b->perJob, end = std::min(b->points.size(), begin + b->perJob);
    uint64_t rejected = 0;
    size_t first = std::numeric_limits<size_t>::max();
    try { // a job must not throw (Jobs.h); the points were checked, so nothing is expected here
        SeaSample s;
        for (size_t i = begin; i < end; ++i) {
            bool ok;
            if (b->heights.empty()) {
                ok = b->impl->answer(b->points[i], b->fields, b->samples[i]);
            } else {
                ok = b->impl->answer(b->points[i], SeaField::Height, s);
                b->heights[i] = s.height;
            }
            if (!ok) {
                ++rejected;
                first = std::min(first, i);
            }
        }
    } catch (...) {
        b->failed = true;
    }
    if (rejected) {
        b->rejected += rejected;
        size_t seen = b->firstRejected.load();
        while (first < seen && !b->firstRejected.compare_exchange_weak(seen, first)) {
        }
    }
}

namespace {

/// Runs the batch's jobs (on the calling thread below one job's worth) and reports what was refused.
Status runBatch(SeaQuery::Impl& impl, Batch& batch, const char* what) {
    if (!impl.ready)
        return {ErrorCode::InvalidArgument, std::string("SeaQuery::") + what + "(): update() first"};
    impl.jobs.run(batch.jobCount(), &Batch::run, &batch); // one job runs on the calling thread
    if (batch.failed)
        return {ErrorCode::Internal, std::string("SeaQuery::") + what + "(): a point's evaluation failed"};
    const uint64_t rejected = batch.rejected;
    impl.counters.points += batch.points.size() - rejected;
    impl.counters.rejected += rejected;
    if (rejected)
        return {ErrorCode::InvalidArgument,
                std::string("SeaQuery::") + what + "(): " + std::to_string(rejected) + " of " +
                    std::to_string(batch.points.size()) + " points are not finite (the first: points[" +
                    std::to_string(batch.firstRejected.load()) +
                    "]); their answers are NaN, every other point is answered"};
    return {};
}

} // namespace

Status SeaQuery::sample(std::span<const glm::dvec2> points, std::span<SeaSample> samples,
                        unsigned fields) noexcept {
    if (!mImpl)
        return {ErrorCode::InvalidArgument, "SeaQuery::sample(): init() first"};
    if (points.size() != samples.size())
        return {ErrorCode::InvalidArgument, "SeaQuery::sample(): " + std::to_string(points.size()) +
                                                " points but " + std::to_string(samples.size()) + " samples"};
    if (fields == 0 || (fields & ~mImpl->desc.fields) != 0)
        return {ErrorCode::InvalidArgument, "SeaQuery::sample(): fields " + std::to_string(fields) +
                                                " are not a non-empty subset of SeaQueryDesc.fields " +
                                                std::to_string(mImpl->desc.fields)};
    Batch batch{mImpl.get(), points, samples, {}, fields, mImpl->desc.pointsPerJob};
    return runBatch(*mImpl, batch, "sample");
}

Status SeaQuery::heights(std::span<const glm::dvec2> points, std::span<double> heights) noexcept {
    if (!mImpl)
        return {ErrorCode::InvalidArgument, "SeaQuery::heights(): init() first"};
    if (points.size() != heights.size())
        return {ErrorCode::InvalidArgument, "SeaQuery::heights(): " + std::to_string(points.size()) +
                                                " points but " + std::to_string(heights.size()) + " heights"};
    if (points.empty())
        return mImpl->ready ? Status{}
                            : Status{ErrorCode::InvalidArgument, "SeaQuery::heights(): update() first"};
    Batch batch{mImpl.get(), points, {}, heights, SeaField::Height, mImpl->desc.pointsPerJob};
    return runBatch(*mImpl, batch, "heights");
}

double SeaQuery::time() const noexcept {
    return mImpl ? mImpl->time : 0.0;
}

const SeaQueryCounters& SeaQuery::counters() const noexcept {
    static const SeaQueryCounters none;
    return mImpl ? mImpl->counters : none;
}

} // namespace pacifica::ocean
