#pragma once

#include <cstdint>
#include <string>

#include "cover/foxglove/protocol.hpp"

// Foxglove's own 3D message types, which its 3D panel shows without configuration, in
// their JSON encoding (encoding `json`, schemaEncoding `jsonschema`): Foxglove decodes
// JSON natively and recognises these schema names; the JSON Schemas below describe the
// fields we send (the field names and layout of Foxglove's schemas 2.x).
namespace cover::foxglove {

inline constexpr const char* kFrameTransformSchema = "foxglove.FrameTransform";
inline constexpr const char* kSceneUpdateSchema = "foxglove.SceneUpdate";

std::string frame_transform_json_schema();
std::string scene_update_json_schema();

// A channel of JSON messages of a Foxglove schema (its id is given by the server).
Channel json_channel(const std::string& topic, const std::string& schema_name);

}  // namespace cover::foxglove
