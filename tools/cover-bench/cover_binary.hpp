#pragma once

#include <string>

namespace cover::bench {

// The path of the COVER program `name` ("cover-launch", "cover", "cover-sim"): the build's
// own (the folders CMake gives as COVER_BUILD_BIN_DIRS), else the one beside cover-bench
// (an installed set), else the first on $PATH; the bare name when none has it, so that
// starting it fails with its name in the error.
std::string cover_binary(const std::string& name);

}  // namespace cover::bench
