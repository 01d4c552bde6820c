#pragma once
/// \file SHA-256 of a byte string, for the provenance of a run (which scenario text produced
/// it). FIPS 180-4; small enough not to need a crypto library.

#include <string>

namespace formsim::sim {

/// Lower-case hex digest of `data`.
std::string Sha256Hex(const std::string& data);

}  // namespace formsim::sim
