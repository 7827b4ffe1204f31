#pragma once

namespace cover::dds {

// Per-vendor operations on one message type (defined in the vendor backends, filled by
// code generated from the IDL). Opaque here so that no vendor header leaks out.
struct FastDdsTypeOps;
struct CycloneTypeOps;

// Everything the DDS layer needs to move a vendor-neutral `cover::msg::X` through either
// vendor: its registered type name, sample allocation, and each vendor's conversions.
struct TypeSupport {
  const char* type_name;  // scoped IDL name, identical on both vendors
  void* (*new_sample)();
  void (*delete_sample)(void* sample);
  void (*copy_sample)(const void* from, void* to);
  const FastDdsTypeOps* fastdds;
  const CycloneTypeOps* cyclone;
};

// Specialised for every IDL struct by the generated type_support.cpp.
template <typename T>
const TypeSupport& type_support();

template <typename T>
TypeSupport make_type_support(const FastDdsTypeOps* fastdds, const CycloneTypeOps* cyclone) {
  return TypeSupport{
      T::kTypeName,
      []() -> void* { return new T(); },
      [](void* sample) { delete static_cast<T*>(sample); },
      [](const void* from, void* to) { *static_cast<T*>(to) = *static_cast<const T*>(from); },
      fastdds,
      cyclone,
  };
}

}  // namespace cover::dds
