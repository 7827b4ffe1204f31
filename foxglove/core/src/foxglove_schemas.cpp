#include "cover/foxglove/foxglove_schemas.hpp"

#include <nlohmann/json.hpp>

namespace cover::foxglove {
namespace {

using nlohmann::json;

json number() {
  return {{"type", "number"}};
}

json object(const std::string& title, json properties) {
  return {{"title", title}, {"type", "object"}, {"properties", std::move(properties)}};
}

json time() {
  return object("time", {{"sec", {{"type", "integer"}, {"minimum", 0}}},
                         {"nsec", {{"type", "integer"}, {"minimum", 0}, {"maximum", 999999999}}}});
}

json vector3() {
  return object("foxglove.Vector3", {{"x", number()}, {"y", number()}, {"z", number()}});
}

json quaternion() {
  return object("foxglove.Quaternion",
                {{"x", number()}, {"y", number()}, {"z", number()}, {"w", number()}});
}

json color() {
  return object("foxglove.Color",
                {{"r", number()}, {"g", number()}, {"b", number()}, {"a", number()}});
}

json pose() {
  return object("foxglove.Pose", {{"position", vector3()}, {"orientation", quaternion()}});
}

json array_of(json items) {
  return {{"type", "array"}, {"items", std::move(items)}};
}

json scene_entity() {
  const json cube =
      object("foxglove.CubePrimitive", {{"pose", pose()}, {"size", vector3()}, {"color", color()}});
  const json arrow = object("foxglove.ArrowPrimitive", {{"pose", pose()},
                                                        {"shaft_length", number()},
                                                        {"shaft_diameter", number()},
                                                        {"head_length", number()},
                                                        {"head_diameter", number()},
                                                        {"color", color()}});
  const json line =
      object("foxglove.LinePrimitive",
             {{"type", {{"type", "integer"}, {"description", "0 strip, 1 loop, 2 list"}}},
              {"pose", pose()},
              {"thickness", number()},
              {"scale_invariant", {{"type", "boolean"}}},
              {"points", array_of(vector3())},
              {"color", color()},
              {"colors", array_of(color())},
              {"indices", array_of({{"type", "integer"}})}});
  const json text = object("foxglove.TextPrimitive", {{"pose", pose()},
                                                      {"billboard", {{"type", "boolean"}}},
                                                      {"font_size", number()},
                                                      {"scale_invariant", {{"type", "boolean"}}},
                                                      {"color", color()},
                                                      {"text", {{"type", "string"}}}});
  json duration = time();
  duration["title"] = "duration";
  return object(
      "foxglove.SceneEntity",
      {{"timestamp", time()},
       {"frame_id", {{"type", "string"}}},
       {"id", {{"type", "string"}}},
       {"lifetime", duration},
       {"frame_locked", {{"type", "boolean"}}},
       {"metadata", array_of(object("foxglove.KeyValuePair", {{"key", {{"type", "string"}}},
                                                              {"value", {{"type", "string"}}}}))},
       {"arrows", array_of(arrow)},
       {"cubes", array_of(cube)},
       {"spheres", array_of(cube)},
       {"cylinders", array_of(json::object())},
       {"lines", array_of(line)},
       {"triangles", array_of(json::object())},
       {"texts", array_of(text)},
       {"models", array_of(json::object())}});
}

}  // namespace

std::string frame_transform_json_schema() {
  return object(kFrameTransformSchema, {{"timestamp", time()},
                                        {"parent_frame_id", {{"type", "string"}}},
                                        {"child_frame_id", {{"type", "string"}}},
                                        {"translation", vector3()},
                                        {"rotation", quaternion()}})
      .dump();
}

std::string scene_update_json_schema() {
  const json deletion = object(
      "foxglove.SceneEntityDeletion",
      {{"timestamp", time()}, {"type", {{"type", "integer"}}}, {"id", {{"type", "string"}}}});
  return object(kSceneUpdateSchema,
                {{"deletions", array_of(deletion)}, {"entities", array_of(scene_entity())}})
      .dump();
}

Channel json_channel(const std::string& topic, const std::string& schema_name) {
  Channel c;
  c.topic = topic;
  c.encoding = "json";
  c.schema_name = schema_name;
  c.schema_encoding = "jsonschema";
  c.schema = schema_name == kFrameTransformSchema ? frame_transform_json_schema()
                                                  : scene_update_json_schema();
  return c;
}

}  // namespace cover::foxglove
