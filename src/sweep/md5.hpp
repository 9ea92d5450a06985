#pragma once
// MD5 (RFC 1321) of a byte string as 32 lowercase hex digits: signac's job id is the MD5 of
// the state point's JSON text (python_json.hpp).
#include <string>
#include <string_view>

namespace invasim::sweep {

std::string md5_hex(std::string_view bytes);

}  // namespace invasim::sweep
