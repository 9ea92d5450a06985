#pragma once
// The words of one `invasim` command after its name: positional words and options written
// `--name VALUE` or `--name=VALUE` (`-o` is `--output`), checked against the options the
// command takes. run, params, render and every sweep verb read their words through
// parse_options, so they share one syntax and one set of messages ("unknown option '--bogus'
// (it takes --set and --seed)", "--out given twice ('a' and 'b')", "-o needs a value").
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "app/cli.hpp"

namespace invasim::app {

struct OptionSpec {
  std::vector<std::string> with_value;  // --name VALUE
  std::vector<std::string> flags;       // --name alone
  std::vector<std::string> repeatable;  // options that may be given more than once (--set)
  std::string prefix;                   // before every message: "invasim sweep run: "
  std::string who = "it";               // "unknown option ... (<who> takes ...)"
  // Options the command does not take but a user may try, with the message that says what to
  // write instead (render's --out: "give it with -o FILE.svg").
  std::map<std::string, std::string> refused = {};
};

struct ParsedOptions {
  std::vector<std::string> positional;
  std::map<std::string, std::vector<std::string>> values;  // in command-line order
  std::set<std::string> flags;
  bool help = false;     // -h or --help
  bool version = false;  // --version

  // The value of an option given once (nullopt when absent).
  std::optional<std::string> value(const std::string& name) const;
  bool flag(const std::string& name) const { return flags.count(name) > 0; }
};

// Splits args by spec; throws UsageError on an unknown option, a missing value, a value given
// to a flag, a non-repeatable option given twice, or '--'.
ParsedOptions parse_options(const std::vector<std::string>& args, const OptionSpec& spec);

// A positive integer option value: an integer in [1, max], else UsageError naming the option.
int positive_option(const std::string& name, const std::string& text, int max = kMaxThreads);

}  // namespace invasim::app
