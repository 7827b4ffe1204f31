#pragma once

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cover/dds/domain_claim.hpp"
#include "cover/process/child_process.hpp"
#include "cover/shm/segment_name.hpp"
#include "cover/shm/seqlock_reader.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/wait_until.hpp"
#include "cover/vocabulary/world_segment.hpp"
#include "process_support.hpp"

namespace cover::test {

// The simulator and both UGV agents on a DDS domain held for the object's life, the
// simulator's world open as ground truth: what the integration tests start before their
// UAV agents. The simulator is on Fast DDS, the agents on Cyclone DDS; each process logs
// to <run id>_<name>.log in the test's scratch folder.
class SimSystem {
 public:
  // `tag` starts the run id, `<tag>_<pid>_<domain>`; `sim_args` follow cover-sim's --clock
  // and --run-id (the scenario, --standing, faults to inject). Returns once the world is
  // there (at most `world_timeout`, else throws).
  SimSystem(int domain, const std::string& tag, const std::vector<std::string>& sim_args,
            const std::string& clock = "realtime",
            std::chrono::milliseconds world_timeout = std::chrono::seconds(20))
      : claim_(claim_domain(domain)),
        domain_(domain),
        run_id_(tag + "_" + std::to_string(getpid()) + "_" + std::to_string(domain)) {
    std::vector<std::string> argv{bin("cover-sim"), "--clock", clock, "--run-id", run_id_};
    argv.insert(argv.end(), sim_args.begin(), sim_args.end());
    sim_ = spawn(argv, "sim", "fastdds");
    for (int k = 0; k < 2; ++k) {
      ugvs_.push_back(
          spawn({bin("cover-ugv-agent"), "--id", std::to_string(k), "--run-id", run_id_},
                "ugv" + std::to_string(k)));
    }
    world_.emplace(shm::SeqlockReader<sim::SharedWorld>::open(
        shm::segment_name(domain, run_id_), sim::kWorldSegmentLayoutVersion, world_timeout));
  }

  // A process of this system, on this domain, logging to <run id>_<name>.log.
  std::unique_ptr<process::ChildProcess> spawn(const std::vector<std::string>& argv,
                                               const std::string& name,
                                               const std::string& vendor = "cyclone") const {
    return std::make_unique<process::ChildProcess>(argv, quiet(vendor, domain_, log_name(name)));
  }
  std::string log_name(const std::string& name) const { return run_id_ + "_" + name + ".log"; }
  std::string log_path(const std::string& name) const { return scratch_path(log_name(name)); }

  // Reads the world every 2 ms until `condition` holds or `timeout` (scaled) passes.
  bool wait_for_world(const std::function<bool(const sim::SharedWorld&)>& condition,
                      std::chrono::milliseconds timeout) {
    auto copy = std::make_unique<sim::SharedWorld>();
    return wait_until([&] { return world_->read(*copy) && condition(*copy); }, timeout,
                      std::chrono::milliseconds(2));
  }
  // One consistent copy of the world: a read that a write overlapped (the world is ~190 KiB,
  // written at 200 Hz by a simulator that may be preempted mid-write) is tried again.
  bool read_world(sim::SharedWorld& out,
                  std::chrono::milliseconds timeout = std::chrono::seconds(5)) {
    return wait_until([&] { return world_->read(out); }, timeout, std::chrono::milliseconds(1));
  }
  shm::SeqlockReader<sim::SharedWorld>& world() { return *world_; }
  // Lets go of the world before the simulator is killed or stopped.
  void close_world() { world_.reset(); }
  std::string segment_path() const {
    return shm::segment_path(shm::segment_name(domain_, run_id_));
  }

  // The UGV agents (last first), then the simulator: SIGINT, SIGKILL after `timeout`.
  void stop(std::chrono::milliseconds timeout) {
    close_world();
    for (auto it = ugvs_.rbegin(); it != ugvs_.rend(); ++it) (*it)->terminate(timeout, SIGINT);
    sim_->terminate(timeout, SIGINT);
  }

  int domain() const { return domain_; }
  const std::string& run_id() const { return run_id_; }
  process::ChildProcess& sim() { return *sim_; }
  process::ChildProcess& ugv(int k) { return *ugvs_.at(k); }
  std::vector<std::unique_ptr<process::ChildProcess>>& ugvs() { return ugvs_; }

 private:
  dds::DomainClaim claim_;  // first: held until every child has stopped
  int domain_;
  std::string run_id_;
  std::unique_ptr<process::ChildProcess> sim_;
  std::vector<std::unique_ptr<process::ChildProcess>> ugvs_;
  std::optional<shm::SeqlockReader<sim::SharedWorld>> world_;
};

}  // namespace cover::test
