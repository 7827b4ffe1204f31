// Echo peer for the cross-vendor round-trip tests: for every catalogue type T it reads
// `<prefix>/<T>/in` and writes each sample back on `<prefix>/<T>/out`. Prints "ready"
// once every reader and writer exists; exits on SIGTERM.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace {

struct Args {
  cover::dds::ParticipantOptions options;
  std::string prefix;
};

Args parse(int argc, char** argv) {
  Args args;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--dds") args.options.vendor = cover::dds::parse_vendor(value);
    if (key == "--domain") args.options.domain_id = std::stoi(value);
    if (key == "--prefix") args.prefix = value;
  }
  return args;
}

// Keeps one writer and one reader per type alive.
struct Echo {
  virtual ~Echo() = default;
};

template <typename T>
struct TypedEcho : Echo {
  TypedEcho(cover::dds::Participant& participant, const std::string& prefix) {
    const std::string base = prefix + "/" + short_name();
    using Topic = cover::dds::Topic<T>;
    writer = participant.make_writer(Topic::uncatalogued(base + "/out", cover::dds::state_qos()));
    reader = participant.make_reader(Topic::uncatalogued(base + "/in", cover::dds::state_qos()),
                                     [this](const T& sample) { writer.write(sample); });
  }
  static std::string short_name() {
    const std::string full = T::kTypeName;
    return full.substr(full.rfind(':') + 1);
  }
  cover::dds::Writer<T> writer;
  cover::dds::Reader<T> reader;
};

}  // namespace

int main(int argc, char** argv) {
  cover::process::ShutdownSignal::install();
  try {
    const Args args = parse(argc, argv);
    cover::dds::Participant participant(args.options);
    std::vector<std::unique_ptr<Echo>> echoes;
    cover::msg::for_each_type([&](auto tag) {
      using T = typename decltype(tag)::type;
      echoes.push_back(std::make_unique<TypedEcho<T>>(participant, args.prefix));
    });
    std::cout << "ready" << std::endl;
    while (!cover::process::ShutdownSignal::wait_for(std::chrono::milliseconds(1000))) {
    }
    echoes.clear();
  } catch (const std::exception& e) {
    std::cerr << "dds_peer: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
