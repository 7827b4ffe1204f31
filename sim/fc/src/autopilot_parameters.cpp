#include "cover/sim/fc/autopilot_parameters.hpp"

#include "cover/mavlink/protocol.hpp"

namespace cover::sim::fc {

namespace {

namespace type = mavlink::mav_param_type;

// Types as PX4 SITL (02e73e3b) answered them: REAL32 (9) or INT32 (6).
std::vector<AutopilotParameter> px4_table(const SimFcParams& p, std::uint8_t system_id) {
  const Px4Params& x = p.px4;
  return {
      {"COM_OF_LOSS_T", type::kReal32, x.com_of_loss_t_s},
      {"COM_OBL_RC_ACT", type::kInt32, static_cast<double>(x.com_obl_rc_act)},
      {"MPC_THR_HOVER", type::kReal32, x.mpc_thr_hover},
      {"COM_DISARM_PRFLT", type::kReal32, x.com_disarm_prflt_s},
      {"COM_DISARM_LAND", type::kReal32, x.com_disarm_land_s},
      {"COM_RC_IN_MODE", type::kInt32, static_cast<double>(x.com_rc_in_mode)},
      {"NAV_DLL_ACT", type::kInt32, static_cast<double>(x.nav_dll_act)},
      {"MPC_LAND_SPEED", type::kReal32, p.land_speed_m_s},
      {"MAV_SYS_ID", type::kInt32, static_cast<double>(system_id)},
  };
}

// Types as ArduCopter SITL (V4.7.0-dev, 90700977) answered them: INT8 (2), INT16 (4),
// INT32 (6), REAL32 (9). SYSID_THISMAV (before 4.7) is not answered, as there.
std::vector<AutopilotParameter> ardupilot_table(const SimFcParams& p, std::uint8_t system_id) {
  const ArduPilotParams& a = p.ardupilot;
  return {
      {"ATC_ANGLE_BOOST", type::kInt8, static_cast<double>(a.atc_angle_boost)},
      {"GUID_OPTIONS", type::kInt32, static_cast<double>(a.guid_options)},
      {"GUID_TIMEOUT", type::kReal32, a.guid_timeout_s},
      {"FS_GCS_ENABLE", type::kInt8, static_cast<double>(a.fs_gcs_enable)},
      {"FS_GCS_TIMEOUT", type::kReal32, a.fs_gcs_timeout_s},
      {"MAV_GCS_SYSID", type::kInt16, static_cast<double>(watched_gcs_sysid(a, system_id))},
      {"FS_THR_ENABLE", type::kInt8, static_cast<double>(a.fs_thr_enable)},
      {"MOT_THST_HOVER", type::kReal32, a.mot_thst_hover},
      {"DISARM_DELAY", type::kInt8, static_cast<double>(a.disarm_delay_s)},
      {"MAV_SYSID", type::kInt16, static_cast<double>(system_id)},
  };
}

// ArduPilot's param_index of an answer to a request by name.
constexpr std::uint16_t kArduPilotByName = 65535;

}  // namespace

AutopilotParameters::AutopilotParameters(Autopilot profile, const SimFcParams& params,
                                         std::uint8_t system_id)
    : profile_(profile),
      encoding_(profile == Autopilot::Px4 ? mavlink::ParamEncoding::Bytewise
                                          : mavlink::ParamEncoding::CCast),
      table_(profile == Autopilot::Px4 ? px4_table(params, system_id)
                                       : ardupilot_table(params, system_id)) {}

std::optional<std::size_t> AutopilotParameters::index_of(const std::string& name) const {
  for (std::size_t i = 0; i < table_.size(); ++i) {
    if (table_[i].name == name) return i;
  }
  return std::nullopt;
}

mavlink::ParamValue AutopilotParameters::value_message(std::size_t index, bool by_name) const {
  const AutopilotParameter& p = table_[index];
  mavlink::ParamValue v;
  v.param_id = mavlink::param_id_from(p.name);
  v.param_type = p.type;
  v.param_value = mavlink::param_field_of(p.value, p.type, encoding_);
  v.param_count = static_cast<std::uint16_t>(table_.size());
  v.param_index = by_name && profile_ == Autopilot::ArduPilot ? kArduPilotByName
                                                              : static_cast<std::uint16_t>(index);
  return v;
}

}  // namespace cover::sim::fc
