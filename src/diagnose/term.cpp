#include "abbe/diagnose/term.hpp"

#include "abbe/diagnose/effect_catalogue.hpp"

namespace abbe::diagnose {

bool same_effect(const Term& a, const Term& b) {
  return a.kind == b.kind && a.axis == b.axis && a.direction == b.direction &&
         a.with_axis == b.with_axis && a.set == b.set;
}

int Term::columns() const {
  const EffectDescriptor& d = effect_descriptor(kind);
  return d.columns ? d.columns(*this) : 1;
}

void Term::basis(const PointContext& pc,
                 Eigen::Ref<Eigen::Matrix<double, 3, Eigen::Dynamic>> out) const {
  out.setZero();
  effect_descriptor(kind).basis(*this, pc, out);
}

Eigen::Vector3d Term::evaluate(const PointContext& pc) const {
  const int n = columns();
  Eigen::Matrix<double, 3, Eigen::Dynamic> g(3, n);
  basis(pc, g);
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  for (int c = 0; c < n && c < static_cast<int>(coef.size()); ++c)
    e += coef[static_cast<std::size_t>(c)] * g.col(c);
  return e;
}

Term position_term(int axis, int direction) {
  Term t;
  t.kind = axis == direction ? TermKind::scale : TermKind::squareness;
  t.axis = axis;
  t.direction = direction;
  return t;
}

std::string Term::label() const { return effect_descriptor(kind).label(*this); }

std::string Term::description() const { return effect_descriptor(kind).description(*this); }

std::vector<std::pair<std::string, double>> Term::params() const {
  return effect_descriptor(kind).params(*this);
}

std::vector<std::pair<std::string, double>> Term::param_stderr() const {
  const EffectDescriptor& d = effect_descriptor(kind);
  if (d.param_stderr) return d.param_stderr(*this);
  const auto p = d.params(*this);
  std::vector<std::pair<std::string, double>> out;
  if (!p.empty()) out.emplace_back(p[0].first, stderr_.empty() ? 0.0 : stderr_[0]);
  return out;
}

}  // namespace abbe::diagnose
