// Fast DDS 2.9 backend of the DDS layer. The only file (with the generated type code)
// that includes Fast DDS headers.
#include "fastdds_backend.hpp"

#include <cstdio>

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>

#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <cstdint>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <map>
#include <memory>
#include <mutex>

#include "cover/dds/dds_error.hpp"
#include "fastdds_type_ops.hpp"

namespace cover::dds {
namespace {

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::Duration_t;
using eprosima::fastrtps::types::ReturnCode_t;

// A sample allocated by a type's new_* function, freed by its delete_* function.
using OwnedSample = std::unique_ptr<void, void (*)(void*)>;

Duration_t to_duration(double seconds) {
  const auto whole = static_cast<int32_t>(seconds);
  return Duration_t(whole, static_cast<uint32_t>((seconds - whole) * 1e9));
}

// The IPv4 address of a named interface, or "" when it has none.
std::string interface_address(const std::string& name) {
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return "";
  std::string address;
  for (ifaddrs* it = list; it; it = it->ifa_next) {
    if (it->ifa_addr && it->ifa_addr->sa_family == AF_INET && name == it->ifa_name) {
      char text[INET_ADDRSTRLEN] = {};
      inet_ntop(AF_INET, &reinterpret_cast<sockaddr_in*>(it->ifa_addr)->sin_addr, text,
                sizeof(text));
      address = text;
      break;
    }
  }
  freeifaddrs(list);
  return address;
}

// The builtin DDS-Security plugins, given the identity's files (checked beforehand by
// check_participant_security).
void add_security(const SecurityOptions& security, fdds::DomainParticipantQos& qos) {
  const SecurityFiles files = SecurityFiles::of(security.directory, security.identity);
  const auto uri = [](const std::string& path) { return "file://" + path; };
  const std::string auth = "dds.sec.auth.builtin.PKI-DH.";
  const std::string access = "dds.sec.access.builtin.Access-Permissions.";
  auto& properties = qos.properties().properties();
  properties.emplace_back("dds.sec.auth.plugin", "builtin.PKI-DH");
  properties.emplace_back(auth + "identity_ca", uri(files.identity_ca));
  properties.emplace_back(auth + "identity_certificate", uri(files.certificate));
  properties.emplace_back(auth + "private_key", uri(files.private_key));
  properties.emplace_back("dds.sec.access.plugin", "builtin.Access-Permissions");
  properties.emplace_back(access + "permissions_ca", uri(files.permissions_ca));
  properties.emplace_back(access + "governance", uri(files.governance));
  properties.emplace_back(access + "permissions", uri(files.permissions));
  properties.emplace_back("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

// Discovery through the server at `server` ("IPv4:port") instead of simple discovery.
void become_client(const std::string& server, fdds::DomainParticipantQos& qos) {
  const ServerAddress parsed = parse_server_address(server);
  eprosima::fastrtps::rtps::RemoteServerAttributes remote;
  // The GUID prefix `fastdds discovery -i <id>` gives its server.
  char prefix[48];
  std::snprintf(prefix, sizeof(prefix), "44.53.%02x.5f.45.50.52.4f.53.49.4d.41",
                kDiscoveryServerId);
  remote.ReadguidPrefix(prefix);
  eprosima::fastrtps::rtps::Locator_t locator;
  eprosima::fastrtps::rtps::IPLocator::setIPv4(locator, parsed.address);
  locator.port = static_cast<std::uint32_t>(parsed.port);
  remote.metatrafficUnicastLocatorList.push_back(locator);
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.discoveryProtocol = eprosima::fastrtps::rtps::DiscoveryProtocol_t::CLIENT;
  discovery.m_DiscoveryServers.push_back(remote);
}

fdds::DomainParticipantQos participant_qos(const ParticipantOptions& options) {
  // Starting from the factory default keeps a user's XML default profile in effect.
  fdds::DomainParticipantQos qos = fdds::PARTICIPANT_QOS_DEFAULT;
  qos.name(options.participant_name);
  // With an interface named, UDP is restricted to it (plus shared memory between Fast DDS
  // processes). On "lo" this matters for Cyclone: Fast DDS otherwise announces only its
  // external addresses, which a Cyclone participant bound to lo discards.
  const bool restrict_interface = !options.interface_name.empty();
  if (restrict_interface || !options.peers.empty()) {
    auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
    if (restrict_interface) {
      const std::string address = interface_address(options.interface_name);
      if (address.empty()) {
        throw DdsError("Fast DDS: network interface '" + options.interface_name +
                       "' has no IPv4 address");
      }
      udp->interfaceWhiteList.push_back(address);
    }
    // The participants a unicast peer address may hold (each takes the next port pair).
    udp->maxInitialPeersRange = static_cast<std::uint32_t>(options.participants_per_peer);
    // Unicast to a peer whose address does not resolve (a vehicle switched off, a spare
    // address) fills the socket's send buffer until ARP gives up, ~3 s, and a blocking
    // send would stall every writer of this process that long: drop instead, as a lossy
    // link would.
    udp->non_blocking_send = !options.peers.empty();
    if (options.receive_buffer_bytes > 0) {
      udp->receiveBufferSize = static_cast<std::uint32_t>(options.receive_buffer_bytes);
    }
    qos.transport().use_builtin_transports = false;
    qos.transport().user_transports.push_back(udp);
    if (options.fastdds_shared_memory) {
      qos.transport().user_transports.push_back(
          std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>());
    }
  }
  if (options.announcement_period_s > 0) {
    qos.wire_protocol().builtin.discovery_config.leaseDuration_announcementperiod =
        to_duration(options.announcement_period_s);
  }
  for (const auto& peer : options.peers) {
    eprosima::fastrtps::rtps::Locator_t locator;
    eprosima::fastrtps::rtps::IPLocator::setIPv4(locator, peer);
    qos.wire_protocol().builtin.initialPeersList.push_back(locator);
  }
  if (!options.discovery_server.empty()) become_client(options.discovery_server, qos);
  if (options.security.enabled) add_security(options.security, qos);
  return qos;
}

template <typename Qos>
void apply_common(const QosProfile& profile, Qos& qos) {
  qos.reliability().kind = profile.reliability == Reliability::Reliable
                               ? fdds::RELIABLE_RELIABILITY_QOS
                               : fdds::BEST_EFFORT_RELIABILITY_QOS;
  qos.durability().kind = profile.durability == Durability::TransientLocal
                              ? fdds::TRANSIENT_LOCAL_DURABILITY_QOS
                              : fdds::VOLATILE_DURABILITY_QOS;
  qos.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
  qos.history().depth = profile.history_depth;
  qos.resource_limits().max_instances = profile.max_instances;
  qos.resource_limits().max_samples_per_instance = profile.history_depth;
  qos.resource_limits().max_samples = profile.max_instances * profile.history_depth;
  // Data sharing (AUTO by default for bounded types) maps a file per writer into /dev/shm
  // sized from these limits, and leaves it behind: the UDP and shared-memory transports
  // serve a 100 Hz loop well enough.
  qos.data_sharing().off();
  // No deadline QoS, offered or requested: the reader counts its misses itself
  // (Reader::deadline_misses). Fast DDS reschedules a deadline timer on every write and every
  // sample received, a wake-up of its event thread each: over a quarter of the CPU of
  // Scenario 2 in lockstep (1.34 -> 0.96 s). A reader of an older build, which requests a
  // deadline, therefore does not match a Fast DDS writer of this one.
}

// The writers of other participants that discovery reported, and who wants to hear of
// them. Installed with the participant, so that no writer discovered before a watch starts
// is missed: a new watch first hears every writer known. Handlers run under the mutex, so
// none runs once remove() returned.
class PublicationDirectory final : public fdds::DomainParticipantListener {
 public:
  std::uint64_t add(PublicationHandler handler) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [guid, publication] : known_) handler(publication);
    handlers_.emplace(next_id_, std::move(handler));
    return next_id_++;
  }
  void remove(std::uint64_t id) {
    std::lock_guard<std::mutex> lock(mutex_);
    handlers_.erase(id);
  }

  void on_publisher_discovery(fdds::DomainParticipant* participant,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override {
    using Info = eprosima::fastrtps::rtps::WriterDiscoveryInfo;
    const auto& writer = info.info;
    if (writer.guid().guidPrefix == participant->guid().guidPrefix) return;  // our own
    std::lock_guard<std::mutex> lock(mutex_);
    if (info.status == Info::REMOVED_WRITER) {
      known_.erase(writer.guid());
      return;
    }
    if (info.status != Info::DISCOVERED_WRITER) return;
    const DiscoveredPublication publication{writer.topicName().to_string(),
                                            writer.typeName().to_string()};
    known_[writer.guid()] = publication;
    for (const auto& [id, handler] : handlers_) handler(publication);
  }

 private:
  std::mutex mutex_;
  std::map<eprosima::fastrtps::rtps::GUID_t, DiscoveredPublication> known_;
  std::map<std::uint64_t, PublicationHandler> handlers_;
  std::uint64_t next_id_ = 0;
};

class FastPublicationWatch final : public PublicationWatchBackend {
 public:
  FastPublicationWatch(std::shared_ptr<PublicationDirectory> directory, PublicationHandler handler)
      : directory_(std::move(directory)), id_(directory_->add(std::move(handler))) {}
  ~FastPublicationWatch() override { directory_->remove(id_); }

 private:
  std::shared_ptr<PublicationDirectory> directory_;
  std::uint64_t id_;
};

// The participant and its publisher/subscriber; shared by every writer and reader so
// that it outlives them whatever order the user destroys things in.
class FastCore {
 public:
  explicit FastCore(const ParticipantOptions& options) {
    auto* factory = fdds::DomainParticipantFactory::get_instance();
    // Discovery callbacks only (StatusMask::none): the readers keep their own listeners.
    participant_ = factory->create_participant(options.domain_id, participant_qos(options),
                                               publications_.get(), fdds::StatusMask::none());
    if (!participant_) {
      throw DdsError("Fast DDS: cannot create a participant on domain " +
                     std::to_string(options.domain_id) +
                     (options.security.enabled ? " with identity " + options.security.identity
                                               : std::string()) +
                     " (see the Fast DDS log above)");
    }
    publisher_ = participant_->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
    subscriber_ = participant_->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
    if (!publisher_ || !subscriber_) throw DdsError("Fast DDS: cannot create publisher/subscriber");
  }
  ~FastCore() {
    participant_->delete_contained_entities();
    fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }

  fdds::Topic* topic(const TypeSupport& type, const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (auto found = topics_.find(name); found != topics_.end()) {
      if (found->second->get_type_name() != type.type_name) {
        throw DdsError("Fast DDS: topic '" + name + "' already used with type " +
                       found->second->get_type_name());
      }
      return found->second;
    }
    if (!participant_->find_type(type.type_name).get()) {
      fdds::TypeSupport support(type.fastdds->new_topic_type());
      if (support.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
        throw DdsError(std::string("Fast DDS: cannot register type ") + type.type_name);
      }
    }
    fdds::Topic* created =
        participant_->create_topic(name, type.type_name, fdds::TOPIC_QOS_DEFAULT);
    if (!created) throw DdsError("Fast DDS: cannot create topic '" + name + "'");
    topics_[name] = created;
    return created;
  }

  fdds::Publisher* publisher() { return publisher_; }
  fdds::Subscriber* subscriber() { return subscriber_; }
  const std::shared_ptr<PublicationDirectory>& publications() const { return publications_; }

 private:
  std::mutex mutex_;
  // Before the participant: it outlives the participant that calls it.
  std::shared_ptr<PublicationDirectory> publications_ = std::make_shared<PublicationDirectory>();
  fdds::DomainParticipant* participant_ = nullptr;
  fdds::Publisher* publisher_ = nullptr;
  fdds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, fdds::Topic*> topics_;
};

class FastWriter final : public WriterBackend {
 public:
  FastWriter(std::shared_ptr<FastCore> core, const TypeSupport& type, const std::string& topic,
             const QosProfile& profile)
      : core_(std::move(core)),
        ops_(*type.fastdds),
        sample_(ops_.new_vendor_sample(), ops_.delete_vendor_sample),
        topic_name_(topic) {
    fdds::DataWriterQos qos = fdds::DATAWRITER_QOS_DEFAULT;
    apply_common(profile, qos);
    // A 100 ms heartbeat (default 3 s) stops the loss of early reliable samples.
    qos.reliable_writer_qos().times.heartbeatPeriod = to_duration(0.1);
    // Every reliable sample sent restarts a nack-suppression timer per matched reader; with
    // the default duration 0 that timer fires at once, a wake-up of the event thread per
    // sample and reader. While a timer is pending a restart is a no-op, so with 20 ms it
    // wakes at most once per 20 ms (lockstep ticks 0.2-0.5 ms apart). A reader's request
    // for a sample younger than that waits for the next heartbeat (<= 100 ms): keep-last-1
    // topics have sent a newer one by then.
    qos.reliable_writer_qos().times.nackSupressionDuration = to_duration(0.02);
    writer_ = core_->publisher()->create_datawriter(core_->topic(type, topic), qos);
    if (!writer_) {
      throw DdsError("Fast DDS: cannot create a writer on '" + topic +
                     "' (with security on: this identity's permissions do not allow it)");
    }
  }
  ~FastWriter() override { core_->publisher()->delete_datawriter(writer_); }
  bool write(const void* neutral) override {
    std::lock_guard<std::mutex> lock(mutex_);
    ops_.to_vendor(neutral, sample_.get());
    // Fast CDR throws when a sample outgrows the type's computed maximum (a string beyond
    // fastddsgen's default bound of 255 characters): a refused write, not a dead process.
    try {
      return writer_->write(sample_.get());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "Fast DDS: sample refused on '%s': %s\n", topic_name_.c_str(), e.what());
      return false;
    }
  }
  bool wait_for_acknowledgments(std::chrono::milliseconds timeout) override {
    return writer_->wait_for_acknowledgments(to_duration(timeout.count() * 1e-3)) ==
           ReturnCode_t::RETCODE_OK;
  }
  std::size_t matched_readers() const override {
    fdds::PublicationMatchedStatus status;
    writer_->get_publication_matched_status(status);
    return static_cast<std::size_t>(status.current_count);
  }

 private:
  std::shared_ptr<FastCore> core_;
  const FastDdsTypeOps& ops_;
  std::mutex mutex_;
  OwnedSample sample_;  // vendor sample reused by every write: no allocation per sample
  std::string topic_name_;
  fdds::DataWriter* writer_ = nullptr;
};

class FastReader final : public ReaderBackend, private fdds::DataReaderListener {
 public:
  FastReader(std::shared_ptr<FastCore> core, const TypeSupport& type, const std::string& topic,
             const QosProfile& profile, SampleHandler handler)
      : core_(std::move(core)),
        type_(type),
        handler_(std::move(handler)),
        vendor_sample_(type.fastdds->new_vendor_sample(), type.fastdds->delete_vendor_sample),
        neutral_sample_(type.new_sample(), type.delete_sample) {
    fdds::DataReaderQos qos = fdds::DATAREADER_QOS_DEFAULT;
    apply_common(profile, qos);
    if (profile.acknowledgement_delay_s > 0) {
      qos.reliable_reader_qos().times.heartbeatResponseDelay =
          to_duration(profile.acknowledgement_delay_s);
    }
    reader_ = core_->subscriber()->create_datareader(core_->topic(type, topic), qos, this,
                                                     fdds::StatusMask::data_available());
    if (!reader_) {
      throw DdsError("Fast DDS: cannot create a reader on '" + topic +
                     "' (with security on: this identity's permissions do not allow it)");
    }
  }
  ~FastReader() override {
    reader_->set_listener(nullptr);
    core_->subscriber()->delete_datareader(reader_);
  }
  std::size_t matched_writers() const override {
    fdds::SubscriptionMatchedStatus status;
    reader_->get_subscription_matched_status(status);
    return static_cast<std::size_t>(status.current_count);
  }

 private:
  void on_data_available(fdds::DataReader* reader) override {
    fdds::SampleInfo info;
    // A malformed sample from a foreign writer must not end the process: skip it.
    while (true) {
      try {
        if (reader->take_next_sample(vendor_sample_.get(), &info) != ReturnCode_t::RETCODE_OK) {
          return;
        }
      } catch (const std::exception& e) {
        std::fprintf(stderr, "Fast DDS: undecodable sample dropped: %s\n", e.what());
        continue;
      }
      if (!info.valid_data) continue;
      type_.fastdds->from_vendor(vendor_sample_.get(), neutral_sample_.get());
      handler_(neutral_sample_.get());
    }
  }
  std::shared_ptr<FastCore> core_;
  const TypeSupport& type_;
  SampleHandler handler_;
  // Owned from the start, so a constructor that throws frees them.
  OwnedSample vendor_sample_;
  OwnedSample neutral_sample_;
  fdds::DataReader* reader_ = nullptr;
};

class FastParticipant final : public ParticipantBackend {
 public:
  explicit FastParticipant(const ParticipantOptions& options)
      : core_(std::make_shared<FastCore>(options)) {}
  std::unique_ptr<WriterBackend> create_writer(const TypeSupport& type, const std::string& topic,
                                               const QosProfile& qos) override {
    return std::make_unique<FastWriter>(core_, type, topic, qos);
  }
  std::unique_ptr<ReaderBackend> create_reader(const TypeSupport& type, const std::string& topic,
                                               const QosProfile& qos,
                                               SampleHandler handler) override {
    return std::make_unique<FastReader>(core_, type, topic, qos, std::move(handler));
  }
  std::unique_ptr<PublicationWatchBackend> watch_publications(PublicationHandler handler) override {
    return std::make_unique<FastPublicationWatch>(core_->publications(), std::move(handler));
  }

 private:
  std::shared_ptr<FastCore> core_;
};

}  // namespace

std::unique_ptr<ParticipantBackend> make_fastdds_participant(const ParticipantOptions& options) {
  return std::make_unique<FastParticipant>(options);
}

}  // namespace cover::dds
