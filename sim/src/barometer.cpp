#include "cover/sim/barometer.hpp"

#include <cmath>

namespace cover::sim {

namespace {

// ISA sea-level values and the troposphere's lapse rate; exponent g M / (R L).
constexpr double kSeaLevelPressurePa = 101325.0;
constexpr double kSeaLevelTemperatureK = 288.15;
constexpr double kLapseRateK_m = 0.0065;
constexpr double kExponent = 5.255877;
constexpr double kKelvinToCelsius = -273.15;

}  // namespace

double isa_pressure_pa(double altitude_amsl_m) {
  return kSeaLevelPressurePa *
         std::pow(1.0 - kLapseRateK_m * altitude_amsl_m / kSeaLevelTemperatureK, kExponent);
}

double isa_temperature_c(double altitude_amsl_m) {
  return kSeaLevelTemperatureK - kLapseRateK_m * altitude_amsl_m + kKelvinToCelsius;
}

double isa_altitude_m(double pressure_pa) {
  return kSeaLevelTemperatureK / kLapseRateK_m *
         (1.0 - std::pow(pressure_pa / kSeaLevelPressurePa, 1.0 / kExponent));
}

Barometer::Barometer(const BarometerParams& params, std::uint64_t seed)
    : params_(params), rng_(seed) {}

BarometerSample Barometer::sample(double world_z_m, double stamp_s) {
  const double altitude_m = params_.home_altitude_amsl_m + world_z_m;
  const double pressure_pa =
      isa_pressure_pa(altitude_m) + params_.pressure_noise_pa * unit_normal_(rng_);
  BarometerSample reading;
  reading.stamp_s = stamp_s;
  reading.pressure_hpa = pressure_pa / 100.0;
  reading.pressure_altitude_m = isa_altitude_m(pressure_pa);
  reading.temperature_c = isa_temperature_c(altitude_m);
  return reading;
}

}  // namespace cover::sim
