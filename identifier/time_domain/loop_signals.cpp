#include "identifier/time_domain/loop_signals.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace ambid::ident {
namespace {

using Index = Eigen::Index;

Index column_of(const std::vector<std::string>& names, const std::string& name, const std::string& what,
                const std::string& who) {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) throw Error(who + ": signal '" + name + "' missing from " + what);
  return static_cast<Index>(it - names.begin());
}

Eigen::MatrixXd columns(const Eigen::MatrixXd& all, const std::vector<std::string>& all_names,
                        const std::vector<std::string>& names, const std::string& what, const std::string& who) {
  Eigen::MatrixXd out(all.rows(), static_cast<Index>(names.size()));
  for (std::size_t j = 0; j < names.size(); ++j)
    out.col(static_cast<Index>(j)) = all.col(column_of(all_names, names[j], what, who));
  return out;
}

}  // namespace

LoopSignals loop_signals(const Experiment& e, const std::vector<std::string>& y_names,
                         const std::vector<std::string>& u_names, const std::string& who) {
  LoopSignals s;
  s.y_names = y_names;
  s.u_names = u_names;
  s.y = columns(e.y_deviation(), e.y_names, y_names, "signals.y", who);
  s.u = columns(e.u_deviation(), e.u_names, u_names, "signals.u", who);
  s.r = Eigen::MatrixXd::Zero(e.samples(), s.u.cols());
  if (e.has_excitation()) {
    const std::vector<std::string>& targets = e.controller ? e.controller->outputs : e.u_names;
    const std::string of = e.controller ? "controller outputs" : "plant inputs (no controller given)";
    const Eigen::MatrixXd rdev = e.r_deviation();
    if (rdev.cols() != static_cast<Index>(targets.size()))
      throw Error(who + ": " + std::to_string(rdev.cols()) + " r signals for " + std::to_string(targets.size()) + " " +
                  of + "; r is added to them one by one, in order");
    for (Index j = 0; j < rdev.cols(); ++j) {
      const std::string& target = targets[static_cast<std::size_t>(j)];
      // An excited plant input that is not among the chosen ones does not enter the model.
      const auto it = std::find(u_names.begin(), u_names.end(), target);
      if (it != u_names.end()) s.r.col(static_cast<Index>(it - u_names.begin())) += rdev.col(j);
    }
  }
  s.uf = s.u - s.r;
  return s;
}

LoopSignals loop_signals(const Experiment& e, const std::string& who) {
  return loop_signals(e, e.y_names, e.u_names, who);
}

}  // namespace ambid::ident
