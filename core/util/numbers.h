// disco — numeric constants shared by every layer.
#pragma once

#include <limits>

namespace disco {

// An absent bound. Ipopt treats any bound beyond +-1e19 as absent, so this
// passes through unchanged.
inline constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace disco
