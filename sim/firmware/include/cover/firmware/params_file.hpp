#pragma once

#include <filesystem>

#include "cover/firmware/sitl_process.hpp"

namespace cover::firmware {

// A firmware parameter file (config/firmware/*.params): one `NAME value` per line, `#`
// starts a comment, blank lines skipped. Throws std::runtime_error naming the file and line
// of a line that is not two words, or a file that cannot be read.
FirmwareParams read_params_file(const std::filesystem::path& path);

}  // namespace cover::firmware
