#pragma once
// Physical parameters of the `maglev1coil_voltage` plant model (experiment-format.md, "Plant
// families"; ../shared/notes/maglev-rig.md): one electromagnet holding a levitated body below
// it against gravity. SI units: m [kg], g [m/s^2], R [ohm], L [H], Km and Ke [N m^n_x / A^n_i],
// kw [V/V], n_i and n_x [-], x_min and x_max [m] (the mechanical stops).
//   m x'' = m g - Km i^n_i / x^n_x + Fz
//   L i'  = kw u - R i - e,   e = -n_i Ke i^(n_i - 1) x' / x^n_x
// The back-EMF is the motional EMF of the co-energy whose force is the one above (Ke = Km for a
// lossless coil): n_i = 2, n_x = 2 gives the reluctance law's -2 Ke i x'/x^2, n_i = 1, n_x = 4
// the dipole law's -Ke x'/x^4. (The note prints the reluctance term with a + sign; the energy
// balance fixes it: moving away from the coil lowers the flux and the EMF drives the current up.)
#include <map>
#include <string>
#include <vector>

namespace ambid::sim {

struct MaglevParameters {
  double m = 0.0;             // levitated mass
  double g = 0.0;             // gravity
  double R = 0.0, L = 0.0;    // coil resistance and inductance
  double Km = 0.0, Ke = 0.0;  // force and back-EMF constants
  double kw = 0.0;            // actuator gain (coil voltage per commanded volt)
  double n_i = 0.0, n_x = 0.0;
  double x_min = 0.0, x_max = 0.0;  // stops: top (magnet against the coil side) and ground

  // The dipole-law values published for the rig (m = 0.74 g, R = 210 ohm, L = 0.3 H,
  // Km = Ke = 1.5e-8, stops 12 and 17 mm): their own equilibrium at 14 mm is 18.6 mA, 3.9 V.
  static MaglevParameters nominal();

  // Under the contract names (m, g, R, L, Km, Ke, kw, n_i, n_x, x_min, x_max). from_map requires
  // every name (Error naming the first missing one), ignores other keys, and validates.
  std::map<std::string, double> to_map() const;
  static MaglevParameters from_map(const std::map<std::string, double>& values);
  // Error listing the valid names for an unknown one; does not validate.
  void set(const std::string& name, double value);
  // Every value finite and positive, x_min < x_max; otherwise Error naming it and its value.
  void validate() const;
  static const std::vector<std::string>& names();

  // F = Km i^n_i / x^n_x (for i >= 0; sign(i) |i|^n_i below).
  double force(double current, double gap) const;
  // The current that holds the body at `gap`: Km i^n_i / gap^n_x = m g.
  double equilibrium_current(double gap) const;
};

}  // namespace ambid::sim
