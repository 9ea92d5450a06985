#include "checkpoint/correlator_sections.hpp"

namespace invasim {

void write_correlator(CheckpointWriter& out, const TimeCorrelator& c, const std::string& prefix) {
  const CorrelatorState s = c.state();
  out.put_u64(prefix + ".samples", s.samples);
  out.put_f64(prefix + ".last_time", s.last_time);
  out.put_f64s(prefix + ".velocity", s.velocity);
  out.put_f64s(prefix + ".orientation", s.orientation);
  out.put_f64s(prefix + ".position", s.position);
  out.put_u64s(prefix + ".origins", s.origins);
  out.put_f64s(prefix + ".sums", s.sums);
  // Only once cells divided or died (TimeCorrelator::sites_changed).
  if (!s.group.empty()) out.put_i32s(prefix + ".group", s.group);
  if (!s.site_pairs.empty()) out.put_f64s(prefix + ".site_pairs", s.site_pairs);
}

CorrelatorState read_correlator_state(const CheckpointReader& in, const std::string& prefix) {
  CorrelatorState s;
  s.samples = in.get_u64(prefix + ".samples");
  s.last_time = in.get_f64(prefix + ".last_time");
  s.velocity = in.get_f64s(prefix + ".velocity");
  s.orientation = in.get_f64s(prefix + ".orientation");
  s.position = in.get_f64s(prefix + ".position");
  s.origins = in.get_u64s(prefix + ".origins");
  s.sums = in.get_f64s(prefix + ".sums");
  if (in.has(prefix + ".group")) s.group = in.get_i32s(prefix + ".group");
  if (in.has(prefix + ".site_pairs")) s.site_pairs = in.get_f64s(prefix + ".site_pairs");
  return s;
}

void read_correlator(const CheckpointReader& in, TimeCorrelator& c, const std::string& prefix) {
  c.restore(read_correlator_state(in, prefix));
}

}  // namespace invasim
