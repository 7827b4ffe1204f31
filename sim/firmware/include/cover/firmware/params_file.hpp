#pragma once

#include <filesystem>

#include "cover/firmware/sitl_process.hpp"

namespace cover::firmware {

// A firmware parameter file (config/firmware/*.params, ArduPilot's *.parm): one `NAME value`
// per line (`NAME,value` as ArduPilot's --defaults also reads it), `#` starts a comment,
// blank lines skipped. Throws std::runtime_error naming the file and line
// of a line that is not two words, or a file that cannot be read.
FirmwareParams read_params_file(const std::filesystem::path& path);

// A parameter value that stands for the instance's own system id: COVER's bridge speaks
// with the vehicle's id, so ArduCopter's MAV_GCS_SYSID (the system whose HEARTBEAT its GCS
// failsafe watches) is the instance's, whichever instance it is.
inline constexpr const char* kOwnSystemId = "$SYSID";

// `params` as ArduPilot's --defaults reads them, one `NAME value` a line, kOwnSystemId as
// `own_system_id`. Throws std::runtime_error naming the file when it cannot be written.
void write_arducopter_params(const std::filesystem::path& path, const FirmwareParams& params,
                             int own_system_id);

}  // namespace cover::firmware
