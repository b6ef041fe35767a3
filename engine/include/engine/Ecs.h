// Ecs: the host engine's entity-component registry. Entities are generational handles, components are plain
// structs kept in sparse sets (packed dense arrays + a paged sparse index, as in EnTT), systems are free
// functions over views. Also names the phases of a frame and pulls in the EventQueue (engine/Events.h).
// Header-only, plain C++20.
//
// STEP BY STEP
// ============
// 1. Make a registry and entities:
//        pacifica::ecs::Registry reg;
//        Entity ship = reg.create();
// 2. Attach plain-struct components (emplace throws if the entity already has one; emplaceOrReplace
//    overwrites):
//        reg.emplace<Transform>(ship, Transform{...});
//        reg.emplace<Wake>(ship, 0.5f);
// 3. Write systems as free functions over views; a view iterates the smallest of its pools:
//        void wakeSystem(Registry& reg, const FrameContext& ctx) {
//            reg.view<Transform, Wake>().each([&](Entity e, Transform& t, Wake& w) { ... });
//        }
// 4. Inside each() you may remove components from, or destroy, the entity being visited. Anything else
//    that changes the viewed pools (adding components of a viewed type, removing them from other
//    entities, destroying other entities) must wait: collect and apply afterwards, or
//        reg.defer([&reg, other] { reg.destroy(other); });
//    and call reg.flushDeferred() once the view is done (typically once per frame phase).
// 5. Destroyed handles go stale: reg.valid(e) is false, tryGet() returns nullptr, get() throws
//    std::logic_error("Registry::get(): stale entity 5v2").
#pragma once

#include "engine/Events.h"

#include <array>
#include <atomic>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

namespace pacifica::ecs {

/// The phases of one frame, in order (the names follow flecs' builtin pipeline). OnLoad: gather input and
/// host data (camera pose, time); PreUpdate: prepare for the update (advance clocks, spawn effects);
/// OnUpdate: simulation and gameplay; PreStore: derive what rendering needs (culling, uniforms);
/// OnStore: hand results over (record render passes, capture).
enum class FramePhase { OnLoad, PreUpdate, OnUpdate, PreStore, OnStore };

/// Every phase in execution order, for loops over the frame.
inline constexpr std::array<FramePhase, 5> ALL_FRAME_PHASES{FramePhase::OnLoad, FramePhase::PreUpdate,
                                                            FramePhase::OnUpdate, FramePhase::PreStore,
                                                            FramePhase::OnStore};

/// The phase's name as written in the enum, e.g. "OnUpdate".
constexpr const char* toString(FramePhase phase) noexcept {
    switch (phase) {
    case FramePhase::OnLoad:
        return "OnLoad";
    case FramePhase::PreUpdate:
        return "PreUpdate";
    case FramePhase::OnUpdate:
        return "OnUpdate";
    case FramePhase::PreStore:
        return "PreStore";
    case FramePhase::OnStore:
        return "OnStore";
    }
    return "?";
}

/// A generational entity handle: a slot index plus the slot's generation when the handle was made.
/// Destroying an entity bumps its slot's generation, so older handles to the slot are detected as stale
/// even after the slot is reused. Entity::null (also the default value) never names a live entity.
struct Entity {
    std::uint32_t index = std::numeric_limits<std::uint32_t>::max();
    std::uint32_t generation = 0;

    /// The handle that names no entity.
    static const Entity null;

    constexpr bool isNull() const noexcept { return index == std::numeric_limits<std::uint32_t>::max(); }
    constexpr auto operator<=>(const Entity&) const = default;
};

inline constexpr Entity Entity::null{};

/// "5v2" for index 5, generation 2; "null" for Entity::null.
inline std::string toString(Entity e) {
    if (e.isNull())
        return "null";
    return std::to_string(e.index) + "v" + std::to_string(e.generation);
}

namespace detail {

/// Entries per page of a sparse index: a page covers 4096 consecutive entity indices.
inline constexpr std::size_t SPARSE_PAGE_SIZE = 4096;
/// Marks "no dense position" in the sparse index.
inline constexpr std::uint32_t NO_POSITION = std::numeric_limits<std::uint32_t>::max();

/// A process-wide counter handing out component type ids, one per type on first use.
inline std::size_t nextComponentTypeId() noexcept {
    static std::atomic<std::size_t> counter{0};
    return counter.fetch_add(1, std::memory_order_relaxed);
}

/// Dense id of component type T (0, 1, 2, ... in order of first use), used to index the registry's pools.
/// Note: like every static-counter scheme, ids are per executable image; component types must not cross
/// shared-library boundaries with different ids (Pacifica builds static libraries).
template <class T>
std::size_t componentTypeId() noexcept {
    static const std::size_t id = nextComponentTypeId();
    return id;
}

/// Type-erased sparse set of entities: packed dense array + paged sparse index (index -> dense position).
/// Also carries the iteration lock that lets the registry enforce the "only the visited entity" rule.
class SparseSet {
public:
    SparseSet() = default;
    SparseSet(const SparseSet&) = delete;
    SparseSet& operator=(const SparseSet&) = delete;
    virtual ~SparseSet() = default;

    /// True if this exact handle (index and generation) is in the set.
    bool contains(Entity e) const noexcept {
        const std::uint32_t pos = position(e.index);
        return pos != NO_POSITION && mDense[pos] == e;
    }
    std::size_t size() const noexcept { return mDense.size(); }
    /// Packed array of the entities in the set, in the same order as the components.
    const std::vector<Entity>& entities() const noexcept { return mDense; }

    /// Removes e and its component by swapping the last element into its place. Returns false if absent.
    bool remove(Entity e) {
        if (!contains(e))
            return false;
        const std::uint32_t pos = position(e.index);
        const Entity last = mDense.back();
        mDense[pos] = last;
        setPosition(last.index, pos);
        setPosition(e.index, NO_POSITION); // after the line above, in case e is the last element
        mDense.pop_back();
        moveLastComponentTo(pos);
        return true;
    }

    /// Removes every element; keeps the sparse pages for reuse.
    void clear() {
        for (const Entity e : mDense)
            setPosition(e.index, NO_POSITION);
        mDense.clear();
        clearComponents();
    }

    // Iteration lock, used by View::each() and checked by the registry.
    bool iterating() const noexcept { return mIterationDepth > 0; }
    Entity visiting() const noexcept { return mVisiting; }
    void beginIteration() noexcept { ++mIterationDepth; }
    void endIteration() noexcept { --mIterationDepth; }
    void setVisiting(Entity e) noexcept { mVisiting = e; }

protected:
    std::uint32_t position(std::uint32_t index) const noexcept {
        const std::size_t page = index / SPARSE_PAGE_SIZE;
        if (page >= mSparse.size() || !mSparse[page])
            return NO_POSITION;
        return (*mSparse[page])[index % SPARSE_PAGE_SIZE];
    }

    /// Appends e to the dense array; the derived pool appends its component at the same position.
    void pushEntity(Entity e) {
        const std::size_t page = e.index / SPARSE_PAGE_SIZE;
        if (page >= mSparse.size())
            mSparse.resize(page + 1);
        if (!mSparse[page]) {
            mSparse[page] = std::make_unique<std::array<std::uint32_t, SPARSE_PAGE_SIZE>>();
            mSparse[page]->fill(NO_POSITION);
        }
        mDense.push_back(e);
        (*mSparse[page])[e.index % SPARSE_PAGE_SIZE] = static_cast<std::uint32_t>(mDense.size() - 1);
    }

    virtual void moveLastComponentTo(std::size_t pos) = 0;
    virtual void clearComponents() noexcept = 0;

private:
    void setPosition(std::uint32_t index, std::uint32_t pos) noexcept {
        (*mSparse[index / SPARSE_PAGE_SIZE])[index % SPARSE_PAGE_SIZE] = pos;
    }

    std::vector<Entity> mDense;
    std::vector<std::unique_ptr<std::array<std::uint32_t, SPARSE_PAGE_SIZE>>> mSparse;
    int mIterationDepth = 0;
    Entity mVisiting;
};

/// The sparse set of one component type: components packed in the same order as entities().
template <class T>
class Pool final : public SparseSet {
public:
    /// Precondition: !contains(e).
    template <class... Args>
    T& emplace(Entity e, Args&&... args) {
        if constexpr (std::is_constructible_v<T, Args...>)
            mComponents.emplace_back(std::forward<Args>(args)...);
        else
            mComponents.push_back(T{std::forward<Args>(args)...}); // aggregates with braces
        try {
            pushEntity(e);
        } catch (...) {
            mComponents.pop_back();
            throw;
        }
        return mComponents.back();
    }

    /// Precondition: contains(e).
    T& get(Entity e) noexcept { return mComponents[position(e.index)]; }
    const T& get(Entity e) const noexcept { return mComponents[position(e.index)]; }

private:
    void moveLastComponentTo(std::size_t pos) override {
        if (pos + 1 != mComponents.size())
            mComponents[pos] = std::move(mComponents.back());
        mComponents.pop_back();
    }
    void clearComponents() noexcept override { mComponents.clear(); }

    std::vector<T> mComponents;
};

} // namespace detail

class Registry;

/// Entities that have all of the components Ts, with access to those components.
///
/// Iteration walks the dense array of the SMALLEST involved pool from back to front and skips entities
/// missing any other component. Because removal swaps the last element into the freed position, walking
/// back to front means that removing the visited entity's components, or destroying it, only moves an
/// already-visited element: every other entity is still visited exactly once.
///
/// Rule for changes during iteration:
/// - allowed: remove<T>() on, or destroy() of, the entity being visited; create(); adding or removing
///   components of types the view does not involve; replacing (emplaceOrReplace) an existing component.
/// - not allowed: adding a component of a viewed type to any entity, removing viewed components from or
///   destroying any OTHER entity, clear(). Inside each() these throw std::logic_error (checked); with a
///   range-for loop they are not checked and are undefined behaviour. Collect such changes and apply them
///   after the loop, or queue them with Registry::defer() and call Registry::flushDeferred() afterwards.
/// - References passed to the callback are invalidated by removing that component or destroying the entity.
template <class... Ts>
class View {
    static_assert(sizeof...(Ts) > 0, "View: name at least one component type");
    static_assert((std::is_same_v<Ts, std::remove_cvref_t<Ts>> && ...), "View: use plain component types");

public:
    /// Forward iterator over the matching entities (back to front of the leading pool).
    class Iterator {
    public:
        using value_type = Entity;
        using difference_type = std::ptrdiff_t;

        Iterator() = default;
        Entity operator*() const { return (*mDense)[mRemaining - 1]; }
        Iterator& operator++() {
            --mRemaining;
            skipNonMatching();
            return *this;
        }
        Iterator operator++(int) {
            Iterator old = *this;
            ++*this;
            return old;
        }
        bool operator==(const Iterator& other) const noexcept { return mRemaining == other.mRemaining; }

    private:
        friend class View;
        // Copies the pool pointers, so an iterator stays usable after a temporary View is gone.
        Iterator(const View& view, const std::vector<Entity>* dense, std::size_t remaining)
            : mPools(view.mPools), mDense(dense), mRemaining(remaining) {
            skipNonMatching();
        }
        void skipNonMatching() {
            // The dense array can shrink under us when the visited entity was removed: clamp first.
            while (mRemaining > 0 &&
                   (mRemaining > mDense->size() || !View::containsIn(mPools, (*mDense)[mRemaining - 1])))
                --mRemaining;
        }

        std::tuple<detail::Pool<Ts>*...> mPools{};
        const std::vector<Entity>* mDense = nullptr;
        std::size_t mRemaining = 0;
    };

    /// Calls f(Entity, Ts&...) or f(Ts&...) for every matching entity. See the class comment for what f may
    /// change.
    template <class F>
    void each(F&& f) {
        IterationGuard guard(std::get<detail::Pool<Ts>*>(mPools)...);
        const std::vector<Entity>& dense = leading().entities();
        for (std::size_t i = dense.size(); i-- > 0;) {
            if (i >= dense.size())
                continue; // the visited entity was removed and the array shrank below i
            const Entity e = dense[i];
            if (!contains(e))
                continue;
            guard.visit(e);
            if constexpr (std::is_invocable_v<F&, Entity, Ts&...>)
                f(e, std::get<detail::Pool<Ts>*>(mPools)->get(e)...);
            else
                f(std::get<detail::Pool<Ts>*>(mPools)->get(e)...);
        }
    }

    Iterator begin() const {
        const std::vector<Entity>& dense = leading().entities();
        return Iterator(*this, &dense, dense.size());
    }
    Iterator end() const { return Iterator(*this, &leading().entities(), 0); }

    /// True if e is alive and has all of Ts.
    bool contains(Entity e) const noexcept { return containsIn(mPools, e); }

    /// Upper bound on the number of matching entities: the size of the smallest pool.
    std::size_t sizeHint() const noexcept { return leading().size(); }

    /// Component T of a matching entity; throws std::logic_error if e does not match the view.
    template <class T>
    T& get(Entity e) const {
        if (!contains(e))
            throw std::logic_error("View::get(): entity " + toString(e) + " is not in the view");
        return std::get<detail::Pool<T>*>(mPools)->get(e);
    }

private:
    friend class Registry;
    explicit View(detail::Pool<Ts>*... pools) : mPools(pools...) {}

    static bool containsIn(const std::tuple<detail::Pool<Ts>*...>& pools, Entity e) noexcept {
        return (std::get<detail::Pool<Ts>*>(pools)->contains(e) && ...);
    }

    /// The smallest involved pool, chosen each time iteration starts.
    const detail::SparseSet& leading() const noexcept {
        const std::array<const detail::SparseSet*, sizeof...(Ts)> pools{
            std::get<detail::Pool<Ts>*>(mPools)...};
        const detail::SparseSet* best = pools[0];
        for (const detail::SparseSet* pool : pools)
            if (pool->size() < best->size())
                best = pool;
        return *best;
    }

    /// Locks the viewed pools for the duration of each() and records the visited entity, restoring the
    /// previous state on exit (views may nest).
    class IterationGuard {
    public:
        explicit IterationGuard(detail::Pool<Ts>*... pools) : mPools{pools...} {
            for (std::size_t i = 0; i < mPools.size(); ++i) {
                mSaved[i] = mPools[i]->visiting();
                mPools[i]->beginIteration();
            }
        }
        IterationGuard(const IterationGuard&) = delete;
        IterationGuard& operator=(const IterationGuard&) = delete;
        ~IterationGuard() {
            for (std::size_t i = 0; i < mPools.size(); ++i) {
                mPools[i]->setVisiting(mSaved[i]);
                mPools[i]->endIteration();
            }
        }
        void visit(Entity e) noexcept {
            for (detail::SparseSet* pool : mPools)
                pool->setVisiting(e);
        }

    private:
        std::array<detail::SparseSet*, sizeof...(Ts)> mPools;
        std::array<Entity, sizeof...(Ts)> mSaved{};
    };

    std::tuple<detail::Pool<Ts>*...> mPools;
};

/// Owns entities and their components.
///
/// Handle checks: mutating calls given a stale or null handle (destroy, emplace, emplaceOrReplace, get)
/// throw std::logic_error whose message starts with the function name, e.g.
/// "Registry::get(): stale entity 5v2"; queries (valid, has, tryGet, remove) return false / nullptr.
/// Not thread-safe. Pools keep stable addresses for the registry's lifetime; component references are
/// invalidated by any structural change to their pool (adding or removing a component of that type).
class Registry {
public:
    Registry() = default;
    Registry(const Registry&) = delete;
    Registry& operator=(const Registry&) = delete;
    Registry(Registry&&) = default;
    Registry& operator=(Registry&&) = default;

    /// Makes a new entity, recycling a free slot (with its bumped generation) if there is one.
    Entity create() {
        if (!mFree.empty()) {
            const std::uint32_t index = mFree.back();
            mFree.pop_back();
            mSlots[index].alive = true;
            ++mAlive;
            return Entity{index, mSlots[index].generation};
        }
        if (mSlots.size() >= Entity::null.index)
            throw std::length_error("Registry::create(): out of entity indices");
        mSlots.push_back(Slot{0, true});
        ++mAlive;
        return Entity{static_cast<std::uint32_t>(mSlots.size() - 1), 0};
    }

    /// Removes all of e's components and frees its slot; the slot's generation is bumped so e goes stale.
    /// A slot whose generation would wrap around is retired instead of recycled.
    void destroy(Entity e) {
        requireValid(e, "Registry::destroy()");
        for (const auto& pool : mPools)
            if (pool && pool->contains(e))
                checkRemovable(*pool, e, "Registry::destroy()");
        for (const auto& pool : mPools)
            if (pool)
                pool->remove(e);
        Slot& slot = mSlots[e.index];
        slot.alive = false;
        --mAlive;
        if (slot.generation == std::numeric_limits<std::uint32_t>::max())
            return; // retire: recycling would hand out generation 0 again and revive ancient handles
        ++slot.generation;
        mFree.push_back(e.index);
    }

    /// True if e names a live entity (right index and current generation).
    bool valid(Entity e) const noexcept {
        return e.index < mSlots.size() && mSlots[e.index].alive && mSlots[e.index].generation == e.generation;
    }

    /// Number of live entities.
    std::size_t alive() const noexcept { return mAlive; }

    /// Adds a component T built from args. Throws std::logic_error if e is stale or already has a T
    /// (use emplaceOrReplace to overwrite), or if a view over T is iterating.
    template <class T, class... Args>
    T& emplace(Entity e, Args&&... args) {
        requireValid(e, "Registry::emplace()");
        detail::Pool<T>& pool = assure<T>();
        if (pool.contains(e))
            throw std::logic_error("Registry::emplace(): entity " + toString(e) + " already has component " +
                                   typeid(T).name() + "; use emplaceOrReplace()");
        checkInsertable(pool, e, "Registry::emplace()");
        return pool.emplace(e, std::forward<Args>(args)...);
    }

    /// Adds a component T, or overwrites the existing one. Throws std::logic_error if e is stale.
    template <class T, class... Args>
    T& emplaceOrReplace(Entity e, Args&&... args) {
        requireValid(e, "Registry::emplaceOrReplace()");
        detail::Pool<T>& pool = assure<T>();
        if (pool.contains(e)) {
            T& existing = pool.get(e);
            if constexpr (std::is_constructible_v<T, Args...>)
                existing = T(std::forward<Args>(args)...);
            else
                existing = T{std::forward<Args>(args)...};
            return existing;
        }
        checkInsertable(pool, e, "Registry::emplaceOrReplace()");
        return pool.emplace(e, std::forward<Args>(args)...);
    }

    /// e's component T. Throws std::logic_error if e is stale/null or has no T.
    template <class T>
    T& get(Entity e) {
        return const_cast<T&>(std::as_const(*this).template get<T>(e));
    }
    template <class T>
    const T& get(Entity e) const {
        requireValid(e, "Registry::get()");
        const detail::Pool<T>* pool = findPool<T>();
        if (!pool || !pool->contains(e))
            throw std::logic_error("Registry::get(): entity " + toString(e) + " has no component " +
                                   typeid(T).name());
        return pool->get(e);
    }

    /// e's component T, or nullptr if e is stale/null or has no T.
    template <class T>
    T* tryGet(Entity e) noexcept {
        return const_cast<T*>(std::as_const(*this).template tryGet<T>(e));
    }
    template <class T>
    const T* tryGet(Entity e) const noexcept {
        const detail::Pool<T>* pool = findPool<T>();
        return valid(e) && pool && pool->contains(e) ? &pool->get(e) : nullptr;
    }

    /// True if e is live and has a T.
    template <class T>
    bool has(Entity e) const noexcept {
        return tryGet<T>(e) != nullptr;
    }

    /// Removes e's T. Returns false (and does nothing) if e is stale or has no T. Throws std::logic_error
    /// when called from View::each() over T for an entity other than the one being visited.
    template <class T>
    bool remove(Entity e) {
        detail::Pool<T>* pool = findPool<T>();
        if (!valid(e) || !pool || !pool->contains(e))
            return false;
        checkRemovable(*pool, e, "Registry::remove()");
        return pool->remove(e);
    }

    /// Number of entities with a T.
    template <class T>
    std::size_t size() const noexcept {
        const detail::Pool<T>* pool = findPool<T>();
        return pool ? pool->size() : 0;
    }

    /// Destroys every entity (generations are bumped, so all old handles go stale) and drops pending
    /// deferred commands. Throws std::logic_error if a view is iterating.
    void clear() {
        for (const auto& pool : mPools)
            if (pool && pool->iterating())
                throw std::logic_error("Registry::clear(): called while a view is iterating");
        for (const auto& pool : mPools)
            if (pool)
                pool->clear();
        for (std::uint32_t i = 0; i < mSlots.size(); ++i) {
            Slot& slot = mSlots[i];
            if (!slot.alive)
                continue;
            slot.alive = false;
            if (slot.generation != std::numeric_limits<std::uint32_t>::max()) {
                ++slot.generation;
                mFree.push_back(i);
            }
        }
        mAlive = 0;
        mDeferred.clear();
    }

    /// A view over the entities having all of Ts (see View for the iteration rules).
    template <class... Ts>
    View<Ts...> view() {
        return View<Ts...>(&assure<Ts>()...);
    }

    /// Queues a command to run at the next flushDeferred(): a callable taking () or (Registry&).
    /// Use it for changes that are not allowed while a view iterates.
    template <class F>
    void defer(F&& command) {
        if constexpr (std::is_invocable_v<F&, Registry&>)
            mDeferred.emplace_back(std::forward<F>(command));
        else
            mDeferred.emplace_back([fn = std::forward<F>(command)](Registry&) mutable { fn(); });
    }

    /// Runs the queued commands in the order they were deferred, including commands that they defer
    /// themselves. Returns how many ran. If a command throws, the exception propagates and the commands
    /// of the same batch after it are discarded.
    std::size_t flushDeferred() {
        std::size_t ran = 0;
        while (!mDeferred.empty()) {
            std::vector<std::function<void(Registry&)>> batch;
            batch.swap(mDeferred); // commands may defer more; they land in mDeferred, not in batch
            for (std::function<void(Registry&)>& command : batch) {
                command(*this);
                ++ran;
            }
        }
        return ran;
    }

    /// Number of commands waiting for flushDeferred().
    std::size_t deferredCount() const noexcept { return mDeferred.size(); }

private:
    struct Slot {
        std::uint32_t generation = 0;
        bool alive = false;
    };

    void requireValid(Entity e, const char* function) const {
        if (valid(e))
            return;
        throw std::logic_error(std::string(function) + (e.isNull() ? ": null entity" : ": stale entity ") +
                               (e.isNull() ? std::string() : toString(e)));
    }

    static void checkInsertable(const detail::SparseSet& pool, Entity e, const char* function) {
        if (pool.iterating())
            throw std::logic_error(std::string(function) + ": cannot add a component to entity " +
                                   toString(e) + " while a view over its type is iterating; use defer()");
    }

    static void checkRemovable(const detail::SparseSet& pool, Entity e, const char* function) {
        if (pool.iterating() && pool.visiting() != e)
            throw std::logic_error(std::string(function) + ": entity " + toString(e) +
                                   " is not the one being visited by the iterating view (" +
                                   toString(pool.visiting()) + "); use defer()");
    }

    template <class T>
    detail::Pool<T>& assure() {
        static_assert(std::is_same_v<T, std::remove_cvref_t<T>>, "Registry: use plain component types");
        const std::size_t id = detail::componentTypeId<T>();
        if (id >= mPools.size())
            mPools.resize(id + 1);
        if (!mPools[id])
            mPools[id] = std::make_unique<detail::Pool<T>>();
        return static_cast<detail::Pool<T>&>(*mPools[id]);
    }

    template <class T>
    const detail::Pool<T>* findPool() const noexcept {
        const std::size_t id = detail::componentTypeId<T>();
        return id < mPools.size() ? static_cast<const detail::Pool<T>*>(mPools[id].get()) : nullptr;
    }
    template <class T>
    detail::Pool<T>* findPool() noexcept {
        return const_cast<detail::Pool<T>*>(std::as_const(*this).template findPool<T>());
    }

    std::vector<Slot> mSlots;
    std::vector<std::uint32_t> mFree;
    std::size_t mAlive = 0;
    std::vector<std::unique_ptr<detail::SparseSet>> mPools; // indexed by detail::componentTypeId<T>()
    std::vector<std::function<void(Registry&)>> mDeferred;  // called with *this, so a moved registry works
};

} // namespace pacifica::ecs

/// Hash of both halves, so handles can key unordered containers.
template <>
struct std::hash<pacifica::ecs::Entity> {
    std::size_t operator()(const pacifica::ecs::Entity& e) const noexcept {
        return std::hash<std::uint64_t>{}((std::uint64_t(e.generation) << 32) | e.index);
    }
};
