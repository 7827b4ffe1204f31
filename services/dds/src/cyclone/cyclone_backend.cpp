// Cyclone DDS 0.10 backend of the DDS layer. The only file (with the generated type
// code) that includes Cyclone headers.
#include "cyclone_backend.hpp"

#include <dds/dds.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <vector>

#include "cover/dds/dds_error.hpp"
#include "cyclone_type_ops.hpp"

namespace cover::dds {
namespace {

std::string describe(dds_return_t rc) {
  return std::string(dds_strretcode(rc));
}

// Cyclone's configuration for this participant, unless $CYCLONEDDS_URI says otherwise.
std::string cyclone_config(const ParticipantOptions& options) {
  std::string xml = "<CycloneDDS><Domain id=\"any\"><General>";
  if (!options.interface_name.empty()) {
    // Cyclone treats `lo` as not multicast-capable and then discovers Fast DDS peers
    // only every 8 s by unicast; telling it multicast works makes matching take ~5 ms.
    const bool loopback = options.interface_name == "lo";
    xml += "<Interfaces><NetworkInterface name=\"" + options.interface_name + "\"" +
           (loopback && options.peers.empty() ? " multicast=\"true\"" : "") + "/></Interfaces>";
  }
  if (!options.peers.empty()) xml += "<AllowMulticast>false</AllowMulticast>";
  xml += "</General><Discovery>";
  if (!options.peers.empty()) {
    xml += "<ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>" +
           std::to_string(options.participants_per_peer - 1) + "</MaxAutoParticipantIndex><Peers>";
    for (const auto& peer : options.peers) xml += "<Peer address=\"" + peer + "\"/>";
    xml += "</Peers>";
  }
  if (options.announcement_period_s > 0) {
    const long period_ms = std::max(1L, std::lround(options.announcement_period_s * 1e3));
    xml += "<SPDPInterval>" + std::to_string(period_ms) + " ms</SPDPInterval>";
  }
  xml += "</Discovery></Domain></CycloneDDS>";
  return xml;
}

// The participant QoS: the DDS-Security plugins and the identity's files when security
// is on (checked beforehand by check_participant_security), else nothing.
dds_qos_t* participant_qos(const SecurityOptions& security) {
  if (!security.enabled) return nullptr;
  const SecurityFiles files = SecurityFiles::of(security.directory, security.identity);
  dds_qos_t* qos = dds_create_qos();
  const auto set = [qos](const std::string& name, const std::string& value) {
    dds_qset_prop(qos, name.c_str(), value.c_str());
  };
  const auto plugin = [&](const std::string& kind, const std::string& library,
                          const std::string& suffix) {
    set("dds.sec." + kind + ".library.path", library);
    set("dds.sec." + kind + ".library.init", "init_" + suffix);
    set("dds.sec." + kind + ".library.finalize", "finalize_" + suffix);
  };
  plugin("auth", "dds_security_auth", "authentication");
  plugin("crypto", "dds_security_crypto", "crypto");
  plugin("access", "dds_security_ac", "access_control");
  set("dds.sec.auth.identity_ca", "file:" + files.identity_ca);
  set("dds.sec.auth.identity_certificate", "file:" + files.certificate);
  set("dds.sec.auth.private_key", "file:" + files.private_key);
  set("dds.sec.access.permissions_ca", "file:" + files.permissions_ca);
  set("dds.sec.access.governance", "file:" + files.governance);
  set("dds.sec.access.permissions", "file:" + files.permissions);
  return qos;
}

dds_qos_t* make_qos(const QosProfile& profile) {
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos,
                       profile.reliability == Reliability::Reliable ? DDS_RELIABILITY_RELIABLE
                                                                    : DDS_RELIABILITY_BEST_EFFORT,
                       DDS_MSECS(100));
  dds_qset_durability(qos, profile.durability == Durability::TransientLocal
                               ? DDS_DURABILITY_TRANSIENT_LOCAL
                               : DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, profile.history_depth);
  dds_qset_resource_limits(qos, profile.max_instances * profile.history_depth,
                           profile.max_instances, profile.history_depth);
  // No requested deadline: the reader counts its misses itself (Reader::deadline_misses),
  // and a reader requesting one would not match a Fast DDS writer, which offers none
  // (fastdds_backend.cpp).
  return qos;
}

dds_qos_t* make_writer_qos(const QosProfile& profile) {
  dds_qos_t* qos = make_qos(profile);
  // Offered on the wire, where it costs nothing measurable: a reader that requests a deadline
  // (a build before readers counted their own misses, another tool) still matches.
  if (profile.deadline_s > 0) {
    dds_qset_deadline(qos, static_cast<dds_duration_t>(profile.deadline_s * 1e9));
  }
  // Cyclone keeps transient-local data for late joiners by the durability-service history
  // (default keep-last 1), not the writer's history: give late joiners the full depth.
  if (profile.durability == Durability::TransientLocal) {
    dds_qset_durability_service(qos, 0, DDS_HISTORY_KEEP_LAST, profile.history_depth,
                                DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  }
  return qos;
}

// The participant handle, shared by writers and readers so it outlives them.
class CycloneCore {
 public:
  explicit CycloneCore(const ParticipantOptions& options) {
    const auto domain = static_cast<dds_domainid_t>(options.domain_id);
    if (!std::getenv("CYCLONEDDS_URI")) {
      const std::string config = cyclone_config(options);
      const dds_entity_t created = dds_create_domain(domain, config.c_str());
      // PRECONDITION_NOT_MET: this process already created the domain; reuse it.
      if (created < 0 && created != DDS_RETCODE_PRECONDITION_NOT_MET) {
        throw DdsError("Cyclone DDS: cannot create domain " + std::to_string(options.domain_id) +
                       ": " + describe(created));
      }
      if (created > 0) domain_ = created;
    }
    dds_qos_t* qos = participant_qos(options.security);
    participant_ = dds_create_participant(domain, qos, nullptr);
    if (qos) dds_delete_qos(qos);
    if (participant_ < 0) {
      throw DdsError("Cyclone DDS: cannot create a participant on domain " +
                     std::to_string(options.domain_id) +
                     (options.security.enabled ? " with identity " + options.security.identity
                                               : std::string()) +
                     ": " + describe(participant_));
    }
  }
  ~CycloneCore() {
    dds_delete(participant_);
    if (domain_ > 0) dds_delete(domain_);
  }

  dds_entity_t topic(const TypeSupport& type, const std::string& name) {
    const dds_entity_t topic =
        dds_create_topic(participant_, type.cyclone->descriptor, name.c_str(), nullptr, nullptr);
    if (topic < 0) {
      throw DdsError("Cyclone DDS: cannot create topic '" + name + "': " + describe(topic));
    }
    return topic;
  }
  dds_entity_t participant() const { return participant_; }

 private:
  dds_entity_t domain_ = 0;
  dds_entity_t participant_ = 0;
};

class CycloneWriter final : public WriterBackend {
 public:
  CycloneWriter(std::shared_ptr<CycloneCore> core, const TypeSupport& type,
                const std::string& topic, const QosProfile& profile)
      : core_(std::move(core)), ops_(*type.cyclone), sample_(ops_.vendor_sample_size) {
    dds_qos_t* qos = make_writer_qos(profile);
    writer_ = dds_create_writer(core_->participant(), core_->topic(type, topic), qos, nullptr);
    dds_delete_qos(qos);
    if (writer_ < 0) {
      throw DdsError("Cyclone DDS: cannot create a writer on '" + topic +
                     "': " + describe(writer_));
    }
  }
  ~CycloneWriter() override { dds_delete(writer_); }

  bool write(const void* neutral) override {
    std::lock_guard<std::mutex> lock(mutex_);
    std::fill(sample_.begin(), sample_.end(), 0);
    ops_.to_vendor(neutral, sample_.data());
    const dds_return_t rc = dds_write(writer_, sample_.data());
    // Frees the strings and sequences to_vendor allocated, not the buffer itself.
    dds_sample_free(sample_.data(), ops_.descriptor, DDS_FREE_CONTENTS);
    return rc == DDS_RETCODE_OK;
  }
  bool wait_for_acknowledgments(std::chrono::milliseconds timeout) override {
    return dds_wait_for_acks(writer_, DDS_MSECS(timeout.count())) == DDS_RETCODE_OK;
  }
  std::size_t matched_readers() const override {
    dds_publication_matched_status_t status{};
    dds_get_publication_matched_status(writer_, &status);
    return status.current_count;
  }

 private:
  std::shared_ptr<CycloneCore> core_;
  const CycloneTypeOps& ops_;
  std::mutex mutex_;
  std::vector<unsigned char> sample_;  // sized once: the vendor struct, reused per write
  dds_entity_t writer_ = 0;
};

class CycloneReader final : public ReaderBackend {
 public:
  CycloneReader(std::shared_ptr<CycloneCore> core, const TypeSupport& type,
                const std::string& topic, const QosProfile& profile, SampleHandler handler)
      : core_(std::move(core)),
        type_(type),
        handler_(std::move(handler)),
        neutral_sample_(type.new_sample(), type.delete_sample) {
    dds_qos_t* qos = make_qos(profile);
    dds_listener_t* listener = dds_create_listener(this);
    dds_lset_data_available(listener, &CycloneReader::on_data_available);
    reader_ = dds_create_reader(core_->participant(), core_->topic(type, topic), qos, listener);
    dds_delete_listener(listener);
    dds_delete_qos(qos);
    if (reader_ < 0) {
      throw DdsError("Cyclone DDS: cannot create a reader on '" + topic +
                     "': " + describe(reader_));
    }
  }
  ~CycloneReader() override {
    dds_delete(reader_);  // waits for a listener call in progress
  }
  std::size_t matched_writers() const override {
    dds_subscription_matched_status_t status{};
    dds_get_subscription_matched_status(reader_, &status);
    return status.current_count;
  }

 private:
  static void on_data_available(dds_entity_t reader, void* self) {
    static_cast<CycloneReader*>(self)->take_all(reader);
  }
  void take_all(dds_entity_t reader) {
    void* samples[1] = {nullptr};
    dds_sample_info_t info{};
    // Loaned samples: no copy into a vendor buffer, only the conversion to neutral.
    while (dds_take(reader, samples, &info, 1, 1) > 0) {
      if (info.valid_data) {
        type_.cyclone->from_vendor(samples[0], neutral_sample_.get());
        handler_(neutral_sample_.get());
      }
      dds_return_loan(reader, samples, 1);
      samples[0] = nullptr;
    }
  }

  std::shared_ptr<CycloneCore> core_;
  const TypeSupport& type_;
  SampleHandler handler_;
  // Owned from the start, so a constructor that throws (topic or reader creation) frees it.
  std::unique_ptr<void, void (*)(void*)> neutral_sample_;
  dds_entity_t reader_ = 0;
};

// The writers of other participants, from the DCPSPublication built-in topic: its reader
// gets every writer known when it is made (the topic's instances), then each new one.
class CyclonePublicationWatch final : public PublicationWatchBackend {
 public:
  CyclonePublicationWatch(std::shared_ptr<CycloneCore> core, PublicationHandler handler)
      : core_(std::move(core)), handler_(std::move(handler)) {
    if (const dds_return_t rc = dds_get_guid(core_->participant(), &own_); rc != DDS_RETCODE_OK) {
      throw DdsError("Cyclone DDS: cannot read the participant's GUID: " + describe(rc));
    }
    dds_listener_t* listener = dds_create_listener(this);
    dds_lset_data_available(listener, &CyclonePublicationWatch::on_data_available);
    reader_ = dds_create_reader(core_->participant(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr,
                                listener);
    dds_delete_listener(listener);
    if (reader_ < 0) {
      throw DdsError("Cyclone DDS: cannot read the DCPSPublication topic: " + describe(reader_));
    }
    take_all(reader_);  // the writers known before the listener could fire
  }
  ~CyclonePublicationWatch() override {
    dds_delete(reader_);  // waits for a listener call in progress
  }

 private:
  static void on_data_available(dds_entity_t reader, void* self) {
    static_cast<CyclonePublicationWatch*>(self)->take_all(reader);
  }
  void take_all(dds_entity_t reader) {
    std::lock_guard<std::mutex> lock(mutex_);  // the constructor's take and the listener's
    constexpr int kBatch = 16;
    void* samples[kBatch] = {};
    dds_sample_info_t infos[kBatch];
    int taken = 0;
    while ((taken = dds_take(reader, samples, infos, kBatch, kBatch)) > 0) {
      for (int i = 0; i < taken; ++i) {
        const auto* writer = static_cast<const dds_builtintopic_endpoint_t*>(samples[i]);
        if (infos[i].valid_data && infos[i].instance_state == DDS_IST_ALIVE &&
            std::memcmp(&writer->participant_key, &own_, sizeof own_) != 0) {
          handler_(DiscoveredPublication{writer->topic_name, writer->type_name});
        }
      }
      dds_return_loan(reader, samples, taken);
      std::fill(std::begin(samples), std::end(samples), nullptr);
    }
  }

  std::shared_ptr<CycloneCore> core_;
  PublicationHandler handler_;
  std::mutex mutex_;
  dds_guid_t own_{};
  dds_entity_t reader_ = 0;
};

class CycloneParticipant final : public ParticipantBackend {
 public:
  explicit CycloneParticipant(const ParticipantOptions& options)
      : core_(std::make_shared<CycloneCore>(options)) {}
  std::unique_ptr<WriterBackend> create_writer(const TypeSupport& type, const std::string& topic,
                                               const QosProfile& qos) override {
    return std::make_unique<CycloneWriter>(core_, type, topic, qos);
  }
  std::unique_ptr<ReaderBackend> create_reader(const TypeSupport& type, const std::string& topic,
                                               const QosProfile& qos,
                                               SampleHandler handler) override {
    return std::make_unique<CycloneReader>(core_, type, topic, qos, std::move(handler));
  }
  std::unique_ptr<PublicationWatchBackend> watch_publications(PublicationHandler handler) override {
    return std::make_unique<CyclonePublicationWatch>(core_, std::move(handler));
  }

 private:
  std::shared_ptr<CycloneCore> core_;
};

}  // namespace

std::unique_ptr<ParticipantBackend> make_cyclone_participant(const ParticipantOptions& options) {
  return std::make_unique<CycloneParticipant>(options);
}

}  // namespace cover::dds
