#pragma once
// JSON text exactly as Python's `json.dumps(value, sort_keys=True)` writes it (default
// separators ", " and ": ", ensure_ascii, floats as Python's repr, integers and floats kept
// apart), and signac's job id: the MD5 of that text (signac's calc_id).
#include <nlohmann/json.hpp>
#include <string>

namespace invasim::sweep {

using Json = nlohmann::json;

// Python's repr of a double: the shortest digits that read back to it, in fixed notation for
// decimal exponents -4 <= e < 16 (with ".0" when integral) and d.ddde+XX otherwise; NaN and
// Infinity as json.dumps writes them.
std::string python_float_repr(double value);

// json.dumps(value, sort_keys=True). Strings must be valid UTF-8 (InputError otherwise).
std::string python_dumps(const Json& value);

// signac's job id of a state point: MD5 hex of python_dumps(statepoint).
std::string signac_id(const Json& statepoint);

}  // namespace invasim::sweep
