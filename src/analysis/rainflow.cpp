#include "crane_twin/analysis/rainflow.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace crane_twin {

std::vector<double> turningPoints(const std::vector<double>& history) {
  std::vector<double> p;
  for (double x : history) {
    if (!std::isfinite(x)) throw std::invalid_argument("rainflow: a value is not finite");
    if (!p.empty() && x == p.back()) continue;  // a plateau counts once
    // The middle one of three on a monotone run is no turning point.
    if (p.size() >= 2 && (p.back() - p[p.size() - 2]) * (x - p.back()) > 0.0)
      p.back() = x;
    else
      p.push_back(x);
  }
  return p;
}

void RainflowCounter::closeCycles(std::vector<double>& s, std::vector<RainflowCycle>& closed) {
  while (s.size() >= 4) {
    const std::size_t n = s.size();
    const double d1 = std::abs(s[n - 3] - s[n - 4]);
    const double d2 = std::abs(s[n - 2] - s[n - 3]);
    const double d3 = std::abs(s[n - 1] - s[n - 2]);
    if (!(d2 <= d1 && d2 <= d3)) break;
    closed.push_back({d2, 0.5 * (s[n - 2] + s[n - 3]), 1.0});
    s.erase(s.end() - 3, s.end() - 1);
  }
}

RainflowCounter::RainflowCounter(RainflowState state)
    : stack_(std::move(state.turning_points)), pending_(std::move(state.pending)) {
  if (pending_.size() > 2) throw std::invalid_argument("rainflow: more than two pending values");
  for (const std::vector<double>* v : {&stack_, &pending_}) {
    for (double x : *v) {
      if (!std::isfinite(x)) throw std::invalid_argument("rainflow: a value is not finite");
    }
  }
}

void RainflowCounter::add(double x, std::vector<RainflowCycle>& closed) {
  if (!std::isfinite(x)) throw std::invalid_argument("rainflow: a value is not finite");
  if (pending_.empty()) {
    pending_.push_back(x);  // the history's first value is a turning point
    return;
  }
  if (x == pending_.back()) return;  // a plateau counts once
  if (pending_.size() == 2 && (pending_[1] - pending_[0]) * (x - pending_[1]) > 0.0) {
    pending_[1] = x;  // the run goes on: the last point moves with it
    return;
  }
  // The history turned: its last point is a turning point.
  stack_.push_back(pending_.back());
  closeCycles(stack_, closed);
  pending_ = {pending_.back(), x};
}

std::vector<RainflowCycle> RainflowCounter::finish() const {
  std::vector<RainflowCycle> cycles;
  std::vector<double> s = stack_;
  if (!pending_.empty()) {
    s.push_back(pending_.back());  // the last value is a turning point
    closeCycles(s, cycles);
  }
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {  // the residue: half cycles
    cycles.push_back({std::abs(s[i + 1] - s[i]), 0.5 * (s[i] + s[i + 1]), 0.5});
  }
  return cycles;
}

std::vector<RainflowCycle> rainflowCount(const std::vector<double>& history) {
  RainflowCounter counter;
  std::vector<RainflowCycle> cycles;
  for (double x : history) counter.add(x, cycles);
  const std::vector<RainflowCycle> rest = counter.finish();
  cycles.insert(cycles.end(), rest.begin(), rest.end());
  return cycles;
}

void SnCurve::check() const {
  if (!(std::isfinite(detail_category) && detail_category > 0.0)) {
    throw std::invalid_argument("detail category must be a stress range > 0 [MPa], got " +
                                std::to_string(detail_category));
  }
  if (!(std::isfinite(gamma_mf) && gamma_mf >= 1.0)) {
    throw std::invalid_argument("gamma_Mf must be a number >= 1, got " + std::to_string(gamma_mf));
  }
}

double SnCurve::cyclesToFailure(double range_mpa) const {
  if (!(range_mpa > 0.0)) return std::numeric_limits<double>::infinity();
  return 2e6 * std::pow(detail_category / (gamma_mf * range_mpa), 3);
}

double minerDamage(const std::vector<RainflowCycle>& cycles, const SnCurve& curve) {
  curve.check();
  double d = 0.0;
  for (const RainflowCycle& c : cycles) {
    const double n = curve.cyclesToFailure(c.range * 1e-6);
    if (std::isfinite(n)) d += c.count / n;
  }
  return d;
}

}  // namespace crane_twin
