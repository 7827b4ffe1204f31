#pragma once

#include <string>

namespace cover::config {

// Where COVER keeps what outlives a run on this machine (the task manager's database), as
// the XDG Base Directory specification places a program's state: $XDG_STATE_HOME/cover,
// else $HOME/.local/state/cover (a relative value of either is ignored, as the
// specification asks). Never the working directory, which is whatever folder a system was
// started from (issue 31: a repository's root). Throws ConfigError when neither variable
// gives an absolute path.
std::string default_state_dir();

// Creates `dir` and its parents when missing (a new folder 0700: another user has no
// business reading a fleet's tasks). Throws ConfigError naming `dir` when it cannot.
void create_state_dir(const std::string& dir);

}  // namespace cover::config
