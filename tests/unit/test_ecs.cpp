// Unit tests for engine/Ecs.h and engine/Events.h: generational handles, sparse-set pools, views and the
// rule for changes during iteration, deferred commands, and the event queue's delivery guarantees.
#include "engine/Ecs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <vector>

using pacifica::ecs::Entity;
using pacifica::ecs::EventQueue;
using pacifica::ecs::FramePhase;
using pacifica::ecs::Registry;

namespace {

struct Position {
    double x = 0, y = 0;
};
struct Velocity {
    double dx = 0, dy = 0;
};
struct Tag {};
struct Health {
    int hp = 100;
};

// Message of the std::logic_error thrown by f, or "" if nothing was thrown.
template <class F>
std::string logicErrorMessage(F&& f) {
    try {
        f();
    } catch (const std::logic_error& e) {
        return e.what();
    }
    return "";
}

// Starts-with, so the tests pin the "function name first" rule of the error messages.
bool startsWith(const std::string& s, const std::string& prefix) {
    return s.rfind(prefix, 0) == 0;
}

} // namespace

TEST(Entity, NullAndHashAndFormatting) {
    EXPECT_TRUE(Entity::null.isNull());
    EXPECT_EQ(Entity{}, Entity::null);
    EXPECT_EQ(pacifica::ecs::toString(Entity{5, 2}), "5v2");
    EXPECT_EQ(pacifica::ecs::toString(Entity::null), "null");
    std::hash<Entity> h;
    EXPECT_NE(h(Entity{5, 2}), h(Entity{5, 3}));
    EXPECT_NE(h(Entity{5, 2}), h(Entity{2, 5}));
    std::unordered_set<Entity> set{Entity{1, 0}, Entity{1, 1}, Entity{1, 0}};
    EXPECT_EQ(set.size(), 2u);
}

TEST(Registry, CreateValidAlive) {
    Registry reg;
    EXPECT_EQ(reg.alive(), 0u);
    const Entity a = reg.create();
    const Entity b = reg.create();
    EXPECT_EQ(a, (Entity{0, 0}));
    EXPECT_EQ(b, (Entity{1, 0}));
    EXPECT_TRUE(reg.valid(a));
    EXPECT_TRUE(reg.valid(b));
    EXPECT_FALSE(reg.valid(Entity::null));
    EXPECT_FALSE(reg.valid(Entity{2, 0})); // never created
    EXPECT_EQ(reg.alive(), 2u);
}

TEST(Registry, StaleHandleDetectedAfterDestroyAndAfterSlotReuse) {
    Registry reg;
    const Entity a = reg.create();
    reg.emplace<Health>(a, 7);
    reg.destroy(a);

    // Stale after destroy, before reuse.
    EXPECT_FALSE(reg.valid(a));
    EXPECT_EQ(reg.tryGet<Health>(a), nullptr);
    EXPECT_FALSE(reg.has<Health>(a));
    EXPECT_FALSE(reg.remove<Health>(a));
    EXPECT_EQ(logicErrorMessage([&] { reg.get<Health>(a); }), "Registry::get(): stale entity 0v0");
    EXPECT_TRUE(
        startsWith(logicErrorMessage([&] { reg.destroy(a); }), "Registry::destroy(): stale entity 0v0"));
    EXPECT_TRUE(startsWith(logicErrorMessage([&] { reg.emplace<Health>(a, 1); }),
                           "Registry::emplace(): stale entity"));
    // A handle to a free slot with the slot's *current* generation was never issued: also rejected.
    EXPECT_FALSE(reg.valid(Entity{0, 1}));

    // The slot is recycled with a bumped generation; the old handle stays stale.
    const Entity b = reg.create();
    EXPECT_EQ(b.index, a.index);
    EXPECT_EQ(b.generation, a.generation + 1);
    EXPECT_TRUE(reg.valid(b));
    EXPECT_FALSE(reg.valid(a));
    EXPECT_FALSE(reg.has<Health>(b)); // components do not survive destroy
    reg.emplace<Health>(b, 42);
    EXPECT_EQ(reg.tryGet<Health>(a), nullptr);
    EXPECT_EQ(logicErrorMessage([&] { reg.get<Health>(a); }), "Registry::get(): stale entity 0v0");
    EXPECT_EQ(reg.get<Health>(b).hp, 42);
    EXPECT_EQ(logicErrorMessage([&] { reg.get<Health>(Entity::null); }), "Registry::get(): null entity");
}

TEST(Registry, GenerationIncrementsOnEveryDestroy) {
    Registry reg;
    Entity e = reg.create();
    for (std::uint32_t g = 0; g < 10; ++g) {
        EXPECT_EQ(e.index, 0u);
        EXPECT_EQ(e.generation, g);
        reg.destroy(e);
        e = reg.create();
    }
    EXPECT_EQ(e.generation, 10u);
    EXPECT_EQ(reg.alive(), 1u);
}

TEST(Registry, ComponentLifecycle) {
    Registry reg;
    const Entity e = reg.create();
    Position& p = reg.emplace<Position>(e, 1.0, 2.0);
    EXPECT_EQ(p.x, 1.0);
    EXPECT_EQ(p.y, 2.0);
    EXPECT_TRUE(reg.has<Position>(e));
    EXPECT_FALSE(reg.has<Velocity>(e));
    EXPECT_EQ(reg.size<Position>(), 1u);
    EXPECT_EQ(reg.size<Velocity>(), 0u);

    // emplace on an entity that already has the component is refused; emplaceOrReplace overwrites.
    const std::string msg = logicErrorMessage([&] { reg.emplace<Position>(e, 3.0, 4.0); });
    EXPECT_TRUE(startsWith(msg, "Registry::emplace(): entity 0v0 already has component")) << msg;
    EXPECT_EQ(reg.get<Position>(e).x, 1.0);
    reg.emplaceOrReplace<Position>(e, 3.0, 4.0);
    EXPECT_EQ(reg.get<Position>(e).x, 3.0);
    EXPECT_EQ(reg.size<Position>(), 1u);

    const std::string missing = logicErrorMessage([&] { reg.get<Velocity>(e); });
    EXPECT_TRUE(startsWith(missing, "Registry::get(): entity 0v0 has no component")) << missing;
    EXPECT_EQ(reg.tryGet<Velocity>(e), nullptr);

    EXPECT_TRUE(reg.remove<Position>(e));
    EXPECT_FALSE(reg.remove<Position>(e));
    EXPECT_FALSE(reg.has<Position>(e));
    EXPECT_EQ(reg.size<Position>(), 0u);
    EXPECT_TRUE(reg.valid(e)); // removing components does not destroy the entity
}

TEST(Registry, RemovalKeepsOtherComponentsIntact) {
    // Swap-and-pop must move the right component with the right entity.
    Registry reg;
    std::vector<Entity> es;
    for (int i = 0; i < 10; ++i) {
        es.push_back(reg.create());
        reg.emplace<Health>(es.back(), i);
    }
    reg.remove<Health>(es[0]);
    reg.remove<Health>(es[5]);
    reg.destroy(es[9]);
    for (int i = 0; i < 10; ++i) {
        if (i == 0 || i == 5 || i == 9)
            EXPECT_FALSE(reg.has<Health>(es[i]));
        else
            EXPECT_EQ(reg.get<Health>(es[i]).hp, i);
    }
    EXPECT_EQ(reg.size<Health>(), 7u);
}

TEST(Registry, SparseIndexPagesAcrossLargeIndices) {
    // Entities far apart in index land on different 4096-entry pages.
    Registry reg;
    std::vector<Entity> es;
    for (int i = 0; i < 10000; ++i)
        es.push_back(reg.create());
    reg.emplace<Health>(es[9999], 9999);
    reg.emplace<Health>(es[3], 3);
    reg.emplace<Health>(es[4096], 4096);
    EXPECT_EQ(reg.get<Health>(es[9999]).hp, 9999);
    EXPECT_EQ(reg.get<Health>(es[4096]).hp, 4096);
    EXPECT_EQ(reg.get<Health>(es[3]).hp, 3);
    EXPECT_FALSE(reg.has<Health>(es[4095]));
    EXPECT_FALSE(reg.has<Health>(es[8192]));
}

TEST(View, YieldsExactlyTheEntitiesWithAllComponents) {
    Registry reg;
    std::set<Entity> withPV, withPVT;
    std::mt19937 rng(1234);
    for (int i = 0; i < 1000; ++i) {
        const Entity e = reg.create();
        const bool p = rng() % 2, v = rng() % 3 != 0, t = rng() % 4 == 0;
        if (p)
            reg.emplace<Position>(e, double(i), 0.0);
        if (v)
            reg.emplace<Velocity>(e, 1.0, double(i));
        if (t)
            reg.emplace<Tag>(e);
        if (p && v)
            withPV.insert(e);
        if (p && v && t)
            withPVT.insert(e);
    }
    ASSERT_GT(withPV.size(), 100u);
    ASSERT_GT(withPVT.size(), 10u);

    std::multiset<Entity> seen;
    reg.view<Position, Velocity>().each([&](Entity e, Position& p, Velocity& v) {
        seen.insert(e);
        EXPECT_EQ(p.x, double(e.index)); // the components belong to the entity
        EXPECT_EQ(v.dy, double(e.index));
    });
    EXPECT_EQ(std::set<Entity>(seen.begin(), seen.end()), withPV);
    EXPECT_EQ(seen.size(), withPV.size()); // no duplicates

    std::multiset<Entity> seen3;
    for (Entity e : reg.view<Position, Velocity, Tag>())
        seen3.insert(e);
    EXPECT_EQ(std::set<Entity>(seen3.begin(), seen3.end()), withPVT);
    EXPECT_EQ(seen3.size(), withPVT.size());

    // The leading pool is the smallest one: Tag.
    const auto pvt = reg.view<Position, Velocity, Tag>();
    EXPECT_EQ(pvt.sizeHint(), reg.size<Tag>());
    EXPECT_LT(reg.size<Tag>(), reg.size<Position>());

    // Component-only callback form.
    int count = 0;
    reg.view<Position, Tag>().each([&](Position&, Tag&) { ++count; });
    int expected = 0;
    for (Entity e : reg.view<Tag>())
        expected += reg.has<Position>(e) ? 1 : 0;
    EXPECT_EQ(count, expected);
    EXPECT_GT(count, 0);
}

TEST(View, EmptyWhenAPoolIsEmpty) {
    Registry reg;
    const Entity e = reg.create();
    reg.emplace<Position>(e);
    int n = 0;
    reg.view<Position, Velocity>().each([&](Entity, Position&, Velocity&) { ++n; });
    EXPECT_EQ(n, 0);
    auto v = reg.view<Position, Velocity>();
    EXPECT_TRUE(v.begin() == v.end());
}

TEST(View, DestroyingVisitedEntityInsideEachIsSafe) {
    Registry reg;
    std::vector<Entity> es;
    for (int i = 0; i < 100; ++i) {
        es.push_back(reg.create());
        reg.emplace<Position>(es.back(), double(i), 0.0);
        reg.emplace<Velocity>(es.back());
    }
    std::map<Entity, int> visits;
    reg.view<Position, Velocity>().each([&](Entity e, Position& p, Velocity&) {
        ++visits[e];
        EXPECT_EQ(p.x, double(e.index));
        if (e.index % 3 == 0)
            reg.destroy(e); // the visited entity: allowed
        else if (e.index % 3 == 1)
            reg.remove<Position>(e); // a viewed component of the visited entity: allowed
    });
    EXPECT_EQ(visits.size(), 100u);
    for (const auto& [e, n] : visits)
        EXPECT_EQ(n, 1) << pacifica::ecs::toString(e);
    EXPECT_EQ(reg.alive(), 66u);          // 34 of 0..99 are multiples of 3
    EXPECT_EQ(reg.size<Position>(), 33u); // only index % 3 == 2 keeps Position
    EXPECT_EQ(reg.size<Velocity>(), 66u);
    for (const Entity e : es) {
        EXPECT_EQ(reg.valid(e), e.index % 3 != 0);
        EXPECT_EQ(reg.has<Position>(e), e.index % 3 == 2);
    }
}

TEST(View, RangeForAllowsRemovingVisitedEntity) {
    Registry reg;
    for (int i = 0; i < 50; ++i)
        reg.emplace<Health>(reg.create(), i);
    std::set<Entity> visited;
    for (Entity e : reg.view<Health>()) {
        EXPECT_TRUE(visited.insert(e).second);
        reg.destroy(e);
    }
    EXPECT_EQ(visited.size(), 50u);
    EXPECT_EQ(reg.alive(), 0u);
}

TEST(View, ChangingOtherEntitiesInsideEachThrows) {
    Registry reg;
    const Entity a = reg.create();
    const Entity b = reg.create();
    const Entity c = reg.create();
    reg.emplace<Position>(a);
    reg.emplace<Position>(b);
    reg.emplace<Velocity>(a);
    reg.emplace<Velocity>(b);

    std::vector<std::string> errors;
    reg.view<Position, Velocity>().each([&](Entity e, Position&, Velocity&) {
        const Entity other = e == a ? b : a;
        errors.push_back(logicErrorMessage([&] { reg.destroy(other); }));
        errors.push_back(logicErrorMessage([&] { reg.remove<Velocity>(other); }));
        errors.push_back(logicErrorMessage([&] { reg.emplace<Position>(c); }));
        errors.push_back(logicErrorMessage([&] { reg.clear(); }));
        // Allowed: components of types the view does not involve, and in-place replacement.
        reg.emplaceOrReplace<Health>(other, 5);
        reg.emplaceOrReplace<Position>(e, 9.0, 9.0);
    });
    ASSERT_EQ(errors.size(), 8u);
    for (std::size_t i = 0; i < errors.size(); i += 4) {
        EXPECT_TRUE(startsWith(errors[i], "Registry::destroy(): entity")) << errors[i];
        EXPECT_TRUE(startsWith(errors[i + 1], "Registry::remove(): entity")) << errors[i + 1];
        EXPECT_TRUE(startsWith(errors[i + 2], "Registry::emplace(): cannot add")) << errors[i + 2];
        EXPECT_TRUE(startsWith(errors[i + 3], "Registry::clear(): called while")) << errors[i + 3];
    }
    // Nothing was changed by the refused calls, and the locks are released after each().
    EXPECT_EQ(reg.alive(), 3u);
    EXPECT_TRUE(reg.has<Velocity>(a) && reg.has<Velocity>(b));
    EXPECT_FALSE(reg.has<Position>(c));
    EXPECT_EQ(reg.get<Position>(a).x, 9.0);
    EXPECT_EQ(reg.get<Health>(a).hp, 5);
    reg.emplace<Position>(c);
    reg.destroy(b);
    EXPECT_EQ(reg.alive(), 2u);
}

TEST(View, DeferredCommandsApplyOnFlush) {
    Registry reg;
    std::vector<Entity> es;
    for (int i = 0; i < 20; ++i) {
        es.push_back(reg.create());
        reg.emplace<Health>(es.back(), i);
    }
    // Each entity kills its neighbour and spawns a child: not allowed directly, so defer.
    reg.view<Health>().each([&](Entity e, Health& h) {
        if (h.hp % 2 == 0) {
            const Entity neighbour = es[std::size_t(h.hp) + 1];
            reg.defer([&reg, neighbour] { reg.destroy(neighbour); });
            reg.defer([](Registry& r) { r.emplace<Health>(r.create(), 1000); });
        }
        (void)e;
    });
    EXPECT_EQ(reg.deferredCount(), 20u);
    EXPECT_EQ(reg.alive(), 20u); // nothing applied yet
    EXPECT_EQ(reg.size<Health>(), 20u);

    EXPECT_EQ(reg.flushDeferred(), 20u);
    EXPECT_EQ(reg.deferredCount(), 0u);
    EXPECT_EQ(reg.alive(), 20u); // 10 destroyed, 10 created
    EXPECT_EQ(reg.size<Health>(), 20u);
    for (int i = 0; i < 20; ++i)
        EXPECT_EQ(reg.valid(es[std::size_t(i)]), i % 2 == 0);
    int children = 0;
    reg.view<Health>().each([&](Health& h) { children += h.hp == 1000 ? 1 : 0; });
    EXPECT_EQ(children, 10);

    // Commands deferred by commands run in the same flush, after the ones already queued.
    std::vector<int> order;
    reg.defer([&] {
        order.push_back(1);
        reg.defer([&] { order.push_back(3); });
    });
    reg.defer([&] { order.push_back(2); });
    EXPECT_EQ(reg.flushDeferred(), 3u);
    EXPECT_EQ(order, (std::vector<int>{1, 2, 3}));
}

TEST(Registry, ChurnOf100kEntitiesKeepsAliveCountRight) {
    Registry reg;
    std::vector<Entity> live;
    std::mt19937 rng(42);
    std::size_t created = 0, destroyed = 0;
    for (int i = 0; i < 100000; ++i) {
        live.push_back(reg.create());
        ++created;
        if (i % 2 == 0)
            reg.emplace<Health>(live.back(), i);
    }
    EXPECT_EQ(reg.alive(), 100000u);
    std::vector<Entity> dead;
    for (int round = 0; round < 5; ++round) {
        std::shuffle(live.begin(), live.end(), rng);
        for (int i = 0; i < 60000; ++i) { // destroy 60k
            reg.destroy(live.back());
            dead.push_back(live.back());
            live.pop_back();
            ++destroyed;
        }
        ASSERT_EQ(reg.alive(), live.size());
        for (int i = 0; i < 60000; ++i) { // recreate 60k into the freed slots
            live.push_back(reg.create());
            ++created;
        }
        ASSERT_EQ(reg.alive(), 100000u);
        ASSERT_EQ(reg.alive(), created - destroyed);
    }
    // Slots were recycled, not appended: no index beyond the peak population.
    std::uint32_t maxIndex = 0;
    for (const Entity e : live) {
        maxIndex = std::max(maxIndex, e.index);
        ASSERT_TRUE(reg.valid(e));
    }
    EXPECT_LT(maxIndex, 100000u);
    for (const Entity e : dead)
        ASSERT_FALSE(reg.valid(e));
    // Every live entity with Health is one of the original ones, and the pool has exactly those.
    std::size_t withHealth = 0;
    for (const Entity e : live)
        withHealth += reg.has<Health>(e) ? 1 : 0;
    EXPECT_EQ(reg.size<Health>(), withHealth);

    reg.clear();
    EXPECT_EQ(reg.alive(), 0u);
    EXPECT_EQ(reg.size<Health>(), 0u);
    for (const Entity e : live)
        ASSERT_FALSE(reg.valid(e));
}

TEST(FramePhase, OrderAndNames) {
    ASSERT_EQ(pacifica::ecs::ALL_FRAME_PHASES.size(), 5u);
    EXPECT_EQ(pacifica::ecs::ALL_FRAME_PHASES[0], FramePhase::OnLoad);
    EXPECT_EQ(pacifica::ecs::ALL_FRAME_PHASES[4], FramePhase::OnStore);
    EXPECT_STREQ(pacifica::ecs::toString(FramePhase::PreStore), "PreStore");
    EXPECT_LT(static_cast<int>(FramePhase::PreUpdate), static_cast<int>(FramePhase::OnUpdate));
}

namespace {
struct Splash {
    int id;
};
struct Gust {
    double speed;
};
} // namespace

TEST(EventQueue, OrderPreservedAcrossTypesAndDeliveredExactlyOnce) {
    EventQueue q;
    std::vector<std::string> log;
    q.subscribe<Splash>([&](const Splash& s) { log.push_back("S" + std::to_string(s.id)); });
    q.subscribe<Gust>([&](const Gust& g) { log.push_back("G" + std::to_string(int(g.speed))); });
    q.subscribe<Splash>([&](const Splash& s) { log.push_back("s" + std::to_string(s.id)); });

    q.enqueue(Splash{1});
    q.enqueue(Gust{7.0});
    q.enqueue(Splash{2});
    EXPECT_EQ(q.pending(), 3u);
    EXPECT_EQ(log.size(), 0u); // nothing delivered before dispatch
    EXPECT_EQ(q.dispatch(), 3u);
    EXPECT_EQ(log, (std::vector<std::string>{"S1", "s1", "G7", "S2", "s2"}));
    EXPECT_EQ(q.pending(), 0u);

    EXPECT_EQ(q.dispatch(), 0u); // exactly once: a second dispatch delivers nothing
    EXPECT_EQ(log.size(), 5u);
}

TEST(EventQueue, EventsEnqueuedDuringDispatchWaitForNextDispatch) {
    EventQueue q;
    std::vector<int> seen;
    q.subscribe<Splash>([&](const Splash& s) {
        seen.push_back(s.id);
        if (s.id < 3)
            q.enqueue(Splash{s.id + 1}); // a chain reaction: one link per frame
    });
    q.enqueue(Splash{1});
    q.dispatch();
    EXPECT_EQ(seen, (std::vector<int>{1}));
    EXPECT_EQ(q.pending(), 1u);
    q.dispatch();
    EXPECT_EQ(seen, (std::vector<int>{1, 2}));
    q.dispatch();
    EXPECT_EQ(seen, (std::vector<int>{1, 2, 3}));
    EXPECT_EQ(q.pending(), 0u);
    q.dispatch();
    EXPECT_EQ(seen.size(), 3u);

    // Dispatching from inside a subscriber would break that rule: refused.
    std::string error;
    q.subscribe<Gust>([&](const Gust&) { error = logicErrorMessage([&] { q.dispatch(); }); });
    q.enqueue(Gust{1.0});
    q.dispatch();
    EXPECT_TRUE(startsWith(error, "EventQueue::dispatch(): called from inside a subscriber")) << error;
}

TEST(EventQueue, UnsubscribeStopsDelivery) {
    EventQueue q;
    int a = 0, b = 0;
    const auto idA = q.subscribe<Splash>([&](const Splash&) { ++a; });
    const auto idB = q.subscribe<Splash>([&](const Splash&) { ++b; });
    EXPECT_NE(idA, idB);
    EXPECT_EQ(q.subscriberCount(), 2u);
    q.enqueue(Splash{1});
    q.dispatch();
    EXPECT_EQ(a, 1);
    EXPECT_EQ(b, 1);

    EXPECT_TRUE(q.unsubscribe(idA));
    EXPECT_FALSE(q.unsubscribe(idA)); // already gone
    EXPECT_FALSE(q.unsubscribe(9999));
    EXPECT_EQ(q.subscriberCount(), 1u);
    q.enqueue(Splash{2});
    q.dispatch();
    EXPECT_EQ(a, 1);
    EXPECT_EQ(b, 2);

    // Unsubscribing another subscriber from inside dispatch: it gets nothing more, even in this batch.
    int c = 0;
    EventQueue::SubscriptionId idC = 0;
    q.subscribe<Splash>([&](const Splash&) { q.unsubscribe(idC); });
    idC = q.subscribe<Splash>([&](const Splash&) { ++c; });
    q.enqueue(Splash{3});
    q.enqueue(Splash{4});
    q.dispatch();
    EXPECT_EQ(c, 0);
    EXPECT_EQ(b, 4);
    EXPECT_EQ(q.subscriberCount(), 2u);
}

TEST(EventQueue, ThrowingSubscriberKeepsUndeliveredEvents) {
    EventQueue q;
    std::vector<int> seen;
    q.subscribe<Splash>([&](const Splash& s) {
        if (s.id == 2 && seen.size() == 1)
            throw std::runtime_error("boom");
        seen.push_back(s.id);
    });
    for (int i = 1; i <= 4; ++i)
        q.enqueue(Splash{i});
    EXPECT_THROW(q.dispatch(), std::runtime_error);
    EXPECT_EQ(seen, (std::vector<int>{1}));
    EXPECT_EQ(q.pending(), 2u); // 3 and 4; event 2 counts as delivered
    q.dispatch();
    EXPECT_EQ(seen, (std::vector<int>{1, 3, 4}));
}
