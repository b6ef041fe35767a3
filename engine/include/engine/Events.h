// EventQueue: typed, deferred events for the host engine. Systems enqueue events during a frame and the
// frame loop calls dispatch() once per frame, so a subscriber never runs in the middle of the system that
// raised the event (no re-entrancy, and events raised while dispatching wait for the next frame).
// Header-only; plain C++20, no engine dependencies. Included by engine/Ecs.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <typeindex>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pacifica::ecs {

/// A queue of typed events delivered in batches.
///
/// Rules (each one is tested in tests/unit/test_ecs.cpp):
/// - dispatch() delivers every event queued before the call, in enqueue order (across all types), to every
///   subscriber of the event's exact type, exactly once, and then forgets it.
/// - Events enqueued while dispatch() runs (from a subscriber) are delivered by the NEXT dispatch(); call
///   dispatch() once per frame. Calling dispatch() from inside a subscriber throws std::logic_error.
/// - A subscriber added during dispatch() receives events from the next event delivered on; one removed
///   during dispatch() receives nothing more.
/// - If a subscriber throws, the exception propagates out of dispatch(); the event being delivered counts
///   as delivered and the undelivered rest of the batch goes back to the front of the queue.
///
/// Usage:
/// @code
/// struct Splash { glm::dvec3 where; };
/// EventQueue q;
/// auto id = q.subscribe<Splash>([](const Splash& s) { spawnFoam(s.where); });
/// q.enqueue(Splash{{0, 0, 0}});
/// q.dispatch();      // spawnFoam runs here
/// q.unsubscribe(id);
/// @endcode
class EventQueue {
public:
    /// Identifies one subscription; 0 is never returned, so it can mean "none".
    using SubscriptionId = std::uint64_t;

    EventQueue() = default;
    EventQueue(const EventQueue&) = delete;
    EventQueue& operator=(const EventQueue&) = delete;
    EventQueue(EventQueue&&) = default;
    EventQueue& operator=(EventQueue&&) = default;

    /// Registers a handler for events of type E; returns an id for unsubscribe().
    /// An empty handler throws std::invalid_argument.
    template <class E>
    SubscriptionId subscribe(std::function<void(const E&)> handler) {
        static_assert(std::is_same_v<E, std::remove_cvref_t<E>>, "EventQueue: use the plain event type");
        if (!handler)
            throw std::invalid_argument("EventQueue::subscribe(): empty handler");
        const SubscriptionId id = mNextId++;
        auto subscriber = std::make_shared<Subscriber>();
        subscriber->id = id;
        subscriber->handler = [fn = std::move(handler)](const EventBase& event) {
            fn(static_cast<const EventHolder<E>&>(event).value);
        };
        mSubscribers[std::type_index(typeid(E))].push_back(std::move(subscriber));
        mSubscriptionTypes.emplace(id, std::type_index(typeid(E)));
        return id;
    }

    /// Removes a subscription. Returns false when the id is unknown (already removed, or never issued).
    bool unsubscribe(SubscriptionId id) {
        const auto typeIt = mSubscriptionTypes.find(id);
        if (typeIt == mSubscriptionTypes.end())
            return false;
        std::vector<std::shared_ptr<Subscriber>>& list = mSubscribers.at(typeIt->second);
        mSubscriptionTypes.erase(typeIt);
        for (auto it = list.begin(); it != list.end(); ++it) {
            if ((*it)->id != id)
                continue;
            (*it)->active = false;
            if (mDispatching)
                mNeedsCompaction = true; // dispatch() walks this list by index; erase after it
            else
                list.erase(it);
            return true;
        }
        return true;
    }

    /// Queues an event for the next dispatch().
    template <class E>
    void enqueue(E event) {
        static_assert(std::is_same_v<E, std::remove_cvref_t<E>>, "EventQueue: use the plain event type");
        mQueue.push_back(
            Entry{std::type_index(typeid(E)), std::make_unique<EventHolder<E>>(std::move(event))});
    }

    /// Delivers the events queued before this call (see the class comment for the rules).
    /// Returns the number of events taken from the queue.
    std::size_t dispatch() {
        if (mDispatching)
            throw std::logic_error(
                "EventQueue::dispatch(): called from inside a subscriber; events raised now "
                "are delivered by the next dispatch()");
        std::vector<Entry> batch;
        batch.swap(mQueue);
        mDispatching = true;
        std::size_t next = 0;
        // Restores the queue's state even if a subscriber throws.
        struct Finish {
            EventQueue& queue;
            std::vector<Entry>& batch;
            const std::size_t& next;
            ~Finish() {
                queue.mDispatching = false;
                if (next < batch.size())
                    queue.mQueue.insert(queue.mQueue.begin(), std::make_move_iterator(batch.begin() + next),
                                        std::make_move_iterator(batch.end()));
                queue.compact();
            }
        } finish{*this, batch, next};

        while (next < batch.size()) {
            const Entry& entry = batch[next++];
            const auto it = mSubscribers.find(entry.type);
            if (it == mSubscribers.end())
                continue;
            // A reference to a mapped value survives rehashing if a subscriber subscribes to a new type.
            std::vector<std::shared_ptr<Subscriber>>& list = it->second;
            const std::size_t count = list.size(); // late subscribers start with the next event
            for (std::size_t i = 0; i < count; ++i) {
                const std::shared_ptr<Subscriber> subscriber = list[i]; // keeps it alive during the call
                if (subscriber->active)
                    subscriber->handler(*entry.event);
            }
        }
        return batch.size();
    }

    /// Number of events waiting for the next dispatch().
    std::size_t pending() const noexcept { return mQueue.size(); }

    /// Number of live subscriptions, all types together.
    std::size_t subscriberCount() const noexcept { return mSubscriptionTypes.size(); }

    /// Drops every pending event without delivering it.
    void clearPending() { mQueue.clear(); }

private:
    struct EventBase {
        virtual ~EventBase() = default;
    };
    template <class E>
    struct EventHolder final : EventBase {
        explicit EventHolder(E&& e) : value(std::move(e)) {}
        E value;
    };
    struct Subscriber {
        SubscriptionId id = 0;
        std::function<void(const EventBase&)> handler;
        bool active = true;
    };
    struct Entry {
        std::type_index type;
        std::unique_ptr<EventBase> event;
    };

    void compact() {
        if (!mNeedsCompaction)
            return;
        for (auto& [type, list] : mSubscribers)
            std::erase_if(list, [](const std::shared_ptr<Subscriber>& s) { return !s->active; });
        mNeedsCompaction = false;
    }

    std::unordered_map<std::type_index, std::vector<std::shared_ptr<Subscriber>>> mSubscribers;
    std::unordered_map<SubscriptionId, std::type_index> mSubscriptionTypes;
    std::vector<Entry> mQueue;
    SubscriptionId mNextId = 1;
    bool mDispatching = false;
    bool mNeedsCompaction = false;
};

} // namespace pacifica::ecs
