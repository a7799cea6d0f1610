// What diagnostics has per plant family: a piece a family lacks, or an unknown family, is a
// clear error naming it.
#include "diagnostics/plant_families.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace ambid::diag {
namespace plant_families_test {

std::string error_of(const std::string& model, DiagnosticsPiece piece) {
  try {
    require_diagnostics_piece(model, piece, "audit");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(DiagnosticsFamilies, TheBearingAndTheMaglevHaveEveryPiece) {
  EXPECT_EQ(error_of("amb1dof_voltage", DiagnosticsPiece::effect_catalogue), "");
  EXPECT_EQ(error_of("amb1dof_voltage", DiagnosticsPiece::fault_signatures), "");
  EXPECT_EQ(error_of("maglev1coil_voltage", DiagnosticsPiece::fault_signatures), "");
}

TEST(DiagnosticsFamilies, EachFamilyBringsItsMonitoredParameters) {
  EXPECT_EQ(monitored_parameters("amb1dof_voltage"),
            (std::vector<std::string>{"R1", "R2", "kw1", "kw2", "kr1", "kr2", "ks"}));
  EXPECT_EQ(monitored_parameters("maglev1coil_voltage"), (std::vector<std::string>{"R", "L", "Km", "n_i", "n_x"}));
  EXPECT_EQ(parameter_role("maglev1coil_voltage", "R").fault, "coil_resistance");
  EXPECT_EQ(parameter_role("amb1dof_voltage", "R1").channel, 1);
  try {
    parameter_role("amb1dof_voltage", "R");
    ADD_FAILURE() << "R is not a bearing's parameter";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "diagnostics: parameter 'R' is not monitored for amb1dof_voltage (monitored: R1, R2, kw1, kw2, kr1, "
              "kr2, ks)");
  }
  EXPECT_EQ(monitored_family("maglev1coil_voltage", "test").window_method, "greybox");
}

TEST(DiagnosticsFamilies, EachFamilyBringsItsOwnCatalogue) {
  EXPECT_EQ(error_of("maglev1coil_voltage", DiagnosticsPiece::effect_catalogue), "");
  std::vector<std::string> names;
  for (const auto& spec : effect_catalogue_of("maglev1coil_voltage", "audit")) names.push_back(spec.name);
  EXPECT_EQ(names, (std::vector<std::string>{"force_law", "coil_resistance", "amplifier_gain", "sensor_gain",
                                             "sensor_offset", "sensor_nonlinearity", "sensor_delay",
                                             "actuator_quantisation", "rotor_mass", "harmonic_disturbance"}));
  EXPECT_EQ(effect_catalogue_of("amb1dof_voltage", "audit").size(), 12u);
  // A name both families use has each family's scale: a coil of 210 ohm, not of 17.5.
  EXPECT_EQ(
      sim::effect_spec(effect_catalogue_of("maglev1coil_voltage", "audit"), "coil_resistance").parameters[0].scale,
      10.0);
}

TEST(DiagnosticsFamilies, MissingPiecesAndUnknownFamiliesAreNamed) {
  EXPECT_EQ(error_of("lamstf", DiagnosticsPiece::fault_signatures),
            "audit: plant model 'lamstf' has no fault signatures (nor monitored parameters) yet");
  EXPECT_EQ(error_of("lamstf", DiagnosticsPiece::effect_catalogue),
            "audit: plant model 'lamstf' has no effect catalogue yet");
  EXPECT_EQ(error_of("lamstf5", DiagnosticsPiece::fault_signatures),
            "audit: unknown plant 'lamstf5' (known: amb1dof_voltage, maglev1coil_voltage, lamstf)");
}

}  // namespace plant_families_test
}  // namespace ambid::diag
