#pragma once

#include <string>

#include "cover/dds/participant_options.hpp"

namespace cover::cli {

enum class TopicsFormat {
  Table,     // for reading in a terminal
  Json,      // one JSON object per topic and line
  Markdown,  // exactly the table of docs/topics.md, which a test compares with the catalogue
};
// `cover topics`: prints the topic catalogue.
int list_topics(TopicsFormat format);

struct EchoRequest {
  std::string topic;
  int count = 0;           // 0: until interrupted
  double timeout_s = 0.0;  // 0: wait forever
  bool json = false;       // one compact JSON object per line instead of indented JSON
};
// `cover echo`: prints samples of a catalogue topic as they arrive.
int echo(const dds::ParticipantOptions& options, const EchoRequest& request);

struct PubRequest {
  std::string topic;
  std::string json;
  double rate_hz = 0.0;  // 0: as fast as the single/first sample allows
  int count = 1;
  double wait_for_reader_s = 5.0;
};
// `cover pub`: publishes a JSON sample (missing fields zero, unknown fields an error), with
// ros2's stamping conventions: any field whose name ends with "stamp_ns" given as "now" is
// each sample's send time (host system clock, ns), "seq": "auto" counts up from 0 per
// sample ("auto:N": from N). Without them every sample is the same.
int publish(const dds::ParticipantOptions& options, const PubRequest& request);

// The `cover pub --help` footer: the stamping conventions, with an example.
const char* pub_help_footer();

}  // namespace cover::cli
