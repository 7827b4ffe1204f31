#pragma once

#include <filesystem>

#include "cover/firmware/sitl_process.hpp"

namespace cover::firmware {

// A firmware parameter file (config/firmware/*.params, ArduPilot's *.parm): one `NAME value`
// per line (`NAME,value` as ArduPilot's --defaults also reads it), `#` starts a comment,
// blank lines skipped. Throws std::runtime_error naming the file and line
// of a line that is not two words, or a file that cannot be read.
FirmwareParams read_params_file(const std::filesystem::path& path);

}  // namespace cover::firmware
