#pragma once
// The innovations predictor of the amb1dof_voltage structure (amb1dof_structure.hpp, seed 000
// eq. 4) sampled with a zero-order hold, and its exact derivatives by forward sensitivities:
//   x^[t+1] = Ad x^[t] + Bd [u[t]; 1] + K e[t],   e[t] = y[t] - C x^[t],   x^[0] = x0,
// C picking x, i1, i2. theta = [v1..v9, w (3 constant terms of the x'', i1', i2' rows), x0 (4),
// K (4 x 3, row-major)]: 28 parameters.
//
// Derivatives without dual numbers: [Ad Bd] and d[Ad Bd]/d theta_k (v and w) once per
// evaluation from the block-triangular exponential expm([M dM_k; 0 M]) = [E dE_k; 0 E],
// M = [A B; 0 0] T (the Frechet derivative of expm); then per sample the sensitivity
// psi = d x^ / d theta (4 x 28) runs through the predictor's own dynamics Ad - K C:
//   psi[t+1] = (Ad - K C) psi[t] + dAd_k x^[t] + dBd_k [u[t]; 1] (k in v, w) + dK/dtheta e[t],
//   psi[0] = [0 | I (x0 columns) | 0],   de[t]/dtheta = -C psi[t].
// Cost per sample: about 1000 multiply-adds, independent of the record length.
#include <array>
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace ambid::ident::pem {

constexpr int kStructure = 9;                        // v1..v9
constexpr int kModel = 12;                           // v and w: the parameters of Ad, Bd
constexpr int kInitial = 12;                         // first x0 column
constexpr int kGain = 16;                            // first K column
constexpr int kParameters = 28;                      // v, w, x0, K
constexpr std::array<int, 3> kMeasured = {0, 2, 3};  // states measured as y = [x, i1, i2]

using Vector9 = Eigen::Matrix<double, 9, 1>;
using Parameters = Eigen::Matrix<double, kParameters, 1>;
using Gain = Eigen::Matrix<double, 4, 3>;

Parameters pack(const Vector9& v, const Eigen::Vector3d& w, const Eigen::Vector4d& x0, const Gain& K);
Gain gain_of(const Parameters& theta);

// Ac(v) and [Bc(v) w]: inputs u1, u2 and the constant 1.
void structure_matrices(const Eigen::Ref<const Vector9>& v, const Eigen::Vector3d& w, Eigen::Matrix4d& A,
                        Eigen::Matrix<double, 4, 3>& B);

struct ZeroOrderHold {
  Eigen::Matrix4d Ad;
  Eigen::Matrix<double, 4, 3> Bd;
  // d[Ad Bd]/d theta_k for k < kModel, stacked: rows 4k..4k+3 are [dAd_k dBd_k] (4 x 7).
  Eigen::Matrix<double, 4 * kModel, 7> derivative;
};
// With `derivatives` false only Ad and Bd are filled.
ZeroOrderHold zero_order_hold(const Parameters& theta, double sample_time, bool derivatives);

class Amb1dofPredictor {
 public:
  // y: samples x 3 ([x, i1, i2]), u: samples x 2; both kept by reference. `clamped` (per
  // sample, or empty): the recorded u is not what the plant got there (a controller clamp
  // acted); the prediction error of the next sample, whose prediction used it, is left out of
  // the cost (the predictor still runs through it). Error when its size is not the samples'.
  Amb1dofPredictor(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u, double sample_time,
                   std::vector<bool> clamped = {});

  Eigen::Index samples() const { return y_.rows(); }
  // The samples whose prediction error is in the cost.
  Eigen::Index scored_samples() const { return scored_samples_; }

  // Sum over the scored samples of each output's squared prediction error; nullopt when the predictor
  // diverges (a non-finite error).
  std::optional<Eigen::Vector3d> squares(const Parameters& theta) const;

  // The prediction errors e[t] (samples x 3, [x, i1, i2]); nullopt when the predictor diverges.
  std::optional<Eigen::MatrixXd> errors(const Parameters& theta) const;

  // Rows of the weighted, column-scaled Jacobian and their targets, `block` samples at a time
  // (the last block may be shorter), sample-major with the outputs in order:
  //   jacobian(3 s + j, k) = weight_j scale_k d e_j[s] / d theta_k,   target(3 s + j) = -weight_j e_j[s],
  // zero rows for a sample left out of the cost.
  // Returns false (after the blocks so far) when the predictor diverges.
  using Rows = std::function<void(const Eigen::Ref<const Eigen::MatrixXd>& jacobian,
                                  const Eigen::Ref<const Eigen::VectorXd>& target)>;
  bool linearise(const Parameters& theta, const Eigen::Vector3d& weight, const Parameters& scale, Eigen::Index block,
                 const Rows& rows) const;

 private:
  // Runs the predictor, giving each sample's error to `each(t, e)`; false when it diverges.
  template <typename Each>
  bool predict(const Parameters& theta, Each&& each) const;
  bool scored(Eigen::Index t) const { return skipped_.empty() || !skipped_[std::size_t(t)]; }

  const Eigen::MatrixXd& y_;
  const Eigen::MatrixXd& u_;
  double sample_time_;
  std::vector<bool> skipped_;  // per sample: its prediction used a clamped input; empty: none
  Eigen::Index scored_samples_ = 0;
};

}  // namespace ambid::ident::pem
