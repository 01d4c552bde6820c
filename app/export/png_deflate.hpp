#pragma once
/// \file A zlib stream (RFC 1950/1951) written by our own code for PNG rows filtered "up" (issue
/// 28): exported frames are flat backgrounds with thin lines and text, so after the filter most
/// bytes are zero, and the rows of a horizontal edge or grid line repeat one pixel's difference.
/// A general LZ77 search (zlib) spends most of its time hashing inside those runs; here a run of
/// bytes equal to those one pixel before becomes a match at that distance, everything else a
/// literal, under one dynamic Huffman block built from the exact histogram. In the spirit of
/// fpnge (github.com/veluca93/fpnge). About 8x less CPU than zlib level 2 on our frames, for
/// 1.25x the bytes.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace formsim::app {

/// 8 bytes read as a little-endian word, the same on every host (the encoder's rows are
/// compared and filtered 8 bytes at a time).
inline std::uint64_t LoadLE64(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  v = __builtin_bswap64(v);
#endif
  return v;
}

/// Writes `v` as 8 little-endian bytes.
inline void StoreLE64(std::uint8_t* p, std::uint64_t v) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  v = __builtin_bswap64(v);
#endif
  std::memcpy(p, &v, 8);
}

/// Adler-32 (RFC 1950) of `n` bytes, continuing from `adler` (1 for a new stream): the value of
/// zlib's adler32, computed with AVX2 when the CPU has it.
std::uint32_t Adler32(std::uint32_t adler, const std::uint8_t* data, std::size_t n);

/// True when the PNG encoder runs its AVX2 code: the CPU has AVX2 and ForcePngScalar is off.
/// Every path writes the same bytes (the tests compare them).
bool PngUsesAvx2();

/// For tests: `true` makes the PNG encoder and Adler32 run their plain C++ code, the code the
/// browser build (emscripten) and CPUs without AVX2 run. Not for use while images are encoded.
void ForcePngScalar(bool scalar);

/// Bytes a row given to RunDeflater::AddRow must have readable before and after it (the values
/// there do not matter): the row is compared with itself shifted by one, 64 bytes at a time.
inline constexpr std::size_t kRowPadBefore = 32;
inline constexpr std::size_t kRowPadAfter = 64;

/// Deflates rows of bytes into one zlib stream: inside a row, runs of at least kMinRun bytes
/// equal to the byte `distance` before them are matches, all other bytes literals. Runs do not
/// cross rows. Buffers are kept between streams (one per thread).
class RunDeflater {
 public:
  /// Runs shorter than this stay literals: a match costs its length code, extra bits and the
  /// distance bit, a few short-coded literals about the same, and literals are cheap to find.
  static constexpr std::size_t kMinRun = 8;

  /// Starts a new stream (keeps the buffers) whose matches copy from `distance` (1 to 4) bytes
  /// back: for PNG rows the pixel size, so that a run of equal pixels (a flat row, and under
  /// "up" a horizontal edge or grid line, whose bytes repeat every pixel) is one match.
  void Reset(std::size_t distance);
  /// Adds `n` bytes; `row[-kRowPadBefore]` to `row[n + kRowPadAfter - 1]` must be readable.
  void AddRow(const std::uint8_t* row, std::size_t n);
  /// Appends the zlib stream of everything added since Reset to `out`.
  void Finish(std::vector<std::uint8_t>& out);
  /// Lets go of buffers larger than `bytes` (after a very large image).
  void Trim(std::size_t bytes);

 private:
  /// `lits` literals (taken in turn from lits_) then, if `run` > 0, `run` copies of the last one.
  struct Token {
    std::uint32_t lits, run;
  };
  void AddLiterals(const std::uint8_t* p, std::size_t n);
  void AddRun(std::size_t run);

  std::vector<std::uint8_t> lits_;  ///< literal bytes, in order (size: capacity in use)
  std::size_t n_lits_ = 0;
  std::vector<Token> tokens_;
  std::size_t n_tokens_ = 0;
  std::uint32_t pending_lits_ = 0;  ///< literals since the last token
  std::vector<std::uint64_t> eq_;   ///< bit i of a row: row[i] == row[i - distance_]
  std::uint32_t freq_[286] = {};    ///< literal/length symbol counts
  std::uint32_t adler_ = 1;
  std::size_t distance_ = 1;
};

}  // namespace formsim::app
