#include "checkpoint/dynamics_sections.hpp"

#include "checkpoint/state_checkpoint.hpp"

namespace invasim {

void write_ramp(CheckpointWriter& out, const std::optional<Ramp>& ramp, const std::string& prefix) {
  if (!ramp) return;
  out.put_f64(prefix + ".from", ramp->from);
  out.put_f64(prefix + ".to", ramp->to);
  out.put_u64(prefix + ".steps", ramp->steps);
  if (ramp->start) out.put_u64(prefix + ".start", *ramp->start);
}

std::optional<Ramp> read_ramp(const CheckpointReader& in, const std::string& prefix) {
  if (!in.has(prefix + ".from")) return std::nullopt;
  Ramp r;
  r.from = in.get_f64(prefix + ".from");
  r.to = in.get_f64(prefix + ".to");
  r.steps = in.get_u64(prefix + ".steps");
  if (in.has(prefix + ".start")) r.start = in.get_u64(prefix + ".start");
  if (r.steps == 0) in.fail("section ", prefix, ".steps: a ramp needs steps >= 1");
  return r;
}

void write_method(CheckpointWriter& out, const Method& m, const std::string& prefix) {
  const MethodParams& p = m.params();
  out.put_f64(prefix + ".gamma", p.gamma);
  out.put_f64(prefix + ".kT", p.kT);
  out.put_f64(prefix + ".f0", p.f0);
  out.put_f64(prefix + ".tau_p", p.tau_p);
  out.put_u64(prefix + ".sites", m.group().size());
  if (m.group_changed()) out.put_i32s(prefix + ".group", m.group());
  write_ramp(out, m.kT_ramp(), prefix + ".kT_ramp");
  write_ramp(out, m.f0_ramp(), prefix + ".f0_ramp");
}

namespace {

// The stored group of a method whose cells changed (Proliferation), or none; refuses a
// stored size that does not fit method m.
std::optional<std::vector<int>> stored_group(const CheckpointReader& in, const Method& m,
                                             const std::string& prefix) {
  const std::uint64_t sites = in.get_u64(prefix + ".sites");
  if (in.has(prefix + ".group")) {
    std::vector<int> group = in.get_i32s(prefix + ".group");
    if (group.size() != sites)
      in.fail("section ", prefix, ".group holds ", group.size(), " sites, not ", sites);
    return group;
  }
  if (sites != m.group().size())
    in.fail(prefix, " moves ", sites, " sites in the checkpoint but ", m.group().size(),
            " here (not the same protocol?)");
  return std::nullopt;
}

std::string method_prefix(const std::string& prefix, std::size_t k) {
  return prefix + ".method" + std::to_string(k + 1);
}

}  // namespace

void read_method(const CheckpointReader& in, Method& m, const std::string& prefix) {
  // A group that cells joined or left (Proliferation) is stored: the restored run takes it.
  if (auto group = stored_group(in, m, prefix)) m.set_group(std::move(*group));
  MethodParams p{in.get_f64(prefix + ".gamma"), in.get_f64(prefix + ".kT"),
                 in.get_f64(prefix + ".f0"), in.get_f64(prefix + ".tau_p")};
  p.validate();
  m.set_kT_ramp(read_ramp(in, prefix + ".kT_ramp"));
  m.set_f0_ramp(read_ramp(in, prefix + ".f0_ramp"));
  m.params() = p;  // set_*_ramp resets the value to the ramp's start
}

void write_dynamics(CheckpointWriter& out, const Dynamics& d, const std::string& prefix) {
  out.put_f64(prefix + ".dt", d.dt());
  out.put_u64(prefix + ".methods", d.methods().size());
  for (std::size_t k = 0; k < d.methods().size(); ++k)
    write_method(out, *d.methods()[k], prefix + ".method" + std::to_string(k + 1));
  if (const auto wall = d.pressure_wall()) {
    write_pressure_wall(out, *wall, prefix + ".pressure_wall");
    write_ramp(out, wall->pressure_ramp, prefix + ".pressure_wall.ramp");
  }
}

void check_dynamics(const CheckpointReader& in, const Dynamics& d, const std::string& prefix) {
  const std::uint64_t n = in.get_u64(prefix + ".methods");
  if (n != d.methods().size())
    in.fail("its Dynamics has ", n, " methods, this one ", d.methods().size(),
            " (not the same protocol?)");
  const bool has_wall = in.has(prefix + ".pressure_wall.pressure");
  if (has_wall != bool(d.pressure_wall()))
    in.fail("its Dynamics ", has_wall ? "has a pressure wall, this one has none"
                                      : "has no pressure wall, this one has one");
  for (std::size_t k = 0; k < n; ++k) stored_group(in, *d.methods()[k], method_prefix(prefix, k));
}

void read_dynamics(const CheckpointReader& in, Dynamics& d, const std::string& prefix) {
  check_dynamics(in, d, prefix);  // before the first method changes
  d.set_dt(in.get_f64(prefix + ".dt"));
  for (std::size_t k = 0; k < d.methods().size(); ++k)
    read_method(in, *d.methods()[k], method_prefix(prefix, k));
  if (const auto wall = d.pressure_wall()) {
    read_pressure_wall(in, *wall, prefix + ".pressure_wall");
    wall->pressure_ramp = read_ramp(in, prefix + ".pressure_wall.ramp");
  }
}

}  // namespace invasim
