#pragma once
// Physical parameters of the `amb1dof_voltage` plant model (experiment-format.md, "Plant model
// amb1dof_voltage"; seed 000 eq. 1): one bearing axis, two opposing voltage-driven coils.
// SI units throughout: m [kg], x0 [m], i0 [A], Rj [ohm], Lsj [H], Kj [H m], kwj [V/V].
#include <map>
#include <string>
#include <vector>

namespace ambid::sim {

struct Amb1dofParameters {
  double m = 0.0;               // rotor mass
  double x0 = 0.0;              // nominal air gap (clearance) of each coil
  double i0 = 0.0;              // bias current of both coils at the operating point
  double R1 = 0.0, R2 = 0.0;    // coil resistances
  double Ls1 = 0.0, Ls2 = 0.0;  // leakage inductances
  double K1 = 0.0, K2 = 0.0;    // force constants: Fj = Kj/4 (ij / gap_j)^2
  double kw1 = 0.0, kw2 = 0.0;  // amplifier gains (coil voltage per commanded volt)

  // Seed 000 "Computer simulation", inductances in henry (see the contract).
  static Amb1dofParameters nominal();

  // The eleven parameters under their contract names (m, x0, i0, R1, R2, Ls1, Ls2, K1, K2,
  // kw1, kw2). from_map requires every name (Error naming the first missing one) and, like
  // the experiment contract, ignores other keys. The result is validated.
  std::map<std::string, double> to_map() const;
  static Amb1dofParameters from_map(const std::map<std::string, double>& values);

  // Sets one parameter by name; an unknown name is an Error listing the valid names.
  // Does not validate (call validate() after a batch of changes).
  void set(const std::string& name, double value);
  double get(const std::string& name) const;

  // Every parameter finite and strictly positive; otherwise Error naming it and its value.
  void validate() const;

  // Total coil inductance at the operating point, Lj = Lsj + Kj / (2 x0) [H].
  double L1() const;
  double L2() const;

  static const std::vector<std::string>& names();
};

}  // namespace ambid::sim
