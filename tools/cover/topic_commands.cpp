#include "topic_commands.hpp"

#include <chrono>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <thread>
#include <vector>

#include "cover/clock/clock.hpp"
#include "cover/dds/json_codec.hpp"
#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace cover::cli {
namespace {

using namespace std::chrono_literals;

const dds::TopicInfo& lookup(const std::string& topic) {
  const dds::TopicInfo* info = dds::find_topic(topic);
  if (!info) {
    throw std::runtime_error("'" + topic + "' is not in the catalogue (see `cover topics`)");
  }
  return *info;
}

template <typename T>
int echo_typed(dds::Participant& participant, const EchoRequest& request) {
  auto reader =
      participant.make_reader(dds::catalogued_topic<T>(request.topic), [&request](const T& sample) {
        const auto json = dds::to_json(sample);
        std::cout << (request.json ? json.dump() : json.dump(2)) << std::endl;
      });
  const auto give_up = std::chrono::steady_clock::now() +
                       std::chrono::milliseconds(static_cast<long>(request.timeout_s * 1000));
  while (request.count <= 0 ||
         reader.received_count() < static_cast<std::uint64_t>(request.count)) {
    if (process::ShutdownSignal::requested()) return 130;
    if (request.timeout_s > 0 && std::chrono::steady_clock::now() >= give_up) {
      std::cerr << "cover echo: timeout after " << reader.received_count() << " samples\n";
      return 1;
    }
    reader.wait_for_sample(50ms, reader.received_count());
  }
  return 0;
}

// ros2's stamping conventions in a sample given as JSON, so that a person can stand in for
// an agent: a receiver that checks stamps (a flight-controller bridge) treats one sample
// repeated verbatim as stale. Any field whose name ends with "stamp_ns" given as "now"
// becomes each sample's send time (host system clock, ns since the epoch); "seq" given as
// "auto" counts up per sample from 0, "auto:N" from N.
class SampleStamper {
 public:
  explicit SampleStamper(nlohmann::json sample) : sample_(std::move(sample)) {
    find(sample_, nlohmann::json::json_pointer());
  }
  bool stamps() const { return !fields_.empty(); }
  // The next sample: every "now" field set to `now_ns`, every "auto" one to its count.
  const nlohmann::json& next(std::int64_t now_ns) {
    for (const Field& field : fields_) {
      sample_[field.where] = field.seq ? field.start + sent_ : now_ns;
    }
    ++sent_;
    return sample_;
  }

 private:
  struct Field {
    nlohmann::json::json_pointer where;
    bool seq = false;
    std::int64_t start = 0;  // seq: the first sample's
  };

  static bool ends_with(const std::string& text, const std::string& tail) {
    return text.size() >= tail.size() &&
           text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
  }

  void find(const nlohmann::json& node, const nlohmann::json::json_pointer& where) {
    if (node.is_array()) {
      for (std::size_t i = 0; i < node.size(); ++i) find(node[i], where / i);
      return;
    }
    if (!node.is_object()) return;
    for (const auto& [key, value] : node.items()) {
      if (!value.is_string()) {
        find(value, where / key);
      } else if (ends_with(key, "stamp_ns") && value == "now") {
        fields_.push_back({where / key, false, 0});
      } else if (key == "seq" && value.get<std::string>().rfind("auto", 0) == 0) {
        fields_.push_back({where / key, true, seq_start(value.get<std::string>())});
      }
    }
  }

  // "auto" -> 0, "auto:N" -> N.
  static std::int64_t seq_start(const std::string& text) {
    if (text == "auto") return 0;
    const std::string digits = text.size() > 5 && text[4] == ':' ? text.substr(5) : "";
    if (digits.empty() || digits.size() > 10 ||
        digits.find_first_not_of("0123456789") != std::string::npos) {
      throw std::runtime_error("seq: '" + text + "' (expected \"auto\" or \"auto:N\")");
    }
    return std::stoll(digits);
  }

  nlohmann::json sample_;
  std::vector<Field> fields_;
  std::int64_t sent_ = 0;
};

template <typename T>
int publish_typed(dds::Participant& participant, const PubRequest& request,
                  const nlohmann::json& parsed, SampleStamper stamper) {
  // Checked before anything is sent (a bad field is an error, not a first sample); stamped
  // again right before each write, after the wait for a subscriber.
  T sample = dds::from_json<T>(stamper.stamps() ? SampleStamper(parsed).next(0) : parsed);
  const auto topic = dds::catalogued_topic<T>(request.topic);
  auto writer = participant.make_writer(topic);
  const auto wait = std::chrono::milliseconds(static_cast<long>(request.wait_for_reader_s * 1000));
  if (!writer.wait_for_readers(1, wait)) {
    std::cerr << "cover pub: no subscriber on " << request.topic << " yet; publishing anyway\n";
  }
  const auto period = request.rate_hz > 0
                          ? std::chrono::nanoseconds(static_cast<long>(1e9 / request.rate_hz))
                          : std::chrono::nanoseconds(0);
  auto next = std::chrono::steady_clock::now();
  for (int i = 0; i < request.count && !process::ShutdownSignal::requested(); ++i) {
    if (stamper.stamps()) sample = dds::from_json<T>(stamper.next(clock::system_ns()));
    if (!writer.write(sample)) {
      std::cerr << "cover pub: write failed\n";
      return 1;
    }
    next += period;
    std::this_thread::sleep_until(next);
  }
  // Reliable topics: make sure the subscribers have the samples before the writer goes.
  if (topic.qos().reliability == dds::Reliability::Reliable) writer.wait_for_acknowledgments(2s);
  return 0;
}

// "cover::idl::UgvImu" -> "UgvImu", as docs/topics.md writes types.
std::string short_type_name(const std::string& type_name) {
  return type_name.substr(type_name.rfind(':') + 1);
}

void print_markdown(const std::vector<dds::TopicInfo>& catalog) {
  std::cout << "| topic | type | rate | QoS profile | publisher -> subscribers |\n"
            << "| --- | --- | --- | --- | --- |\n";
  for (const auto& entry : catalog) {
    std::cout << "| `" << entry.pattern << "` | `" << short_type_name(entry.type_name) << "` | "
              << entry.rate << " | " << entry.qos_profile << " | " << entry.flow << " |\n";
  }
}

void print_json_lines(const std::vector<dds::TopicInfo>& catalog) {
  for (const auto& entry : catalog) {
    std::cout << nlohmann::json{{"topic", entry.pattern},
                                {"type", entry.type_name},
                                {"qos", entry.qos_profile},
                                {"rate", entry.rate},
                                {"publisher_subscribers", entry.flow},
                                {"description", entry.description}}
                     .dump()
              << "\n";
  }
}

void print_table(const std::vector<dds::TopicInfo>& catalog) {
  for (const auto& entry : catalog) {
    std::cout << std::left << std::setw(26) << entry.pattern << std::setw(21)
              << short_type_name(entry.type_name) << std::setw(9) << entry.qos_profile
              << std::setw(11) << entry.rate << entry.flow << "\n"
              << std::setw(26) << "" << entry.description << "\n";
  }
}

}  // namespace

int list_topics(TopicsFormat format) {
  const auto& catalog = dds::topic_catalog();
  switch (format) {
    case TopicsFormat::Table:
      print_table(catalog);
      break;
    case TopicsFormat::Json:
      print_json_lines(catalog);
      break;
    case TopicsFormat::Markdown:
      print_markdown(catalog);
      break;
  }
  return 0;
}

int echo(const dds::ParticipantOptions& options, const EchoRequest& request) {
  const auto& info = lookup(request.topic);
  dds::Participant participant(options);
  int rc = 0;
  msg::with_type(info.type_name, [&](auto tag) {
    rc = echo_typed<typename decltype(tag)::type>(participant, request);
  });
  return rc;
}

const char* pub_help_footer() {
  return R"(Stamping (ros2's conventions), so that a person can stand in for an agent:
  "stamp_ns": "now"   any field whose name ends with stamp_ns: the send time of each
                      sample (host system clock, ns since the epoch)
  "seq": "auto"       counts up per sample from 0 ("auto:N": from N)
Without them every sample is the same, which a receiver that checks stamps (a
flight-controller bridge) treats as stale. Example, 100 Hz for 5 s:
  cover pub cover/uav/0/cmd '{"uav_id": 0, "stamp_ns": "now", "seq": "auto",
    "thrust_m_s2": 9.81, "armed": true}' --rate 100 --count 500
Exit: 0 published, 1 a write failed, 2 a bad topic, JSON or field.)";
}

int publish(const dds::ParticipantOptions& options, const PubRequest& request) {
  const auto& info = lookup(request.topic);
  nlohmann::json parsed;
  try {
    parsed = nlohmann::json::parse(request.json);
  } catch (const nlohmann::json::exception& e) {  // a syntax error, or a number beyond double
    throw std::runtime_error(std::string("invalid JSON: ") + e.what());
  }
  SampleStamper stamper(parsed);  // a bad "seq" is an error before DDS starts
  dds::Participant participant(options);
  int rc = 0;
  msg::with_type(info.type_name, [&](auto tag) {
    rc = publish_typed<typename decltype(tag)::type>(participant, request, parsed, stamper);
  });
  return rc;
}

}  // namespace cover::cli
