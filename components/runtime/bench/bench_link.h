#pragma once

#include <functional>
#include <memory>
#include <string>

#include "runtime/qos_catalog.h"
#include "sensors.h"

namespace stickrep::runtime::bench {

// The two ways a sample can travel: through the runtime layer (Participant, Writer, Reader
// and an Executor) or through a plain Fast DDS DataWriter/DataReader pair.
enum class Impl { kRuntime, kRaw };
const char* ToString(Impl impl);

// The topics of the ping-pong: the driver writes pings, the echo writes them back as pongs.
inline constexpr const char* kPingTopic = "bench/ping";
inline constexpr const char* kPongTopic = "bench/pong";

// Where one side of the ping-pong lives and which QoS its two topics use.
struct LinkConfig {
  int domain_id = 90;
  std::string name;    // participant name
  QosCatalog catalog;  // knows kPingTopic and kPongTopic
  std::string out_topic;
  std::string in_topic;
  std::string profile_xml;  // Fast DDS XML file whose default profile both sides use ("": none)
  // DDS Security from deploy/security/make-keys.sh's directory, as identity "bench" (its
  // governance protects bench/* as commands and camera frames are); "": plain DDS.
  std::string security_dir;
};

// One side of the ping-pong: a writer on `out_topic` and a reader on `in_topic` whose
// samples go to a callback (runtime: on the executor thread; raw: on the DDS listener
// thread). Send() is called from one thread only.
class PingPongLink {
 public:
  using OnSample = std::function<void(const msgs::Image&)>;
  virtual ~PingPongLink() = default;
  // Writes one sample; false if DDS refused it.
  virtual bool Send(msgs::Image& sample) = 0;
  // True once the writer and the reader each match at least one remote endpoint.
  virtual bool Matched() const = 0;
};

// The raw implementation creates its participant with the factory's default participant QoS
// (the runtime one reads LinkConfig::profile_xml as every StickRep process does); this makes
// the default participant profile (is_default_profile="true") of a Fast DDS XML file that
// default, for every participant the process creates afterwards. Throws InputError if the
// file cannot be loaded or has no default participant profile.
void UseDefaultParticipantProfile(const std::string& xml_file);

// Throws std::runtime_error if DDS fails.
std::unique_ptr<PingPongLink> MakeLink(Impl impl, const LinkConfig& config,
                                       PingPongLink::OnSample on_sample);

// A catalog in which kPingTopic and kPongTopic both use `profile` (taken from another
// catalog, normally configs/qos.yaml), so that both implementations get the same QoS.
QosCatalog BenchCatalog(const QosProfile& profile, const std::string& source_file);

}  // namespace stickrep::runtime::bench
