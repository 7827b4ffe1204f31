#pragma once

#include <cstdint>
#include <random>

#include "cover/config/param_fields.hpp"
#include "cover/sim/sensor_rate_field.hpp"

namespace cover::sim {

// A barometer over the International Standard Atmosphere's troposphere: the static
// pressure at the UAV's altitude above mean sea level (home altitude + world z), with white
// noise on the pressure; the temperature the ISA lapse rate gives.
struct BarometerParams {
  double rate_hz = 50.0;                // Gazebo iris's barometer_plugin pubRate
  double home_altitude_amsl_m = 488.0;  // PX4 SITL's default home (Zurich)
  double pressure_noise_pa = 1.2;       // about 0.1 m of altitude near sea level

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("rate_hz", self.rate_hz,
          sensor_rate_field("sample rate (Gazebo iris: 50); must divide the physics rate"));
    visit("home_altitude_amsl_m", self.home_altitude_amsl_m,
          Field("m", "altitude above mean sea level of the world's z = 0")
              .at_least(-400.0)
              .at_most(10000.0));
    visit("pressure_noise_pa", self.pressure_noise_pa,
          Field("Pa", "static pressure white noise 1-sigma").at_least(0.0).at_most(1000.0));
  }
};

struct BarometerSample {
  double stamp_s = 0.0;
  double pressure_hpa = 0.0;
  double pressure_altitude_m = 0.0;  // the ISA altitude of the (noisy) pressure
  double temperature_c = 0.0;
};

// ISA troposphere: pressure (Pa) and temperature (deg C) at `altitude_amsl_m`, and back.
double isa_pressure_pa(double altitude_amsl_m);
double isa_temperature_c(double altitude_amsl_m);
double isa_altitude_m(double pressure_pa);

class Barometer {
 public:
  Barometer(const BarometerParams& params, std::uint64_t seed);
  BarometerSample sample(double world_z_m, double stamp_s);

 private:
  BarometerParams params_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_normal_{0.0, 1.0};
};

}  // namespace cover::sim
