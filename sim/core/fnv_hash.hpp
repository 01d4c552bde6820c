#pragma once
/// \file The 64-bit FNV-1a hash of a string: a fast, stable, non-cryptographic checksum (a
/// journal entry's check) and seed (a named sensor's noise stream). Its values are pinned by
/// saved journals and by the determinism tests: never change the constants or the order.

#include <cstdint>
#include <string>

namespace formsim::sim {

/// FNV-1a (64-bit) of the bytes of `text`, each read as an unsigned char.
inline std::uint64_t Fnv1a64(const std::string& text) {
  std::uint64_t hash = 1469598103934665603ULL;  // the FNV-1a 64-bit offset basis
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ULL;  // the FNV 64-bit prime
  }
  return hash;
}

}  // namespace formsim::sim
