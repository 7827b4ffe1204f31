// fake_process: a stand-in for cover-sim and the agents in cover-launch's tests.
// It prints its pid, COVER_DDS, COVER_DDS_DOMAIN and its arguments, then behaves as told by
// `--mode=`:
//   wait    (default) run until SIGINT or SIGTERM, print which one, exit 0
//   exit    exit with --code=N after --after-ms=T
//   ignore  ignore SIGINT and SIGTERM: only SIGKILL ends it
//   signal  die at once by SIGUSR1 (a crash without a core dump)
// It also lists any descriptor above 2 it inherited ("open fd: N"), whether it leads its
// own session ("session leader: yes|no") and whether SIGHUP is ignored ("sighup: ignored" or
// "sighup: default"). Other options: --ready=PATH
// (create PATH once signals are handled, so a test knows the process is up), --await=PATH (mode
// exit: first wait until PATH exists; repeatable),
// --shm=NAME (create /dev/shm/NAME and leave it), --result=PATH (write {"fake": true}),
// --once=PATH (a first run, PATH absent, creates PATH and exits with --code at once, before
// --ready; a later run, PATH present, goes on as told: a respawned process that dies once).
// Unknown arguments are only printed. Every mode gives up after 30 s, so a broken test
// cannot leave it running for ever.
#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr int kGiveUpSeconds = 30;

struct Options {
  std::string mode = "wait";
  int code = 0;
  int after_ms = 0;
  std::string ready;
  std::vector<std::string> await;
  std::string shm;
  std::string result;
  std::string once;
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&](const char* key) -> const char* {
      const std::size_t n = std::strlen(key);
      return arg.compare(0, n, key) == 0 ? argv[i] + n : nullptr;
    };
    if (auto v = value("--mode=")) options.mode = v;
    if (auto v = value("--code=")) options.code = std::atoi(v);
    if (auto v = value("--after-ms=")) options.after_ms = std::atoi(v);
    if (auto v = value("--ready=")) options.ready = v;
    if (auto v = value("--await=")) options.await.push_back(v);
    if (auto v = value("--shm=")) options.shm = v;
    if (auto v = value("--result=")) options.result = v;
    if (auto v = value("--once=")) options.once = v;
  }
  return options;
}

void print_environment(int argc, char** argv) {
  const char* vendor = std::getenv("COVER_DDS");
  const char* domain = std::getenv("COVER_DDS_DOMAIN");
  std::printf("pid: %d\n", static_cast<int>(getpid()));
  std::printf("COVER_DDS=%s\nCOVER_DDS_DOMAIN=%s\n", vendor ? vendor : "", domain ? domain : "");
  std::printf("session leader: %s\n", getsid(0) == getpid() ? "yes" : "no");
  struct sigaction hangup {};
  sigaction(SIGHUP, nullptr, &hangup);
  std::printf("sighup: %s\n", hangup.sa_handler == SIG_IGN ? "ignored" : "default");
  // The scheduling of a thread started now: what every thread of a real process gets.
  std::thread([] {
    int policy = 0;
    sched_param param{};
    pthread_getschedparam(pthread_self(), &policy, &param);
    std::printf("thread sched: %s %d\n", policy == SCHED_FIFO ? "fifo" : "other",
                param.sched_priority);
    cpu_set_t set;
    CPU_ZERO(&set);
    std::string cpus;
    if (pthread_getaffinity_np(pthread_self(), sizeof set, &set) == 0) {
      for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
        if (CPU_ISSET(cpu, &set)) cpus += (cpus.empty() ? "" : ",") + std::to_string(cpu);
      }
    }
    std::printf("thread cpus: %s\n", cpus.c_str());
  }).join();
  for (int i = 1; i < argc; ++i) std::printf("arg: %s\n", argv[i]);
  // Descriptors beyond stdin, stdout and stderr that the launcher let through.
  if (DIR* fds = opendir("/proc/self/fd")) {
    while (const dirent* entry = readdir(fds)) {
      const int fd = std::atoi(entry->d_name);
      if (fd > 2 && fd != dirfd(fds)) std::printf("open fd: %d\n", fd);
    }
    closedir(fds);
  }
  std::fflush(stdout);
}

void touch(const std::string& path, const std::string& content) {
  std::ofstream(path) << content;
}

void wait_for_files(const std::vector<std::string>& paths) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kGiveUpSeconds);
  for (const auto& path : paths) {
    while (access(path.c_str(), F_OK) != 0 && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));  // polling, with a give-up
    }
  }
}

int wait_for_signal() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  timespec timeout{kGiveUpSeconds, 0};
  const int received = sigtimedwait(&set, nullptr, &timeout);
  std::printf("got %s\n", received == SIGINT    ? "SIGINT"
                          : received == SIGTERM ? "SIGTERM"
                                                : "timeout");
  return received > 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  if (options.mode == "ignore") {
    signal(SIGINT, SIG_IGN);
    signal(SIGTERM, SIG_IGN);
  } else if (options.mode == "wait") {
    sigprocmask(SIG_BLOCK, &set, nullptr);  // taken with sigtimedwait
  }
  print_environment(argc, argv);
  if (!options.once.empty() && access(options.once.c_str(), F_OK) != 0) {
    touch(options.once, "first run\n");
    std::printf("first run: exiting with %d\n", options.code);
    return options.code;
  }
  if (!options.shm.empty()) {
    const int fd = shm_open(("/" + options.shm).c_str(), O_CREAT | O_RDWR, 0600);
    if (fd >= 0) close(fd);
  }
  if (!options.result.empty()) touch(options.result, "{\"fake\": true, \"score\": 7}\n");
  if (!options.ready.empty()) touch(options.ready, "ready\n");
  if (options.mode == "signal") raise(SIGUSR1);
  if (options.mode == "exit") {
    wait_for_files(options.await);
    // Ends late on purpose: the behaviour a test asks of this stand-in, not a synchronisation.
    std::this_thread::sleep_for(std::chrono::milliseconds(options.after_ms));
    std::printf("exiting with %d\n", options.code);
    return options.code;
  }
  if (options.mode == "ignore") {
    std::this_thread::sleep_for(std::chrono::seconds(kGiveUpSeconds));  // deaf until killed
    return 1;
  }
  return wait_for_signal();
}
