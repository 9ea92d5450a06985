#include "forces/contact_pairs.hpp"

#include <algorithm>
#include <atomic>

#include "forces/contact_force.hpp"

namespace invasim {

PairCoefficients pair_coefficients(const ContactParams& p, SiteKind ka, SiteKind kb, double da,
                                   double db) {
  const bool cc = ka == SiteKind::kCancer && kb == SiteKind::kCancer;
  const bool cv = ka != kb;
  const double eps = cc ? p.eps_cc : (cv ? p.eps_cv : p.eps_vv);
  return pair_coefficients(0.5 * (da + db), eps, p.pair_alpha(cv), p.pair_beta(cc, cv));
}

bool PairTable::build(const Sites& s, const ContactParams& p) {
  static std::atomic<std::uint64_t> builds{0};
  version_ = ++builds;
  const std::size_t n = s.size();
  std::vector<SiteKind> kinds;
  std::vector<double> diams;
  cls_.resize(n);
  kind_.resize(n);
  for (std::size_t i = 0; i < n; ++i) kind_[i] = int(s.kind[i]);
  usable_ = false;
  for (std::size_t i = 0; i < n; ++i) {
    int c = 0;
    while (c < int(kinds.size()) && !(kinds[c] == s.kind[i] && diams[c] == s.diameter[i])) ++c;
    if (c == int(kinds.size())) {
      if (c == kMaxClasses) return false;
      kinds.push_back(s.kind[i]);
      diams.push_back(s.diameter[i]);
    }
    cls_[i] = c;
  }
  n_classes_ = int(kinds.size());
  const std::size_t nt = std::size_t(n_classes_) * n_classes_;
  const std::size_t padded = std::max<std::size_t>(nt, kLookupEntries);
  for (auto* v : {&rc2, &rb2, &tiny2, &c_rep, &d_rep, &r0_rep, &c_att, &d_att, &r0_att, &e0})
    v->assign(padded, 0.0);
  for (int a = 0; a < n_classes_; ++a)
    for (int b = 0; b < n_classes_; ++b) {
      const PairCoefficients k = pair_coefficients(p, kinds[a], kinds[b], diams[a], diams[b]);
      const std::size_t t = std::size_t(a) * n_classes_ + b;
      rc2[t] = k.rc2;
      rb2[t] = k.rb2;
      tiny2[t] = k.tiny2;
      c_rep[t] = k.c_rep;
      d_rep[t] = k.d_rep;
      r0_rep[t] = k.r0_rep;
      c_att[t] = k.c_att;
      d_att[t] = k.d_att;
      r0_att[t] = k.r0_att;
      e0[t] = k.e0;
    }
  usable_ = true;
  return true;
}

}  // namespace invasim
