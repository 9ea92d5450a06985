#include "app/options.hpp"

#include "core/names.hpp"
#include "io/text_format.hpp"

namespace invasim::app {

namespace {

// As the user writes it: -o for --output.
std::string shown(const std::string& name) {
  return name == "--output" ? "-o" : name;
}

// "A, B and C".
std::string listing(const OptionSpec& spec) {
  std::vector<std::string> all;
  for (const auto& n : spec.with_value) all.push_back(shown(n));
  for (const auto& n : spec.flags) all.push_back(n);
  std::string out;
  for (std::size_t i = 0; i < all.size(); ++i)
    out += (i == 0 ? "" : i + 1 == all.size() ? " and " : ", ") + all[i];
  return out;
}

}  // namespace

std::optional<std::string> ParsedOptions::value(const std::string& name) const {
  const auto it = values.find(name);
  if (it == values.end()) return std::nullopt;
  return it->second.front();
}

ParsedOptions parse_options(const std::vector<std::string>& args, const OptionSpec& spec) {
  ParsedOptions p;
  const auto usage = [&spec](const std::string& text) { throw UsageError(spec.prefix + text); };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "-h" || arg == "--help") p.help = true;
    if (arg == "--version") p.version = true;
    if (p.help || p.version) return p;
    if (arg == "--") usage("unexpected '--'");
    if (arg.size() < 2 || arg[0] != '-') {
      p.positional.push_back(arg);
      continue;
    }
    std::string name = arg == "-o" ? "--output" : arg, value;
    bool has_value = false;
    if (const auto eq = name.find('='); eq != std::string::npos && name.rfind("--", 0) == 0) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      has_value = true;
    }
    if (contains(spec.flags, name)) {
      if (has_value) usage(name + " takes no value");
      p.flags.insert(name);
      continue;
    }
    if (const auto it = spec.refused.find(name); it != spec.refused.end()) usage(it->second);
    if (!contains(spec.with_value, name)) {
      const std::string all = listing(spec);
      usage("unknown option '" + name + "' (" +
            (all.empty() ? spec.who + " takes none" : spec.who + " takes " + all) + ")");
    }
    if (!has_value) {
      if (i + 1 >= args.size()) usage(shown(name) + " needs a value");
      value = args[++i];
    }
    auto& given = p.values[name];
    if (!given.empty() && !contains(spec.repeatable, name))
      usage(shown(name) + " given twice ('" + given.front() + "' and '" + value + "')");
    given.push_back(value);
  }
  return p;
}

int positive_option(const std::string& name, const std::string& text, int max) {
  const auto value = text::parse<int>(text);
  if (!value || *value < 1 || *value > max)
    throw UsageError(name + " expects an integer in [1, " + std::to_string(max) + "], got '" +
                     text + "'");
  return *value;
}

}  // namespace invasim::app
