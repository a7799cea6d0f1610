#include "identifier/time_domain/markov.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/linalg.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;

// Coefficient i of a list (zero matrix beyond its end).
const Eigen::MatrixXd* at(const std::vector<Eigen::MatrixXd>& v, Index i) {
  return i >= 0 && i < static_cast<Index>(v.size()) ? &v[static_cast<std::size_t>(i)] : nullptr;
}

void check_count(Index count, const char* who) {
  if (count < 0) throw Error(std::string(who) + ": Markov parameter count must be >= 0, got " + std::to_string(count));
}

void check_sequence(const MarkovSequence& s, Index needed, Index rows, Index cols, const std::string& what) {
  if (static_cast<Index>(s.size()) < needed)
    throw Error(what + ": needs " + std::to_string(needed) + " Markov parameters, got " + std::to_string(s.size()));
  for (Index k = 0; k < needed; ++k) {
    const Eigen::MatrixXd& m = s[static_cast<std::size_t>(k)];
    if (m.rows() != rows || m.cols() != cols)
      throw Error(what + ": Markov parameter " + std::to_string(k) + " is " + dims(m) + ", expected " +
                  std::to_string(rows) + "x" + std::to_string(cols));
  }
}

// c = a * b (convolution), index 0..count.
MarkovSequence convolve(const MarkovSequence& a, const MarkovSequence& b, Index count) {
  MarkovSequence c;
  for (Index k = 0; k <= count; ++k) {
    Eigen::MatrixXd s = Eigen::MatrixXd::Zero(a[0].rows(), b[0].cols());
    for (Index i = 0; i <= k; ++i) s += a[static_cast<std::size_t>(i)] * b[static_cast<std::size_t>(k - i)];
    c.push_back(s);
  }
  return c;
}

// x = (I - g)^-1 f  for Markov sequences with g_0 = 0:  x_k = f_k + sum_{i=1..k} g_i x_(k-i).
MarkovSequence feedback_solve(const MarkovSequence& g, const MarkovSequence& f, Index count) {
  MarkovSequence x;
  for (Index k = 0; k <= count; ++k) {
    Eigen::MatrixXd s = f[static_cast<std::size_t>(k)];
    for (Index i = 1; i <= k; ++i) s += g[static_cast<std::size_t>(i)] * x[static_cast<std::size_t>(k - i)];
    x.push_back(s);
  }
  return x;
}

// Largest singular value, from the largest eigenvalue of the small Gram matrix.
double spectral_norm(const Eigen::MatrixXd& m) {
  const Eigen::MatrixXd g =
      m.cols() <= m.rows() ? Eigen::MatrixXd(m.transpose() * m) : Eigen::MatrixXd(m * m.transpose());
  return std::sqrt(std::max(0.0, linalg::symmetric_eigenvalues(g).maxCoeff()));
}

}  // namespace

MarkovSequence markov_parameters(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                                 const Eigen::MatrixXd& D, Index count) {
  check_count(count, "markov_parameters");
  if (A.rows() != A.cols() || B.rows() != A.rows() || C.cols() != A.rows())
    throw Error("markov_parameters: inconsistent A " + dims(A) + ", B " + dims(B) + ", C " + dims(C));
  if (D.size() != 0 && (D.rows() != C.rows() || D.cols() != B.cols()))
    throw Error("markov_parameters: D is " + dims(D) + ", expected " + std::to_string(C.rows()) + "x" +
                std::to_string(B.cols()));
  MarkovSequence y;
  y.push_back(D.size() ? D : Eigen::MatrixXd::Zero(C.rows(), B.cols()));
  Eigen::MatrixXd AkB = B;
  for (Index k = 1; k <= count; ++k) {
    y.push_back(C * AkB);
    AkB = A * AkB;
  }
  return y;
}

MarkovSequence markov_parameters(const DiscreteSystem& sys, Index count) {
  sys.validate();
  return markov_parameters(sys.A, sys.B, sys.C, sys.D, count);
}

MarkovParameters markov_from_arx(const std::vector<Eigen::MatrixXd>& a, const std::vector<Eigen::MatrixXd>& b,
                                 Index count) {
  check_count(count, "markov_from_arx");
  if (a.empty() || b.empty()) throw Error("markov_from_arx: needs at least a_1 and b_0");
  const Index p = a[0].rows(), m = b[0].cols();
  for (const auto& ai : a)
    if (ai.rows() != p || ai.cols() != p)
      throw Error("markov_from_arx: a_i is " + dims(ai) + ", expected square " + std::to_string(p));
  for (const auto& bi : b)
    if (bi.rows() != p || bi.cols() != m)
      throw Error("markov_from_arx: b_i is " + dims(bi) + ", expected " + dims(b[0]));
  MarkovParameters out;
  out.system.push_back(b[0]);
  out.gain.push_back(Eigen::MatrixXd::Identity(p, p));
  for (Index k = 1; k <= count; ++k) {
    const Eigen::MatrixXd* bk = at(b, k);
    Eigen::MatrixXd y = bk ? *bk : Eigen::MatrixXd::Zero(p, m);
    Eigen::MatrixXd n = Eigen::MatrixXd::Zero(p, p);
    for (Index i = 1; i <= k; ++i) {
      const Eigen::MatrixXd* ai = at(a, i - 1);
      if (!ai) break;
      y += *ai * out.system[static_cast<std::size_t>(k - i)];
      n += *ai * out.gain[static_cast<std::size_t>(k - i)];
    }
    out.system.push_back(y);
    out.gain.push_back(n);
  }
  return out;
}

MarkovParameters markov_from_arx(const ArxModel& arx, Index count) {
  if (arx.targets != arx.outputs)
    throw Error("markov_from_arx: the ARX target is not its own output (" + std::to_string(arx.targets) + " targets, " +
                std::to_string(arx.outputs) + " outputs); use secondary_markov_from_arx");
  return markov_from_arx(arx.a, arx.b, count);
}

MarkovParameters secondary_markov_from_arx(const std::vector<Eigen::MatrixXd>& c, const std::vector<Eigen::MatrixXd>& d,
                                           const MarkovParameters& primary, Index count) {
  check_count(count, "secondary_markov_from_arx");
  if (c.empty() || d.empty()) throw Error("secondary_markov_from_arx: needs at least c_1 and d_0");
  if (primary.system.empty() || primary.gain.empty())
    throw Error("secondary_markov_from_arx: empty primary Markov parameters");
  const Index t = c[0].rows(), p = primary.gain[0].rows(), m = primary.system[0].cols();
  check_sequence(primary.system, count + 1, p, m, "secondary_markov_from_arx (primary system)");
  check_sequence(primary.gain, count + 1, p, p, "secondary_markov_from_arx (primary gain)");
  for (const auto& ci : c)
    if (ci.rows() != t || ci.cols() != p) throw Error("secondary_markov_from_arx: c_i is " + dims(ci));
  for (const auto& di : d)
    if (di.rows() != t || di.cols() != m) throw Error("secondary_markov_from_arx: d_i is " + dims(di));
  MarkovParameters out;
  out.system.push_back(d[0]);
  out.gain.push_back(Eigen::MatrixXd::Zero(t, p));
  for (Index k = 1; k <= count; ++k) {
    const Eigen::MatrixXd* dk = at(d, k);
    Eigen::MatrixXd z = dk ? *dk : Eigen::MatrixXd::Zero(t, m);
    Eigen::MatrixXd w = Eigen::MatrixXd::Zero(t, p);
    for (Index i = 1; i <= k; ++i) {
      const Eigen::MatrixXd* ci = at(c, i - 1);
      if (!ci) break;
      z += *ci * primary.system[static_cast<std::size_t>(k - i)];
      w += *ci * primary.gain[static_cast<std::size_t>(k - i)];
    }
    out.system.push_back(z);
    out.gain.push_back(w);
  }
  return out;
}

MarkovParameters secondary_markov_from_arx(const ArxModel& arx, const MarkovParameters& primary, Index count) {
  return secondary_markov_from_arx(arx.a, arx.b, primary, count);
}

MarkovParameters lee_open_loop_markov(const MarkovParameters& closed_loop, const MarkovSequence& controller) {
  if (closed_loop.system.empty() || closed_loop.gain.empty() || controller.empty())
    throw Error("lee_open_loop_markov: empty Markov sequence");
  const Index J = static_cast<Index>(closed_loop.system.size()) - 1;
  const Index p = closed_loop.system[0].rows(), m = closed_loop.system[0].cols();
  check_sequence(closed_loop.system, J + 1, p, m, "lee_open_loop_markov (closed-loop system)");
  check_sequence(closed_loop.gain, J + 1, p, p, "lee_open_loop_markov (closed-loop gain)");
  check_sequence(controller, J + 1, m, p, "lee_open_loop_markov (controller)");
  if (closed_loop.system[0].norm() != 0.0)
    throw Error("lee_open_loop_markov: the closed-loop Yc_0 must be zero (strictly proper plant), norm " +
                std::to_string(closed_loop.system[0].norm()));
  const auto& Yc = closed_loop.system;
  const auto& Nc = closed_loop.gain;
  const auto& Yd = controller;
  MarkovParameters out;
  out.system.push_back(Eigen::MatrixXd::Zero(p, m));
  out.gain.push_back(Eigen::MatrixXd::Identity(p, p));
  MarkovSequence alpha{Eigen::MatrixXd::Zero(p, p)};  // alpha_0 unused
  for (Index j = 1; j <= J; ++j) {
    // Y_j: the k = j term multiplies Yc_0 = 0, so alpha_1..alpha_(j-1) suffice.
    Eigen::MatrixXd y = Yc[static_cast<std::size_t>(j)];
    for (Index k = 1; k < j; ++k) y -= alpha[static_cast<std::size_t>(k)] * Yc[static_cast<std::size_t>(j - k)];
    out.system.push_back(y);
    Eigen::MatrixXd aj = Eigen::MatrixXd::Zero(p, p);
    for (Index i = 1; i <= j; ++i) aj += out.system[static_cast<std::size_t>(i)] * Yd[static_cast<std::size_t>(j - i)];
    alpha.push_back(aj);
    // N_j: keep the k = j term alpha_j Nc_0.
    Eigen::MatrixXd n = Nc[static_cast<std::size_t>(j)];
    for (Index k = 1; k <= j; ++k) n -= alpha[static_cast<std::size_t>(k)] * Nc[static_cast<std::size_t>(j - k)];
    out.gain.push_back(n);
  }
  return out;
}

ControllerMarkov controller_markov(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& C,
                                   const Eigen::MatrixXd& D, Index plant_inputs, Index count) {
  check_count(count, "controller_markov");
  const Index l = A.rows();
  if (A.cols() != l || B.rows() != l || C.cols() != l || D.rows() != C.rows() || D.cols() != B.cols())
    throw Error("controller_markov: inconsistent controller A " + dims(A) + ", B " + dims(B) + ", C " + dims(C) +
                ", D " + dims(D));
  if (plant_inputs < 0 || plant_inputs > B.cols())
    throw Error("controller_markov: " + std::to_string(plant_inputs) + " plant inputs but the controller has " +
                std::to_string(B.cols()) + " inputs");
  if (C.rows() != plant_inputs)
    throw Error("controller_markov: the controller has " + std::to_string(C.rows()) +
                " outputs, expected one per plant input (" + std::to_string(plant_inputs) + ")");
  for (Index j = 0; j < plant_inputs; ++j)
    if (D.col(j).norm() != 0.0)
      throw Error("controller_markov: the controller has direct feedthrough from plant input " + std::to_string(j + 1) +
                  " (D column " + std::to_string(j + 1) + " is non-zero): an algebraic loop through u is refused");
  const Index py = B.cols() - plant_inputs;
  const MarkovSequence all = markov_parameters(A, B, C, D, count);
  ControllerMarkov out;
  for (const auto& g : all) {
    out.from_u.push_back(g.leftCols(plant_inputs));
    out.from_y.push_back(g.rightCols(py));
  }
  return out;
}

MarkovParameters open_loop_markov(const MarkovParameters& closed_loop, const ControllerMarkov& controller) {
  if (closed_loop.system.empty() || closed_loop.gain.empty() || controller.from_u.empty() || controller.from_y.empty())
    throw Error("open_loop_markov: empty Markov sequence");
  const Index J = static_cast<Index>(closed_loop.system.size()) - 1;
  const Index p = closed_loop.system[0].rows(), m = closed_loop.system[0].cols();
  check_sequence(closed_loop.system, J + 1, p, m, "open_loop_markov (closed-loop system)");
  check_sequence(closed_loop.gain, J + 1, p, p, "open_loop_markov (closed-loop gain)");
  check_sequence(controller.from_u, J + 1, m, m, "open_loop_markov (controller from u)");
  check_sequence(controller.from_y, J + 1, m, p, "open_loop_markov (controller from y)");
  if (closed_loop.system[0].norm() != 0.0)
    throw Error("open_loop_markov: the closed-loop Yc_0 must be zero (strictly proper plant), norm " +
                std::to_string(closed_loop.system[0].norm()));
  if (controller.from_u[0].norm() != 0.0)
    throw Error("open_loop_markov: the controller has direct feedthrough from u (Gu_0 non-zero)");

  // Uc = (I - Gu)^-1 (I + Gy Yc), Unc = (I - Gu)^-1 Gy Nc.
  MarkovSequence f = convolve(controller.from_y, closed_loop.system, J);
  f[0] += Eigen::MatrixXd::Identity(m, m);
  const MarkovSequence Uc = feedback_solve(controller.from_u, f, J);
  const MarkovSequence Unc = feedback_solve(controller.from_u, convolve(controller.from_y, closed_loop.gain, J), J);

  MarkovParameters out;
  out.system.push_back(Eigen::MatrixXd::Zero(p, m));
  out.gain.push_back(Eigen::MatrixXd::Identity(p, p));
  for (Index j = 1; j <= J; ++j) {
    Eigen::MatrixXd y = closed_loop.system[static_cast<std::size_t>(j)];
    for (Index i = 1; i < j; ++i) y -= out.system[static_cast<std::size_t>(i)] * Uc[static_cast<std::size_t>(j - i)];
    out.system.push_back(y);
    Eigen::MatrixXd n = closed_loop.gain[static_cast<std::size_t>(j)];
    for (Index i = 1; i <= j; ++i) n -= out.system[static_cast<std::size_t>(i)] * Unc[static_cast<std::size_t>(j - i)];
    out.gain.push_back(n);
  }
  return out;
}

std::vector<double> markov_errors_percent(const MarkovSequence& truth, const MarkovSequence& estimate, Index first,
                                          Index count) {
  if (first < 0 || count < 1 || static_cast<Index>(truth.size()) < first + count ||
      static_cast<Index>(estimate.size()) < first + count)
    throw Error("markov_errors_percent: sequences of " + std::to_string(truth.size()) + " and " +
                std::to_string(estimate.size()) + " do not cover indices " + std::to_string(first) + ".." +
                std::to_string(first + count - 1));
  std::vector<double> e;
  for (Index k = first; k < first + count; ++k) {
    const Eigen::MatrixXd& t = truth[static_cast<std::size_t>(k)];
    const Eigen::MatrixXd& h = estimate[static_cast<std::size_t>(k)];
    if (t.rows() != h.rows() || t.cols() != h.cols())
      throw Error("markov_errors_percent: Markov parameter " + std::to_string(k) + " is " + dims(h) + ", truth " +
                  dims(t));
    const double nt = spectral_norm(t);
    if (!(nt > 0.0)) throw Error("markov_errors_percent: true Markov parameter " + std::to_string(k) + " is zero");
    const Eigen::MatrixXd diff = t - h;
    e.push_back(100.0 * spectral_norm(diff) / nt);
  }
  return e;
}

}  // namespace ambid::ident
