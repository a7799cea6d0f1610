#include "identifier/families/amb1dof_predictor.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident::pem {
namespace {

using Index = Eigen::Index;

// Where theta_k (k < kModel) enters M = [Ac Bc w; 0 0] (7 x 7), and with which sign
// (amb1dof_structure.hpp): v1..v9, then w of the x'', i1', i2' rows.
struct Entry {
  int row, col;
  double sign;
};
constexpr std::array<Entry, kModel> kEntries = {{{1, 0, 1.0},
                                                 {1, 2, 1.0},
                                                 {1, 3, -1.0},
                                                 {2, 1, -1.0},
                                                 {2, 2, -1.0},
                                                 {3, 1, 1.0},
                                                 {3, 3, -1.0},
                                                 {2, 4, 1.0},
                                                 {3, 5, 1.0},
                                                 {1, 6, 1.0},
                                                 {2, 6, 1.0},
                                                 {3, 6, 1.0}}};

// [Ac Bc w; 0 0] for the first kModel entries of `model` (v then w).
Eigen::Matrix<double, 7, 7> generator(const double* model) {
  Eigen::Matrix<double, 7, 7> M = Eigen::Matrix<double, 7, 7>::Zero();
  M(0, 1) = 1.0;
  for (int k = 0; k < kModel; ++k) M(kEntries[k].row, kEntries[k].col) += kEntries[k].sign * model[k];
  return M;
}

}  // namespace

Parameters pack(const Vector9& v, const Eigen::Vector3d& w, const Eigen::Vector4d& x0, const Gain& K) {
  Parameters theta;
  theta.head<9>() = v;
  theta.segment<3>(9) = w;
  theta.segment<4>(kInitial) = x0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) theta(kGain + 3 * i + j) = K(i, j);
  return theta;
}

Gain gain_of(const Parameters& theta) {
  Gain K;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) K(i, j) = theta(kGain + 3 * i + j);
  return K;
}

void structure_matrices(const Eigen::Ref<const Vector9>& v, const Eigen::Vector3d& w, Eigen::Matrix4d& A,
                        Eigen::Matrix<double, 4, 3>& B) {
  double model[kModel];
  for (int k = 0; k < 9; ++k) model[k] = v(k);
  for (int k = 0; k < 3; ++k) model[9 + k] = w(k);
  const Eigen::Matrix<double, 7, 7> M = generator(model);
  A = M.topLeftCorner<4, 4>();
  B = M.block<4, 3>(0, 4);
}

ZeroOrderHold zero_order_hold(const Parameters& theta, double sample_time, bool derivatives) {
  const Eigen::MatrixXd M = generator(theta.data()) * sample_time;
  ZeroOrderHold out;
  out.derivative.setZero();
  if (!derivatives) {
    const Eigen::MatrixXd E = linalg::matrix_exp(M);
    out.Ad = E.topLeftCorner(4, 4);
    out.Bd = E.block(0, 4, 4, 3);
    return out;
  }
  // expm([M dM; 0 M]) = [E L(M, dM); 0 E]: L is the Frechet derivative of expm at M along dM.
  Eigen::MatrixXd block = Eigen::MatrixXd::Zero(14, 14);
  block.topLeftCorner(7, 7) = M;
  block.bottomRightCorner(7, 7) = M;
  for (int k = 0; k < kModel; ++k) {
    block.topRightCorner(7, 7).setZero();
    block(kEntries[k].row, 7 + kEntries[k].col) = kEntries[k].sign * sample_time;
    const Eigen::MatrixXd E = linalg::matrix_exp(block);
    if (k == 0) {
      out.Ad = E.topLeftCorner(4, 4);
      out.Bd = E.block(0, 4, 4, 3);
    }
    out.derivative.block<4, 7>(4 * k, 0) = E.block(0, 7, 4, 7);
  }
  return out;
}

Amb1dofPredictor::Amb1dofPredictor(const Eigen::MatrixXd& y, const Eigen::MatrixXd& u, double sample_time,
                                   std::vector<bool> clamped)
    : y_(y), u_(u), sample_time_(sample_time), scored_samples_(y.rows()) {
  if (clamped.empty()) return;
  if (std::ssize(clamped) != y.rows())
    throw Error("amb1dof predictor: the clamp mask has " + std::to_string(clamped.size()) + " entries for " +
                std::to_string(y.rows()) + " samples");
  skipped_.assign(clamped.size(), false);
  for (std::size_t t = 1; t < clamped.size(); ++t) skipped_[t] = clamped[t - 1];
  scored_samples_ -= std::count(skipped_.begin(), skipped_.end(), true);
}

template <typename Each>
bool Amb1dofPredictor::predict(const Parameters& theta, Each&& each) const {
  const ZeroOrderHold zoh = zero_order_hold(theta, sample_time_, false);
  const Gain K = gain_of(theta);
  Eigen::Vector4d x = theta.segment<4>(kInitial);
  Eigen::Vector3d e;
  for (Index t = 0; t < samples(); ++t) {
    e << y_(t, 0) - x(0), y_(t, 1) - x(2), y_(t, 2) - x(3);
    each(t, e);
    x = zoh.Ad * x + zoh.Bd.col(0) * u_(t, 0) + zoh.Bd.col(1) * u_(t, 1) + zoh.Bd.col(2) + K * e;
    if (t % 1024 == 0 && !x.allFinite()) return false;  // diverged: stop early
  }
  return x.allFinite();
}

std::optional<Eigen::Vector3d> Amb1dofPredictor::squares(const Parameters& theta) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  if (!predict(theta,
               [&](Index t, const Eigen::Vector3d& e) {
                 if (scored(t)) sum += e.cwiseAbs2();
               }) ||
      !sum.allFinite())
    return std::nullopt;
  return sum;
}

std::optional<Eigen::MatrixXd> Amb1dofPredictor::errors(const Parameters& theta) const {
  Eigen::MatrixXd out(samples(), 3);
  if (!predict(theta, [&](Index t, const Eigen::Vector3d& e) { out.row(t) = e.transpose(); }) || !out.allFinite())
    return std::nullopt;
  return out;
}

bool Amb1dofPredictor::linearise(const Parameters& theta, const Eigen::Vector3d& weight, const Parameters& scale,
                                 Index block, const Rows& rows) const {
  using Sensitivity = Eigen::Matrix<double, 4, kParameters>;
  const ZeroOrderHold zoh = zero_order_hold(theta, sample_time_, true);
  const Gain K = gain_of(theta);
  Eigen::Matrix4d C_K = Eigen::Matrix4d::Zero();  // K C
  for (int j = 0; j < 3; ++j) C_K.col(kMeasured[std::size_t(j)]) = K.col(j);
  const Eigen::Matrix4d F = zoh.Ad - C_K;
  Eigen::Vector4d x = theta.segment<4>(kInitial);
  Sensitivity psi = Sensitivity::Zero(), next;
  psi.block<4, 4>(0, kInitial).setIdentity();
  Eigen::Matrix<double, 7, 1> z;  // [x^; u1; u2; 1]
  Eigen::Matrix<double, 4 * kModel, 1> model_terms;
  Eigen::Vector3d e;
  Eigen::MatrixXd jacobian(3 * block, kParameters);
  Eigen::VectorXd target(3 * block);
  const Eigen::RowVectorXd row_scale = scale.transpose();
  Index filled = 0;
  for (Index t = 0; t < samples(); ++t) {
    e << y_(t, 0) - x(0), y_(t, 1) - x(2), y_(t, 2) - x(3);
    const double w = scored(t) ? 1.0 : 0.0;  // a row of zeros leaves the sample out
    for (int j = 0; j < 3; ++j) {
      jacobian.row(3 * filled + j) = (-w * weight(j)) * psi.row(kMeasured[std::size_t(j)]).cwiseProduct(row_scale);
      target(3 * filled + j) = -w * weight(j) * e(j);
    }
    if (++filled == block || t + 1 == samples()) {
      if (!target.head(3 * filled).allFinite()) return false;
      rows(jacobian.topRows(3 * filled), target.head(3 * filled));
      filled = 0;
    }
    z << x, u_(t, 0), u_(t, 1), 1.0;
    model_terms.noalias() = zoh.derivative * z;
    next.noalias() = F * psi;
    next.leftCols<kModel>() += Eigen::Map<const Eigen::Matrix<double, 4, kModel>>(model_terms.data());
    for (int i = 0; i < 4; ++i) next.block<1, 3>(i, kGain + 3 * i) += e.transpose();
    psi = next;
    x = zoh.Ad * x + zoh.Bd * z.tail<3>() + K * e;
  }
  return true;
}

}  // namespace ambid::ident::pem
