#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "component/component.h"
#include "convert/convert.h"
#include "runtime/endpoint.h"
#include "runtime/process.h"

namespace stickrep::runtime {

// A component's samples of one topic, written on DDS: converted to the IDL type, stamped and
// numbered by the writer, counted as sent.
template <typename PubSubType, typename T>
class DdsPublisher : public component::Publisher<T> {
 public:
  DdsPublisher(NodeContext& ctx, const std::string& topic)
      : counters_(ctx.counters), writer_(ctx.participant, topic) {}
  bool Publish(const T& sample) override {
    typename PubSubType::type m = convert::ToIdl(sample);
    if (!writer_.Publish(m, sample.header.stamp_ns)) return false;
    counters_.CountOut();
    return true;
  }
  const Writer<PubSubType>& writer() const { return writer_; }

 private:
  SampleCounters& counters_;
  Writer<PubSubType> writer_;
};

// The C++ sample type a DDS topic type converts to (convert/).
template <typename PubSubType>
using SampleOf = typename decltype(convert::FromIdl(
    std::declval<const typename PubSubType::type&>()).value)::value_type;

// The node of one component: Build() makes the component and wires its topics with Publish()
// and Feed(); the lifecycle, the timers (on the executor, wall clock) and the summary are
// forwarded. Every sample read is counted, converted and checked (convert/), and dropped
// with its reason when bad, before the component sees it.
class ComponentNode : public ProcessNode {
 public:
  void Configure(NodeContext& ctx) final {
    ctx_ = &ctx;
    clock_ = std::make_unique<ScaledClock>(ctx.now_ns);
    component_ctx_ = std::make_unique<component::Context>(
        component::Context{ctx.name, *clock_, ctx.log, ctx.counters, ctx.request_stop});
    component_ = Build(ctx, *component_ctx_);
    // Timer periods are in the component's time: faster than real time, they fire as many
    // times as often on the wall clock.
    for (component::Timer& t : component_->Timers()) {
      ctx.executor.AddTimer(t.period_s / clock_->scale(), std::move(t.fire));
    }
  }
  void Activate() override { component_->Activate(); }
  void Deactivate() override { component_->Deactivate(); }
  std::string Summary() const override { return component_->Summary(); }

 protected:
  virtual std::unique_ptr<component::Component> Build(NodeContext& ctx,
                                                      component::Context& component_ctx) = 0;

  // A publisher of `topic` for the component; the node owns it.
  template <typename PubSubType>
  DdsPublisher<PubSubType, SampleOf<PubSubType>>& Publish(const std::string& topic) {
    auto p = std::make_unique<DdsPublisher<PubSubType, SampleOf<PubSubType>>>(*ctx_, topic);
    auto& ref = *p;
    publishers_.push_back(std::move(p));
    return ref;
  }

  // Hands each good sample of `topic` to `to` on the executor thread.
  template <typename PubSubType>
  Reader<PubSubType>& Feed(const std::string& topic,
                           std::function<void(const SampleOf<PubSubType>&)> to) {
    NodeContext* ctx = ctx_;
    auto r = std::make_unique<Reader<PubSubType>>(
        ctx->participant, ctx->executor, topic,
        [ctx, topic, to = std::move(to)](const typename PubSubType::type& m) {
          ctx->counters.CountIn();
          auto checked = convert::FromIdl(m);
          if (!checked.value) {
            ctx->counters.Drop(topic, checked.reason);
            return;
          }
          to(*checked.value);
        });
    auto& ref = *r;
    readers_.push_back(std::move(r));
    return ref;
  }

  NodeContext& ctx() { return *ctx_; }

  // The component's clock runs `factor` times as fast as the wall clock from now on (a
  // simulation faster than real time); its timers fire as many times as often. Call from
  // Build(), before the component reads the clock.
  void SetRealTimeFactor(double factor) { clock_->Rescale(factor); }

 private:
  // The wall clock, or time that runs `scale` times as fast from the moment it was rescaled.
  class ScaledClock : public component::Clock {
   public:
    explicit ScaledClock(std::function<int64_t()> now) : now_(std::move(now)) {}
    int64_t NowNs() const override {
      const int64_t wall = now_();
      if (scale_ == 1.0) return wall;
      return origin_ns_ + static_cast<int64_t>(static_cast<double>(wall - origin_ns_) * scale_);
    }
    void Rescale(double factor) {
      origin_ns_ = now_();
      scale_ = factor;
    }
    double scale() const { return scale_; }

   private:
    std::function<int64_t()> now_;
    int64_t origin_ns_ = 0;
    double scale_ = 1.0;
  };

  NodeContext* ctx_ = nullptr;
  std::unique_ptr<ScaledClock> clock_;
  std::unique_ptr<component::Context> component_ctx_;
  // Destroyed in reverse: readers first (no more callbacks), then the component, then the
  // publishers it wrote to.
  std::vector<std::shared_ptr<void>> publishers_;
  std::unique_ptr<component::Component> component_;
  std::vector<std::shared_ptr<void>> readers_;
};

}  // namespace stickrep::runtime
