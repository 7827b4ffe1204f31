#pragma once

#include <memory>
#include <string>

#include "cover/dds/backend.hpp"
#include "cover/dds/participant_options.hpp"
#include "cover/dds/publication_watch.hpp"
#include "cover/dds/reader.hpp"
#include "cover/dds/topic.hpp"
#include "cover/dds/writer.hpp"
#include "cover/msg/type_support.hpp"

namespace cover::dds {

// One DDS domain participant on the chosen vendor. Creates typed writers and readers on
// the catalogue's topics (topics.hpp): a topic brings its message type and QoS, so a
// writer of the wrong type or QoS cannot be made.
//
// Writers and readers share ownership of the vendor participant with this object, so they
// may be destroyed before or after it, in any order; the vendor participant goes with the
// last of them. A reader's callback may run until its reader is destroyed: destroy readers
// before what their callbacks capture.
class Participant {
 public:
  // Throws DdsError with a clear message (bad domain id, vendor failure).
  explicit Participant(const ParticipantOptions& options);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  Vendor vendor() const { return options_.vendor; }
  int domain_id() const { return options_.domain_id; }

  // Throws DdsError on a vendor failure, or for an uncatalogued topic with a catalogued name.
  template <typename T>
  Writer<T> make_writer(const Topic<T>& topic) {
    check(topic);
    return Writer<T>(backend_->create_writer(type_support<T>(), topic.name(), topic.qos()));
  }

  // Latest-sample style: poll `reader.latest()` or wait with `wait_for_sample`.
  template <typename T>
  Reader<T> make_reader(const Topic<T>& topic) {
    return make_reader(topic, nullptr);
  }

  // Callback style: `on_sample` runs on the vendor's receive thread for every sample;
  // keep it short. The latest sample is kept as well.
  template <typename T>
  Reader<T> make_reader(const Topic<T>& topic, typename Reader<T>::Callback on_sample) {
    check(topic);
    auto state =
        std::make_shared<typename Reader<T>::State>(std::move(on_sample), topic.qos().deadline_s);
    auto handler = [state](const void* sample) { state->deliver(*static_cast<const T*>(sample)); };
    return Reader<T>(backend_->create_reader(type_support<T>(), topic.name(), topic.qos(), handler),
                     state);
  }

  // Reports every writer of the other participants of the domain, those known now and each
  // one discovered later, to `on_publication` (publication_watch.hpp: a vendor thread, keep
  // it short, make no reader or writer in it) until the watch is destroyed.
  PublicationWatch watch_publications(PublicationHandler on_publication) {
    return PublicationWatch(backend_->watch_publications(std::move(on_publication)));
  }

 private:
  template <typename T>
  static void check(const Topic<T>& topic) {
    if (!topic.catalogued()) require_uncatalogued(topic.name());
  }

  ParticipantOptions options_;
  std::unique_ptr<ParticipantBackend> backend_;
};

}  // namespace cover::dds
