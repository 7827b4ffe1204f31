// DDS-Security with real processes: a participant without an identity, an identity
// without the permission, another CA and forged permissions are all refused, counted on
// the receiving side (a secure `cover echo`, whose printed samples are the count); a secure
// Scenario 2 flies on each vendor; a mixed-vendor secure fleet is refused at start-up.
// Domains 120..129 (apart from every other test: tests run in parallel).
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cover/process/child_process.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/time_scale.hpp"
#include "process_support.hpp"

namespace {

namespace fs = std::filesystem;
using cover::process::ChildProcess;
using cover::process::SpawnOptions;

// The running test's folder for fleet directories (private keys) and logs: removed when
// the test passes.
const fs::path& scratch() {
  return cover::test::scratch_dir();
}

std::string log_path(const std::string& name) {
  return (scratch() / name).string();
}

struct Outcome {
  int exit_code = -1;
  std::string out;  // stdout
  std::string log;  // stderr
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// Runs `cover ARGS` to its end; stdout captured, stderr in a log file.
Outcome cover_cli(const std::vector<std::string>& args, const std::string& log_name,
                  std::chrono::seconds timeout = std::chrono::seconds(60)) {
  std::vector<std::string> argv{COVER_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = log_path(log_name);
  ChildProcess child(argv, options);
  Outcome outcome;
  while (const auto line = child.read_line(timeout)) outcome.out += *line + "\n";
  outcome.exit_code = child.wait(timeout).value_or(-1);
  outcome.log = read_text(options.log_file);
  return outcome;
}

// A fleet directory made by `cover security init` in the test's temp folder.
fs::path make_fleet(const std::string& name, const std::vector<std::string>& flags = {}) {
  const fs::path dir = scratch() / ("fleet_" + name);
  fs::remove_all(dir);
  std::vector<std::string> args{"security", "init", dir.string()};
  args.insert(args.end(), flags.begin(), flags.end());
  const Outcome init = cover_cli(args, "init_" + name + ".log");
  EXPECT_EQ(init.exit_code, 0) << init.log;
  return dir;
}

std::vector<std::string> secure(const fs::path& fleet, const std::string& identity) {
  return {"--security", fleet.string(), "--identity", identity};
}

std::vector<std::string> on(const std::string& vendor, int domain, std::vector<std::string> args) {
  args.insert(args.end(), {"--dds", vendor, "--domain", std::to_string(domain)});
  return args;
}

std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// One sample of each kind an attacker would want to inject.
struct Injection {
  std::string topic;
  std::string json;
  std::string allowed_identity;  // who may publish it (the positive control)
};
const std::vector<Injection> kInjections{
    {"cover/task/request", R"({"task_id": "evil", "uav_id": 0})", "task-manager"},
    {"cover/uav/0/cmd", R"({"uav_id": 0, "thrust_m_s2": 30.0, "armed": true})", "uav-agent-0"},
    {"cover/ugv/0/imu", R"({"ugv_id": 0, "specific_force_m_s2": {"x": 50.0}})", "ugv-agent-0"},
};

// A secure `cover echo` (ground-station-0 of `fleet`) on `topic`, started before the
// publisher and stopped by its timeout: its printed lines are the samples it took.
// Echoes `topic` as the ground station until `count` samples or `timeout_s` seconds.
std::unique_ptr<ChildProcess> start_echo(const fs::path& fleet, const std::string& vendor,
                                         int domain, const std::string& topic,
                                         const std::string& log, int count = 1000,
                                         int timeout_s = 7) {
  std::vector<std::string> argv{COVER_CLI};
  argv =
      argv + on(vendor, domain,
                std::vector<std::string>{"echo", topic, "--json", "--count", std::to_string(count),
                                         "--timeout", std::to_string(timeout_s)} +
                    secure(fleet, "ground-station-0"));
  SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = log_path(log);
  return std::make_unique<ChildProcess>(argv, options);
}

int samples_taken(ChildProcess& echo) {
  int samples = 0;
  // Only JSON objects are samples: a vendor's log lines may share stdout.
  while (const auto line = echo.read_line(std::chrono::seconds(20))) {
    const auto sample = nlohmann::json::parse(*line, nullptr, false);
    if (sample.is_object()) ++samples;
  }
  echo.wait(std::chrono::seconds(20));
  return samples;
}

// `cover ARGS` started in the background, its output in a log file.
std::unique_ptr<ChildProcess> start_cover(const std::vector<std::string>& args,
                                          const std::string& log) {
  std::vector<std::string> argv{COVER_CLI};
  SpawnOptions options;
  options.log_file = log_path(log);
  return std::make_unique<ChildProcess>(argv + args, options);
}

class Security : public ::testing::TestWithParam<std::string> {};

// What one round of publishers and secure echoes saw, per injection.
struct RoundResult {
  std::vector<int> taken;     // samples each secure echo printed
  std::vector<bool> matched;  // whether each publisher saw a subscriber before sending
  std::vector<std::string> pub_logs;
};

// Secure echoes (ground-station-0) on every injection's topic, then a publisher on each:
// plain ones, or the identities permitted to write there.
RoundResult run_injection_round(const fs::path& fleet, const std::string& vendor, int domain,
                                bool authenticated, int samples, int taken_enough, int handshake_s,
                                int attempt) {
  const int echo_timeout_s = handshake_s + 15;
  const std::string tag = (authenticated ? "_secure" : "_plain") + std::to_string(attempt);
  std::vector<std::unique_ptr<ChildProcess>> echoes;
  for (const auto& injection : kInjections) {
    const std::string log = "echo_" + injection.topic.substr(6, 3) + tag + ".log";
    echoes.push_back(authenticated ? start_echo(fleet, vendor, domain, injection.topic, log,
                                                taken_enough, echo_timeout_s)
                                   : start_echo(fleet, vendor, domain, injection.topic, log));
  }
  std::vector<std::unique_ptr<ChildProcess>>
      publishers;  // at once, so all fit in the readers' time
  std::vector<std::string> pub_log_names;
  for (const auto& injection : kInjections) {
    const auto flags =
        authenticated ? secure(fleet, injection.allowed_identity) : std::vector<std::string>{};
    pub_log_names.push_back("pub_" + injection.topic.substr(6, 3) + tag + ".log");
    publishers.push_back(
        start_cover(on(vendor, domain,
                       std::vector<std::string>{"pub", injection.topic, injection.json, "--rate",
                                                "50", "--count", std::to_string(samples), "--wait",
                                                authenticated ? std::to_string(handshake_s) : "2"} +
                           flags),
                    pub_log_names.back()));
  }
  RoundResult result;
  for (std::size_t i = 0; i < publishers.size(); ++i) {
    EXPECT_EQ(publishers[i]->wait(std::chrono::seconds(echo_timeout_s)), 0);
    result.pub_logs.push_back(read_text(log_path(pub_log_names[i])));
    result.matched.push_back(result.pub_logs.back().find("no subscriber") == std::string::npos);
  }
  for (auto& echo : echoes) result.taken.push_back(samples_taken(*echo));
  return result;
}

// Plain participants publish a task, a command and an IMU sample: the secure readers
// take none. Then the permitted identities publish the same: the readers take them,
// which shows the readers would have counted the plain samples had they arrived.
TEST_P(Security, UnauthenticatedParticipantIsIgnored) {
  const std::string vendor = GetParam();
  const int domain = vendor == "fastdds" ? 120 : 121;
  const auto claim = cover::test::claim_domain(domain);
  const fs::path fleet = make_fleet(vendor, {"--vendor", vendor});
  // Plain publishers never match a secure reader, so they wait out a short --wait and
  // publish into nothing. Permitted ones wait (up to 40 s) for the secure handshake, which
  // took over 2 s on a loaded machine: samples published before it are lost, not refused.
  constexpr int kSamples = 80;
  constexpr int kTaken = 11;  // what shows the secure reader takes a permitted writer's samples
  // Six secure participants handshake pairwise at once: on a loaded 2-core CI machine one
  // pair took longer than 15 s (the permitted echo then timed out with 0 samples).
  const int handshake_s = 40 * cover::test::whole_time_scale();

  const RoundResult plain =
      run_injection_round(fleet, vendor, domain, false, kSamples, kTaken, handshake_s, 1);
  for (std::size_t i = 0; i < kInjections.size(); ++i) {
    EXPECT_EQ(plain.taken[i], 0) << kInjections[i].topic << " (plain)";
  }

  // A permitted writer that never matched published into nothing: the handshake, not the
  // permission, would be what the count measures. Cyclone DDS 0.10 can give up a pair's
  // handshake for good on a loaded machine (eclipse-cyclonedds/cyclonedds#1895; seen once
  // in CI: no match in 40 s, the other pairs fine), so such a round is run once more with
  // new participants, which handshake afresh; the second round must be complete.
  RoundResult permitted =
      run_injection_round(fleet, vendor, domain, true, kSamples, kTaken, handshake_s, 1);
  const bool all_matched = std::all_of(permitted.matched.begin(), permitted.matched.end(),
                                       [](bool matched) { return matched; });
  if (!all_matched) {
    for (std::size_t i = 0; i < kInjections.size(); ++i) {
      if (!permitted.matched[i]) {
        std::cerr << "[ NOTE     ] " << kInjections[i].topic << ": no secure match in "
                  << handshake_s << " s (" << vendor << "); the round runs again\n";
      }
    }
    permitted = run_injection_round(fleet, vendor, domain, true, kSamples, kTaken, handshake_s, 2);
  }
  for (std::size_t i = 0; i < kInjections.size(); ++i) {
    SCOPED_TRACE(kInjections[i].topic + " (permitted identity)");
    EXPECT_TRUE(permitted.matched[i]) << permitted.pub_logs[i];
    EXPECT_GE(permitted.taken[i], kTaken);
  }
}

// A ground station may not command a UAV: its writer is refused locally, with a message.
TEST_P(Security, IdentityWithoutPermissionCannotWrite) {
  const std::string vendor = GetParam();
  const int domain = vendor == "fastdds" ? 122 : 123;
  const auto claim = cover::test::claim_domain(domain);
  const fs::path fleet = make_fleet(vendor, {"--vendor", vendor});
  for (const std::string topic : {"cover/uav/0/cmd", "cover/task/request", "cover/ugv/0/imu"}) {
    const Outcome pub = cover_cli(on(vendor, domain,
                                     std::vector<std::string>{"pub", topic, "{}", "--wait", "0"} +
                                         secure(fleet, "ground-station-0")),
                                  "gs_pub.log");
    EXPECT_EQ(pub.exit_code, 2) << topic;
    EXPECT_NE(pub.log.find("cannot create a writer on '" + topic + "'"), std::string::npos)
        << pub.log;
  }
  // UAV agent 0 may not command UAV 1.
  const fs::path two = make_fleet(vendor + "_two", {"--vendor", vendor, "--uavs", "2"});
  const Outcome other =
      cover_cli(on(vendor, domain,
                   std::vector<std::string>{"pub", "cover/uav/1/cmd", "{}", "--wait", "0"} +
                       secure(two, "uav-agent-0")),
                "uav0_pub.log");
  EXPECT_EQ(other.exit_code, 2) << other.log;
}

// Replaces the first `from` in `path` by `to`.
void edit(const fs::path& path, const std::string& from, const std::string& to) {
  std::string text = read_text(path);
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from << " not in " << path;
  text.replace(at, from.size(), to);
  write_text(path, text);
}

void sign(const fs::path& document, const fs::path& signed_document, const fs::path& ca_dir) {
  const std::string command = "openssl smime -sign -in '" + document.string() + "' -text -out '" +
                              signed_document.string() + "' -signer '" +
                              (ca_dir / "permissions_ca.pem").string() + "' -inkey '" +
                              (ca_dir / "ca.key").string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

// A participant of another fleet (its own CA), with the permission there, and a ground
// station whose permissions were widened and re-signed by another CA: the fleet's
// readers take nothing from either.
TEST_P(Security, ForeignCaAndForgedPermissionsAreIgnored) {
  const std::string vendor = GetParam();
  const int domain = vendor == "fastdds" ? 124 : 125;
  const auto claim = cover::test::claim_domain(domain);
  const fs::path fleet = make_fleet(vendor, {"--vendor", vendor});
  const fs::path foreign = make_fleet(vendor + "_foreign", {"--vendor", vendor});
  // Forged: the fleet's own ground-station-0 certificate and key, permissions that allow
  // it to command UAV 0, signed by the foreign CA, which the forger trusts locally.
  const fs::path forged = scratch() / ("forged_" + vendor);
  fs::remove_all(forged);
  fs::copy(fleet, forged, fs::copy_options::recursive);
  fs::copy_file(foreign / "permissions_ca.pem", forged / "permissions_ca.pem",
                fs::copy_options::overwrite_existing);
  fs::copy_file(foreign / "governance.p7s", forged / "governance.p7s",
                fs::copy_options::overwrite_existing);
  const fs::path station = forged / "identities" / "ground-station-0";
  edit(station / "permissions.xml", "<publish>\n          <topics>\n",
       "<publish>\n          <topics>\n            <topic>cover/uav/0/cmd</topic>\n");
  sign(station / "permissions.xml", station / "permissions.p7s", foreign);
  // The forger's own check passes for the forged identity: the refusal below is the
  // receivers'.
  const Outcome forged_check = cover_cli({"security", "check", forged.string()}, "forged.log");
  EXPECT_NE(forged_check.out.find("ground-station-0: valid"), std::string::npos)
      << forged_check.out;

  const auto echo = start_echo(fleet, vendor, domain, "cover/uav/0/cmd", "echo_cmd.log");
  std::vector<std::unique_ptr<ChildProcess>> publishers;
  for (const auto& flags : {secure(foreign, "uav-agent-0"), secure(forged, "ground-station-0")}) {
    publishers.push_back(start_cover(
        on(vendor, domain,
           std::vector<std::string>{"pub", "cover/uav/0/cmd", R"({"thrust_m_s2": 30.0})", "--rate",
                                    "50", "--count", "80", "--wait", "2"} +
               flags),
        "forged_pub_" + std::to_string(publishers.size()) + ".log"));
  }
  // Both start: they are permitted by what they trust locally; the receivers refuse them.
  for (auto& publisher : publishers) EXPECT_EQ(publisher->wait(std::chrono::seconds(30)), 0);
  EXPECT_EQ(samples_taken(*echo), 0);
}

INSTANTIATE_TEST_SUITE_P(Vendors, Security, ::testing::Values("fastdds", "cyclone"),
                         [](const auto& info) { return info.param; });

// `cover security check`: least privilege from the catalogue, expiry, private key modes.
TEST(SecurityFleet, CheckReportsLeastPrivilegeAndExpiry) {
  const fs::path fleet = make_fleet("check", {"--uavs", "2", "--days", "30"});
  const Outcome check = cover_cli({"security", "check", fleet.string(), "--json"}, "check.log");
  ASSERT_EQ(check.exit_code, 0) << check.out << check.log;
  const auto report = nlohmann::json::parse(check.out);
  // sim, task-manager, mocap-relay, 2 UGVs, 2 UAVs, their 2 bridges, 1 station
  ASSERT_EQ(report["identities"].size(), 10u);
  const auto publishes = [&](const std::string& topic) {
    std::vector<std::string> who;
    for (const auto& identity : report["identities"]) {
      for (const auto& t : identity["publish"]) {
        if (t == topic) who.push_back(identity["identity"]);
      }
    }
    return who;
  };
  using Names = std::vector<std::string>;
  EXPECT_EQ(publishes("cover/uav/0/cmd"), Names{"uav-agent-0"});
  EXPECT_EQ(publishes("cover/uav/1/cmd"), Names{"uav-agent-1"});
  EXPECT_EQ(publishes("cover/task/request"), Names{"task-manager"});
  EXPECT_EQ(publishes("cover/manager/request"), Names{"ground-station-0"});
  EXPECT_EQ(publishes("cover/uav/1/rel/0"), (Names{"sim", "mocap-relay"}));
  EXPECT_EQ(publishes("cover/ugv/1/imu"), Names{"ugv-agent-1"});
  for (const auto& identity : report["identities"]) {
    EXPECT_TRUE(identity["valid"].get<bool>());
    const auto left = identity["seconds_to_expiry"].get<long>();
    EXPECT_GT(left, 29 * 86400);
    EXPECT_LE(left, 30 * 86400);
    const fs::path key = fleet / "identities" / identity["identity"].get<std::string>() / "key.pem";
    struct stat info {};
    ASSERT_EQ(stat(key.c_str(), &info), 0);
    EXPECT_EQ(info.st_mode & 0777, 0600u) << key;
  }
  // No key material in what init and check print.
  EXPECT_EQ(check.out.find("PRIVATE KEY"), std::string::npos);
  // A fleet directory is never overwritten.
  const Outcome again = cover_cli({"security", "init", fleet.string()}, "again.log");
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.log.find("not empty"), std::string::npos) << again.log;
}

// Broken files: check names each, and a process refuses to start (exit 2) instead of
// running as a plain participant.
TEST(SecurityFleet, BrokenExpiredOrExposedFilesStopAProcess) {
  const fs::path fleet = make_fleet("broken");
  const auto pub_as = [&](const std::string& identity, const std::string& tag) {
    return cover_cli(on("fastdds", 126,
                        std::vector<std::string>{"pub", "cover/task/abort", "{}", "--wait", "0"} +
                            secure(fleet, identity)),
                     "broken_" + tag + ".log");
  };
  const auto expect_refused = [&](const std::string& identity, const std::string& why) {
    const Outcome pub = pub_as(identity, identity);
    EXPECT_EQ(pub.exit_code, 2) << pub.log;
    EXPECT_NE(pub.log.find(why), std::string::npos) << pub.log;
    const Outcome check = cover_cli({"security", "check", fleet.string()}, "check.log");
    EXPECT_EQ(check.exit_code, 1);
    EXPECT_NE(check.out.find(identity + ": INVALID"), std::string::npos) << check.out;
  };
  ASSERT_EQ(pub_as("ground-station-0", "ok").exit_code, 0);

  // Tampered permissions (a topic added after signing).
  const fs::path tm = fleet / "identities" / "task-manager" / "permissions.p7s";
  edit(tm, "<topic>cover/task/request</topic>", "<topic>cover/uav/0/cmd</topic>");
  expect_refused("task-manager", "signature not accepted");
  // Expired permissions, properly signed.
  const fs::path gs = fleet / "identities" / "ground-station-0";
  std::string xml = read_text(gs / "permissions.xml");
  xml = std::regex_replace(xml, std::regex("<not_after>[^<]*</not_after>"),
                           "<not_after>2020-01-01T00:00:00</not_after>");
  write_text(gs / "permissions.xml", xml);
  sign(gs / "permissions.xml", gs / "permissions.p7s", fleet);
  expect_refused("ground-station-0", "permissions expired on 2020-01-01");
  // A private key others can read.
  fs::permissions(fleet / "identities" / "sim" / "key.pem", fs::perms::others_read,
                  fs::perm_options::add);
  expect_refused("sim", "chmod 600");
  // A certificate of another CA.
  const fs::path other = make_fleet("broken_other");
  fs::copy_file(other / "identities" / "uav-agent-0" / "cert.pem",
                fleet / "identities" / "uav-agent-0" / "cert.pem",
                fs::copy_options::overwrite_existing);
  expect_refused("uav-agent-0", "certificate not accepted");
  // A missing file, an unknown identity, no identity at all.
  fs::remove(fleet / "identities" / "ugv-agent-1" / "cert.pem");
  expect_refused("ugv-agent-1", "cannot read");
  const Outcome unknown = pub_as("uav-agent-7", "unknown");
  EXPECT_EQ(unknown.exit_code, 2);
  const Outcome none =
      cover_cli({"pub", "cover/task/abort", "{}", "--security", fleet.string()}, "none.log");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.log.find("no identity"), std::string::npos) << none.log;
}

// A fleet made for one day: inside the default 14-day warning window. A process still
// starts (the identity is valid) and logs when it expires and the time left; `cover
// security check` fails with 4 (expiring, not broken) until the window is narrowed.
// Domain 131.
TEST(SecurityFleet, ShortLivedFleetWarnsAtStartAndFailsTheCheck) {
  const fs::path fleet = make_fleet("short", {"--days", "1"});
  const Outcome pub =
      cover_cli(on("fastdds", 131,
                   std::vector<std::string>{"pub", "cover/task/abort", "{}", "--wait", "0"} +
                       secure(fleet, "ground-station-0")),
                "short_pub.log");
  EXPECT_EQ(pub.exit_code, 0) << pub.log;
  EXPECT_NE(pub.log.find("identity ground-station-0 expires on"), std::string::npos) << pub.log;
  // A day at most (whole seconds: made in the same second, exactly a day).
  EXPECT_TRUE(std::regex_search(pub.log, std::regex(", in (0 d 23 h [0-9]+|1 d 0 h 0) min")))
      << pub.log;
  EXPECT_NE(pub.log.find("within security.expiry_warning_days (14)"), std::string::npos) << pub.log;
  EXPECT_EQ(pub.out.find("expires"), std::string::npos) << "the warning belongs on stderr";

  const Outcome check = cover_cli({"security", "check", fleet.string()}, "short_check.log");
  EXPECT_EQ(check.exit_code, 4) << check.out << check.log;
  EXPECT_NE(check.out.find("CA: valid until"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("ground-station-0: valid until"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("EXPIRES WITHIN THE WARNING WINDOW"), std::string::npos) << check.out;
  const Outcome json = cover_cli({"security", "check", fleet.string(), "--json"}, "short_json.log");
  EXPECT_EQ(json.exit_code, 4);
  const auto report = nlohmann::json::parse(json.out);
  EXPECT_EQ(report["warning_days"], 14);
  EXPECT_TRUE(report["ca"]["expires_within_warning"].get<bool>());
  for (const auto& identity : report["identities"]) {
    EXPECT_TRUE(identity["expires_within_warning"].get<bool>()) << identity;
  }
  const Outcome narrow =
      cover_cli({"security", "check", fleet.string(), "--warning-days", "0"}, "short_narrow.log");
  EXPECT_EQ(narrow.exit_code, 0) << narrow.out << narrow.log;
  EXPECT_EQ(narrow.out.find("EXPIRES WITHIN"), std::string::npos) << narrow.out;
  const Outcome bad =
      cover_cli({"security", "check", fleet.string(), "--warning-days", "-1"}, "short_bad.log");
  EXPECT_EQ(bad.exit_code, 2) << bad.log;
}

struct LaunchOutcome {
  int exit_code = -1;
  nlohmann::json result;
  std::string text;
  std::map<std::string, std::string> logs;  // each process's log, by its launch name
};

LaunchOutcome launch(const std::vector<std::string>& flags, int domain) {
  const auto claim = cover::test::claim_domain(domain);
  const fs::path run_dir = cover::test::scratch_dir() / ("cover_sec_run_" + std::to_string(domain));
  fs::remove_all(run_dir);
  std::vector<std::string> argv{COVER_LAUNCH,
                                std::string(COVER_CONFIG_DIR) + "/launch/scenario2.yaml",
                                "--json",
                                "--domain",
                                std::to_string(domain),
                                "--run-dir",
                                run_dir.string()};
  argv = argv + flags;
  SpawnOptions options;
  options.capture_stdout = true;
  options.log_file = log_path("launch_" + std::to_string(domain) + ".log");
  ChildProcess child(argv, options);
  LaunchOutcome outcome;
  while (const auto line = child.read_line(std::chrono::seconds(300))) outcome.text += *line + "\n";
  outcome.exit_code = child.wait(std::chrono::seconds(300)).value_or(-1);
  outcome.text += read_text(options.log_file);
  outcome.result =
      nlohmann::json::parse(outcome.text.substr(0, outcome.text.find('\n')), nullptr, false);
  std::error_code missing;  // no run folder: nothing started
  for (const auto& entry : fs::directory_iterator(run_dir, missing)) {
    if (entry.path().extension() == ".log") {
      outcome.logs[entry.path().stem().string()] = read_text(entry.path().string());
    }
  }
  if (outcome.exit_code == 0) fs::remove_all(run_dir);
  return outcome;
}

// Scenario 2 as real processes, every one with its own identity (cover-launch by role).
TEST_P(Security, SecureScenarioTwoLands) {
  const std::string vendor = GetParam();
  const int domain = vendor == "fastdds" ? 127 : 128;
  const fs::path fleet = make_fleet(vendor, {"--vendor", vendor});
  const auto before = cover::test::shm_entries();
  const std::vector<std::string> flags{"--security", fleet.string(), "--dds", "*=" + vendor};
  LaunchOutcome run = launch(flags, domain);
  // docs/security.md, "a secure Fast DDS start can stall": a pair matched without data (or
  // never matched) and the simulator ended the run as stalled. What recovers it is new
  // participants, as an operator restarts the pair: one more run, which must fly.
  const auto stalled = [](const LaunchOutcome& r) {
    return r.logs.count("sim") && r.logs.at("sim").find("lockstep stalled") != std::string::npos;
  };
  if (run.exit_code != 0 && vendor == "fastdds" && stalled(run)) {
    std::cerr << "[ AGAIN    ] the secure Fast DDS start stalled (docs/security.md); "
                 "the run again with new participants\n";
    run = launch(flags, domain);
  }
  ASSERT_EQ(run.exit_code, 0) << run.text;
  EXPECT_TRUE(run.result["success"].get<bool>()) << run.result.dump(2);
  EXPECT_LE(run.result["landing_error_m"].get<double>(), 0.05);
  // The clock replies came on the UAV agent's own reply topic, which its permissions
  // grant it alone (cover/time/reply/cover_uav_agent_0; the answerers' a '*' pattern).
  const std::string uav_log = run.logs.count("uav0") ? run.logs.at("uav0") : "";
  const std::string summary = "clock replies delivered to ";
  const std::size_t at = uav_log.find(summary);
  ASSERT_NE(at, std::string::npos) << uav_log;
  const std::size_t count_at = uav_log.find(": ", at) + 2;
  EXPECT_GT(std::atoll(uav_log.c_str() + count_at), 0) << uav_log.substr(at, 120);
  EXPECT_NE(uav_log.find("clock offset to "), std::string::npos) << uav_log;
  for (const auto& [name, text] : run.logs) {
    EXPECT_EQ(text.find("cannot answer"), std::string::npos) << name << ": " << text;
  }
  for (const auto& name : cover::test::shm_entries()) {
    if (!before.count(name)) {
      EXPECT_TRUE(name.rfind("cover_sim_", 0) != 0) << name;
    }
  }
}

// Fast DDS 2.9 and Cyclone 0.10 do not reliably finish the security handshake with each
// other: a secure launch that mixes them is refused before anything starts.
TEST(SecurityFleet, MixedVendorSecureLaunchIsRefused) {
  const fs::path fleet = make_fleet("mixed");  // a Fast DDS fleet
  const LaunchOutcome run = launch({"--security", fleet.string(), "--dds", "ugv*=cyclone"}, 129);
  EXPECT_EQ(run.exit_code, 2) << run.text;
  EXPECT_NE(run.text.find("process 'ugv0'"), std::string::npos) << run.text;
  EXPECT_NE(run.text.find("a secure fleet runs one vendor"), std::string::npos) << run.text;
  const Outcome alone =
      cover_cli(on("cyclone", 129,
                   std::vector<std::string>{"pub", "cover/task/abort", "{}", "--wait", "0"} +
                       secure(fleet, "ground-station-0")),
                "mixed.log");
  EXPECT_EQ(alone.exit_code, 2);
  EXPECT_NE(alone.log.find("runs fastdds, this process cyclone"), std::string::npos) << alone.log;
}

}  // namespace
