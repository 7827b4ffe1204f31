#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <utility>

#include "cover/dds/qos.hpp"

namespace cover::dds {

template <typename T>
class Topic;
template <typename T, typename... Ids>
struct TopicDescriptor;
template <typename T>
Topic<T> catalogued_topic(std::string_view name);

// A concrete topic bound to its message type: a name and the QoS its writers and readers
// use. Only the catalogue (topics.hpp) and `uncatalogued` create one, so a writer or
// reader can only be made for the type and QoS a catalogued name was defined with.
template <typename T>
class Topic {
 public:
  const std::string& name() const { return name_; }
  const QosProfile& qos() const { return qos_; }
  bool catalogued() const { return catalogued_; }

  // The same topic with a keep-last history of at least `depth`: for a reader whose
  // callback may run late and must not lose a sample meanwhile (the flight recorder).
  // History is no part of DDS's request/offer matching: it still matches every writer.
  Topic with_history_depth(int depth) const {
    Topic deeper = *this;
    deeper.qos_.history_depth = std::max(deeper.qos_.history_depth, depth);
    return deeper;
  }

  // The same topic without a deadline: for a reader that does not watch the sample period
  // (the flight recorder); its deadline_misses() stays 0.
  Topic without_deadline() const {
    Topic relaxed = *this;
    relaxed.qos_.deadline_s = 0.0;
    return relaxed;
  }

  // The same topic, its reliable reader acknowledging at most every `delay_s`: for a
  // reader that only logs (a recorder), whose acknowledgement per sample would cost a
  // wake-up of its own per sample. The writer keeps unacknowledged samples that long.
  Topic with_acknowledgement_delay(double delay_s) const {
    Topic batched = *this;
    batched.qos_.acknowledgement_delay_s = delay_s;
    return batched;
  }

  // For tests and benchmarks only: a topic outside the catalogue (e.g. "cover_test/...").
  // Creating a writer/reader on it checks the name is NOT a catalogued pattern (throws
  // DdsError otherwise), so it cannot bypass the catalogue's type and QoS.
  static Topic uncatalogued(std::string name, QosProfile qos) {
    return Topic(std::move(name), std::move(qos), false);
  }

 private:
  Topic(std::string name, QosProfile qos, bool catalogued)
      : name_(std::move(name)), qos_(std::move(qos)), catalogued_(catalogued) {}

  template <typename, typename...>
  friend struct TopicDescriptor;
  template <typename U>
  friend Topic<U> catalogued_topic(std::string_view name);

  std::string name_;
  QosProfile qos_;
  bool catalogued_;
};

// Throws DdsError when `name` matches a catalogue pattern (defined with the catalogue).
void require_uncatalogued(std::string_view name);

}  // namespace cover::dds
