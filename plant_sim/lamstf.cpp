#include "plant_sim/lamstf.hpp"

namespace ambid::sim {

NamedSystem lamstf() {
  Eigen::MatrixXd A21(5, 5), B2(5, 5), C1(5, 5);
  // Seed 002 eq. (3.1)-(3.2), printed to four or five significant digits; the "-0.0000"
  // entries of the print are zero.
  A21 << 3341.5, 0, -39392, 0, 0, 0, 3341.5, 0, 0, 0, -9.8070, 0, 49.937, 0, -0.0251, 0, 0, 0, 95.577, 0, 0, 0, -0.0251,
      0, -0.9132;
  // B2(1,1) is printed "538.370" (OCR of 38.370: the row is constant). B2(5,1) is printed
  // -0.2767; the identified B2(5,1) = +0.2773 and the sign pattern of the row say +0.2767.
  // B2 does not enter the open-loop eigenvalues, so Table 3.1 cannot decide between them.
  B2 << 38.370, 38.370, 38.370, 38.370, 38.370, 0, 89.802, 55.514, -55.514, -89.802, 0.2214, -0.1527, 0.0784, 0.0784,
      -0.1527, 0, 0.1215, -0.1967, 0.1967, -0.1215, 0.2767, -0.0854, 0.2238, 0.2238, -0.0854;
  C1 << 89.024, 0, 0, 0, 6097.6, 0, 0, 7874.0, 0, 0, -116.25, 0, 0, 0, 6250.0, 0, 95.425, 0, -6535.9, 0, 0, -107.25, 0,
      -5181.3, 0;

  NamedSystem out;
  out.model = "lamstf";
  ContinuousSystem& s = out.system;
  s.A = Eigen::MatrixXd::Zero(10, 10);
  s.A.topRightCorner(5, 5).setIdentity();
  s.A.bottomLeftCorner(5, 5) = A21;  // A22 = 0: no damping in the analytical model
  s.B = Eigen::MatrixXd::Zero(10, 5);
  s.B.bottomRows(5) = B2;
  s.C = Eigen::MatrixXd::Zero(5, 10);
  s.C.leftCols(5) = C1;
  s.D = Eigen::MatrixXd::Zero(5, 5);
  out.state_names = {"pitch", "yaw", "x", "y", "z", "pitch_dot", "yaw_dot", "x_dot", "y_dot", "z_dot"};
  out.input_names = {"i1", "i2", "i3", "i4", "i5"};
  out.output_names = {"s1", "s2", "s3", "s4", "s5"};
  return out;
}

}  // namespace ambid::sim
