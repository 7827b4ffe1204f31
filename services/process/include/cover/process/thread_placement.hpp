#pragma once

#include <string>

namespace cover::process {

// Where a realtime loop's threads run: the calling thread alone on one CPU, every other
// thread of the process on the rest of the CPUs the process was started with. A control
// thread that shares its core with the DDS receive threads finds its caches emptied by them
// between its rehearsal and its measurement; alone on its core it does not, and it may wait
// for its sample on the CPU without holding those threads off.
struct ThreadPlacement {
  bool placed = false;
  int threads_moved = 0;  // the process's other threads, put on `others`
  std::string others;     // "0" or "0,2-3": where they run now
  std::string error;      // why not placed (a CPU the process may not use, one CPU only)
};

// Places the calling thread on `cpu` and the process's other threads on `allowed` minus
// `cpu`, where `allowed` is the CPU list the process started with (first call) — threads
// started later by the calling thread inherit its CPU, so call it again after starting one.
ThreadPlacement place_calling_thread_alone(int cpu);

}  // namespace cover::process
