#pragma once

#include <functional>
#include <memory>
#include <string>

namespace cover::dds {

// A writer of another participant in the domain, as discovery announced it.
struct DiscoveredPublication {
  std::string topic_name;  // cover/uav/0/rel/1
  std::string type_name;   // cover::idl::RelativeState (the writer's registered type name)
};

// Called on a vendor thread for every discovered writer; keep it short, and create no
// reader or writer in it (the vendor holds its discovery locks): hand the name to a thread
// of yours.
using PublicationHandler = std::function<void(const DiscoveredPublication&)>;

// The vendor's side of a PublicationWatch.
class PublicationWatchBackend {
 public:
  virtual ~PublicationWatchBackend() = default;
};

// Reports the writers of the other participants of the domain (other processes, and other
// participants of this one): first every writer discovery already knows, then each one as it
// is discovered, on either vendor (Fast DDS: the participant's discovery listener; Cyclone:
// the DCPSPublication built-in topic). A tool that records or shows "whatever is published"
// subscribes to what this reports, as `ros2 bag record -a` does, instead of to every
// topic that could exist. A writer that goes away and comes back is reported again. No
// handler call runs past the watch's destruction. Made by Participant::watch_publications.
class PublicationWatch {
 public:
  PublicationWatch() = default;
  explicit PublicationWatch(std::unique_ptr<PublicationWatchBackend> backend)
      : backend_(std::move(backend)) {}

  // Stops the reports; idempotent.
  void stop() { backend_.reset(); }
  explicit operator bool() const { return static_cast<bool>(backend_); }

 private:
  std::unique_ptr<PublicationWatchBackend> backend_;
};

}  // namespace cover::dds
