#include "sweep/overrides.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "core/names.hpp"

namespace invasim::sweep {

namespace {

std::vector<std::string> declared_names(const SweepSpec& spec) {
  std::vector<std::string> names;
  for (const auto& d : spec.declared) names.push_back(d.name);
  return names;
}

// Sets fixed parameter `name` (and the preparation's, unless prep.set gives it); an axis of
// that parameter (product, seeds or a zip group's list) is dropped: the value replaces it.
void set_fixed(SweepSpec& spec, const std::string& name, const Json& value) {
  std::erase_if(spec.product, [&](const Axis& a) { return a.first == name; });
  for (auto& group : spec.zips)
    std::erase_if(group, [&](const Axis& a) { return a.first == name; });
  std::erase_if(spec.zips, [](const std::vector<Axis>& g) { return g.empty(); });
  spec.fixed[name] = value;
  if (spec.has_prep && !spec.prep_own.contains(name)) spec.prep_set[name] = value;
}

// The state-point value of `text` for the declared parameter `p` (an integer-looking number
// of a number parameter stays an integer, as in a Lua spec); InputError naming `where`.
Json override_value(const Param& p, const std::string& text, const std::string& where) {
  ParamValue parsed;
  try {
    parsed = parse_value(p.type, p.name, text);
  } catch (const InputError& e) {
    fail_input(where, ": ", e.what());
  }
  if (const std::string why = value_violation(p, parsed); !why.empty())
    fail_input(where, ": parameter '", p.name, "' ", why);
  if (p.type == ParamType::kNumber) {
    const double d = std::get<double>(parsed);
    const bool integral_text = text.find_first_of(".eEnN") == std::string::npos;
    if (integral_text && std::floor(d) == d && std::fabs(d) < 9.0e15)
      return Json(static_cast<std::int64_t>(d));
    return Json(d);
  }
  return to_json(parsed);
}

}  // namespace

void apply_spec_overrides(SweepSpec& spec, const SpecOverrides& o) {
  std::optional<int> take = o.take;
  if (o.tiny) {
    if (!spec.has_tiny)
      fail_input("sweep init --tiny: ", spec.path,
                 " has no tiny = { set = { ... }, take = N } (the CI size); give --set and "
                 "--take instead");
    for (const auto& item : spec.tiny_set.items()) set_fixed(spec, item.key(), item.value());
    if (!take) take = spec.tiny_take;
  }
  std::vector<std::string> seen;
  for (const auto& s : o.set) {
    const std::string where = "--set " + s.key + "=" + s.text;
    const Param* p = find_param(spec.declared, s.key);
    if (!p)
      fail_input(where, ": '", s.key, "' is not a parameter of ", spec.protocol,
                 did_you_mean(s.key, declared_names(spec)),
                 "; declared parameters: ", join_names(declared_names(spec)));
    if (std::find(seen.begin(), seen.end(), s.key) != seen.end())
      fail_input(where, ": '", s.key, "' is given twice");
    seen.push_back(s.key);
    set_fixed(spec, s.key, override_value(*p, s.text, where));
  }
  if (take) {
    if (*take < 1) fail_input("--take ", *take, ": expects an integer >= 1");
    for (auto& [name, values] : spec.product)
      values.resize(std::min<std::size_t>(values.size(), name == "seed" ? 1 : *take));
    for (auto& group : spec.zips)
      for (auto& [name, values] : group) values.resize(std::min<std::size_t>(values.size(), *take));
  }
}

}  // namespace invasim::sweep
