#pragma once

#include <memory>
#include <string>

#include "cover/dds/backend.hpp"
#include "cover/dds/participant_options.hpp"
#include "cover/dds/reader.hpp"
#include "cover/dds/writer.hpp"
#include "cover/msg/type_support.hpp"

namespace cover::dds {

// One DDS domain participant on the chosen vendor. Creates typed writers and readers
// for the generated `cover::msg` types. Destroying the participant after its writers and
// readers is the caller's job (declare it first).
class Participant {
 public:
  // Throws DdsError with a clear message (bad domain id, vendor failure).
  explicit Participant(const ParticipantOptions& options);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  Vendor vendor() const { return options_.vendor; }
  int domain_id() const { return options_.domain_id; }

  template <typename T>
  Writer<T> make_writer(const std::string& topic, const QosProfile& qos) {
    return Writer<T>(backend_->create_writer(type_support<T>(), topic, qos));
  }

  // Latest-sample style: poll `reader.latest()` or wait with `wait_for_sample`.
  template <typename T>
  Reader<T> make_reader(const std::string& topic, const QosProfile& qos) {
    return make_reader<T>(topic, qos, nullptr);
  }

  // Callback style: `on_sample` runs on the vendor's receive thread for every sample;
  // keep it short. The latest sample is kept as well.
  template <typename T>
  Reader<T> make_reader(const std::string& topic, const QosProfile& qos,
                        typename Reader<T>::Callback on_sample) {
    auto state = std::make_shared<typename Reader<T>::State>(std::move(on_sample));
    auto handler = [state](const void* sample) { state->deliver(*static_cast<const T*>(sample)); };
    return Reader<T>(backend_->create_reader(type_support<T>(), topic, qos, handler), state);
  }

 private:
  ParticipantOptions options_;
  std::unique_ptr<ParticipantBackend> backend_;
};

}  // namespace cover::dds
