#include "dds_ping_pong.hpp"

#include <pthread.h>
#include <sched.h>

#include <chrono>
#include <condition_variable>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "bench_cli.hpp"
#include "cover/process/child_process.hpp"
#include "cover/process/shutdown_signal.hpp"

namespace cover::bench {

namespace {

using msg::RelativeState;
using namespace std::chrono_literals;

dds::Topic<RelativeState> bench_topic(const std::string& name, const dds::QosProfile& qos) {
  return dds::Topic<RelativeState>::uncatalogued(name, qos);
}

// Receives pongs and lets the pinger wait for a given sequence number.
class PongWaiter {
 public:
  void on_pong(const RelativeState& pong) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      last_seq_ = pong.stamp_ns;
    }
    arrived_.notify_all();
  }
  bool wait_for(std::int64_t seq, std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return arrived_.wait_for(lock, timeout, [&] { return last_seq_ == seq; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::int64_t last_seq_ = -1;
};

// The calling thread at a SCHED_FIFO priority while it lives (threads it starts meanwhile
// inherit it), then back to its policy before.
class ScopedRealtime {
 public:
  explicit ScopedRealtime(int priority) {
    if (priority <= 0) return;
    pthread_getschedparam(pthread_self(), &old_policy_, &old_param_);
    sched_param param{};
    param.sched_priority = priority;
    if (pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0) priority_ = priority;
  }
  ~ScopedRealtime() {
    if (priority_ > 0) pthread_setschedparam(pthread_self(), old_policy_, &old_param_);
  }
  ScopedRealtime(const ScopedRealtime&) = delete;
  ScopedRealtime& operator=(const ScopedRealtime&) = delete;
  int priority() const { return priority_; }

 private:
  int priority_ = 0;
  int old_policy_ = SCHED_OTHER;
  sched_param old_param_{};
};

process::SpawnOptions pong_spawn_options(const PingPongOptions& options) {
  process::SpawnOptions spawn;
  spawn.capture_stdout = true;
  spawn.realtime_priority = options.pong_realtime_priority;
  spawn.cpu_affinity = options.pong_cpu_affinity;
  return spawn;
}

dds::QosProfile named(dds::QosProfile qos) {
  if (qos.name.empty()) return reliable_bench_qos();
  return qos;
}

}  // namespace

dds::QosProfile reliable_bench_qos() {
  return {"bench", dds::Reliability::Reliable, dds::Durability::Volatile, 1, 0.0};
}

struct PingPong::Impl {
  explicit Impl(const PingPongOptions& options)
      : pong_process({"/proc/self/exe", "dds-pong", "--dds", dds::vendor_name(options.pong_vendor),
                      "--domain", std::to_string(options.domain_id), "--prefix", options.prefix,
                      "--ping-qos", named(options.ping_qos).name, "--pong-qos",
                      named(options.pong_qos).name},
                     pong_spawn_options(options)),
        ping_scheduling(options.ping_realtime_priority),
        pong_priority(options.pong_realtime_priority) {
    const auto ready = pong_process.read_line(20s);
    if (!ready || *ready != "ready") throw std::runtime_error("the pong process did not start");
    dds::ParticipantOptions participant_options;
    participant_options.vendor = options.ping_vendor;
    participant_options.domain_id = options.domain_id;
    participant_options.participant_name = "cover-bench-ping";
    participant = std::make_unique<dds::Participant>(participant_options);
    pong_reader.emplace(
        participant->make_reader(bench_topic(options.prefix + "/pong", named(options.pong_qos)),
                                 [this](const RelativeState& s) { waiter.on_pong(s); }));
    ping_writer.emplace(
        participant->make_writer(bench_topic(options.prefix + "/ping", named(options.ping_qos))));
    if (!ping_writer->wait_for_readers(1, 20s) || !pong_reader->wait_for_writers(1, 20s)) {
      throw std::runtime_error("ping and pong never matched");
    }
  }

  process::ChildProcess pong_process;
  ScopedRealtime ping_scheduling;  // before the participant: its threads inherit it
  int pong_priority = 0;
  std::unique_ptr<dds::Participant> participant;
  PongWaiter waiter;
  std::optional<dds::Reader<RelativeState>> pong_reader;
  std::optional<dds::Writer<RelativeState>> ping_writer;
  std::int64_t seq = 0;
};

PingPong::PingPong(const PingPongOptions& options) : impl_(std::make_unique<Impl>(options)) {}

int PingPong::ping_realtime_priority() const {
  return impl_->ping_scheduling.priority();
}

std::vector<int> PingPong::pong_cpus() const {
  return impl_->pong_process.cpus();
}

int PingPong::pong_realtime_priority() const {
  return impl_->pong_process.realtime() ? impl_->pong_priority : 0;
}

PingPong::~PingPong() {
  impl_->pong_process.terminate();
}

RoundTrips PingPong::run(int count, double rate_hz) {
  RoundTrips result;
  result.round_trip_us.reserve(static_cast<std::size_t>(count));
  RelativeState sample;
  sample.position_m = {1.0, 2.0, 3.0};
  sample.attitude = {1.0, 0.0, 0.0, 0.0};
  sample.valid = true;
  const auto period = rate_hz > 0 ? std::chrono::nanoseconds(static_cast<long>(1e9 / rate_hz))
                                  : std::chrono::nanoseconds(0);
  auto next = std::chrono::steady_clock::now();
  for (int i = 0; i < count; ++i) {
    if (rate_hz > 0) {
      next += period;
      std::this_thread::sleep_until(next);
    }
    sample.stamp_ns = ++impl_->seq;
    const auto start = std::chrono::steady_clock::now();
    if (!impl_->ping_writer->write(sample)) continue;
    ++result.sent;
    if (!impl_->waiter.wait_for(impl_->seq, 1000ms)) continue;  // counted as lost
    const auto round_trip = std::chrono::steady_clock::now() - start;
    ++result.received;
    result.round_trip_us.push_back(std::chrono::duration<double, std::micro>(round_trip).count());
  }
  return result;
}

namespace {

// The pong's two hops by the name PingPong passes: a catalogue profile or "bench".
dds::QosProfile profile_named(const std::string& name) {
  return name == reliable_bench_qos().name ? reliable_bench_qos() : dds::qos_profile(name);
}

}  // namespace

int run_pong(const std::vector<std::string>& args) {
  process::ShutdownSignal::install();
  CLI::App app{"cover-bench dds-pong: echo peer of `cover-bench dds` and `e2e` (internal)"};
  std::string vendor = "fastdds", prefix, ping_qos = "bench", pong_qos = "bench";
  int domain_id = 0;
  app.add_option("--dds", vendor);
  app.add_option("--domain", domain_id);
  app.add_option("--prefix", prefix)->required();
  app.add_option("--ping-qos", ping_qos, "sensor | command | bench");
  app.add_option("--pong-qos", pong_qos, "sensor | command | bench");
  if (int rc = parse_args(app, args); rc >= 0) return rc;
  dds::ParticipantOptions options;
  options.vendor = dds::parse_vendor(vendor);
  options.domain_id = domain_id;
  options.participant_name = "cover-bench-pong";
  dds::Participant participant(options);
  auto pong = participant.make_writer(bench_topic(prefix + "/pong", profile_named(pong_qos)));
  auto ping = participant.make_reader(bench_topic(prefix + "/ping", profile_named(ping_qos)),
                                      [&pong](const RelativeState& sample) { pong.write(sample); });
  std::cout << "ready" << std::endl;
  while (!process::ShutdownSignal::wait_for(1000ms)) {
  }
  return 0;
}

}  // namespace cover::bench
