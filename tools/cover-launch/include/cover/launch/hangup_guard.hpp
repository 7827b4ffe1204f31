#pragma once

namespace cover::launch {

// A field vehicle must not lose its processes to the link it is operated over: closing the
// terminal that runs cover-launch, or dropping the SSH session, sends SIGHUP, and a reader
// of stdout that went away makes the next write raise SIGPIPE; either would kill the
// launcher, and every child with it (they die with their parent). install() blocks both in
// every thread; a watcher thread takes each SIGHUP with sigwait and logs it, and the
// launcher keeps supervising. A write to a vanished stdout then fails with EPIPE instead.
// Call first in main(), before any thread exists (ShutdownSignal::install starts one).
class HangupGuard {
 public:
  static void install();
  // SIGHUPs received so far.
  static int count();
};

}  // namespace cover::launch
