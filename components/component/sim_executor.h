#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <vector>

#include "component/component.h"

namespace stickrep::component {

// Runs components in one process on a simulated clock, deterministically: the same inputs
// give the same run. Topics are named as on DDS; a sample published goes, in publication
// order, to every subscriber of its topic before the clock moves on (no transport delay, no
// loss). Timers fire in time order, ties in the order they were added.
class SimExecutor : public Clock {
 public:
  // Simulated time starts at `start_ns` (never 0: components treat 0 as "never").
  explicit SimExecutor(int64_t start_ns = kDefaultStartNs) : now_ns_(start_ns), start_ns_(start_ns) {}
  static constexpr int64_t kDefaultStartNs = 1'000'000'000'000'000'000;

  int64_t NowNs() const override { return now_ns_; }
  // Seconds since the start.
  double ElapsedS() const { return (now_ns_ - start_ns_) * 1e-9; }

  // The publisher of `topic`; one per topic and type, owned by the executor.
  template <typename T>
  Publisher<T>& Advertise(const std::string& topic) {
    return TopicOf<T>(topic).publisher;
  }
  template <typename T>
  void Subscribe(const std::string& topic, std::function<void(const T&)> on_sample) {
    TopicOf<T>(topic).subscribers.push_back(std::move(on_sample));
  }

  // Calls `fire` every `period_s` of simulated time, first after `first_after_s`.
  void AddTimer(double period_s, std::function<void()> fire, double first_after_s);
  void AddTimer(double period_s, std::function<void()> fire) {
    AddTimer(period_s, std::move(fire), period_s);
  }
  // A component's timers, first after one period each.
  void AddTimers(Component& component);

  // Moves the clock to the next due timer and fires every timer due then, delivering what
  // each published before the next fires.
  void Step();
  // Steps until `done` holds (checked after each step) or `max_s` simulated seconds have
  // passed since the start; true if `done` held.
  bool RunUntil(const std::function<bool()>& done, double max_s);
  // Hands every queued sample to its subscribers, including those published meanwhile.
  void Deliver();

  uint64_t delivered() const { return delivered_; }

 private:
  struct TopicBase {
    virtual ~TopicBase() = default;
  };
  template <typename T>
  struct Topic : TopicBase {
    class Out : public Publisher<T> {
     public:
      Out(SimExecutor& e, Topic& t) : e_(e), t_(t) {}
      bool Publish(const T& sample) override {
        T copy = sample;
        copy.header.sequence = ++sequence_;
        e_.queue_.push_back([t = &t_, s = std::move(copy)] {
          for (const auto& sub : t->subscribers) sub(s);
        });
        return true;
      }

     private:
      SimExecutor& e_;
      Topic& t_;
      uint32_t sequence_ = 0;
    };
    explicit Topic(SimExecutor& e) : publisher(e, *this) {}
    Out publisher;
    std::vector<std::function<void(const T&)>> subscribers;
  };

  template <typename T>
  Topic<T>& TopicOf(const std::string& name) {
    auto it = topics_.find(name);
    if (it == topics_.end()) {
      it = topics_.emplace(name, std::make_unique<Topic<T>>(*this)).first;
    }
    auto* topic = dynamic_cast<Topic<T>*>(it->second.get());
    if (topic == nullptr) {
      throw std::logic_error("topic '" + name + "' is used with two sample types");
    }
    return *topic;
  }

  struct TimerEntry {
    int64_t period_ns;
    int64_t next_ns;
    std::function<void()> fire;
  };

  int64_t now_ns_;
  int64_t start_ns_;
  std::map<std::string, std::unique_ptr<TopicBase>> topics_;
  std::deque<std::function<void()>> queue_;
  std::vector<TimerEntry> timers_;
  uint64_t delivered_ = 0;
};

}  // namespace stickrep::component
