#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "cover/dds/publication_watch.hpp"
#include "cover/dds/qos.hpp"
#include "cover/dds/type_support.hpp"

namespace cover::dds {

// The vendor-neutral interface the two backends implement. Users hold typed
// `Writer<T>` / `Reader<T>` (writer.hpp, reader.hpp), which wrap these.

class WriterBackend {
 public:
  virtual ~WriterBackend() = default;
  // Writes one vendor-neutral sample; false on a vendor error (never throws).
  virtual bool write(const void* sample) = 0;
  virtual std::size_t matched_readers() const = 0;
  // Reliable topics: waits until matched readers acknowledged every sample written.
  virtual bool wait_for_acknowledgments(std::chrono::milliseconds timeout) = 0;
};

// Called from the vendor's receive thread with a vendor-neutral sample.
using SampleHandler = std::function<void(const void* sample)>;

class ReaderBackend {
 public:
  virtual ~ReaderBackend() = default;
  virtual std::size_t matched_writers() const = 0;
};

class ParticipantBackend {
 public:
  virtual ~ParticipantBackend() = default;
  virtual std::unique_ptr<WriterBackend> create_writer(const TypeSupport& type,
                                                       const std::string& topic,
                                                       const QosProfile& qos) = 0;
  virtual std::unique_ptr<ReaderBackend> create_reader(const TypeSupport& type,
                                                       const std::string& topic,
                                                       const QosProfile& qos,
                                                       SampleHandler handler) = 0;
  // Starts reporting the writers of other participants (publication_watch.hpp).
  virtual std::unique_ptr<PublicationWatchBackend> watch_publications(
      PublicationHandler handler) = 0;
};

}  // namespace cover::dds
