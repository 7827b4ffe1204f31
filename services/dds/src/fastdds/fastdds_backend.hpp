#pragma once

#include <memory>

#include "cover/dds/backend.hpp"
#include "cover/dds/participant_options.hpp"

namespace cover::dds {

// Creates a Fast DDS participant; throws DdsError on failure.
std::unique_ptr<ParticipantBackend> make_fastdds_participant(const ParticipantOptions& options);

}  // namespace cover::dds
