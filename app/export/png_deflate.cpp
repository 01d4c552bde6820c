#include "app/export/png_deflate.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <stdexcept>

#include "control/common/cpu_features.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define FORMSIM_PNG_X86 1
#endif

namespace formsim::app {
namespace {
namespace pngz {  // named: in a unity build the other files' anonymous namespaces are this one

std::atomic<bool> force_scalar{false};

constexpr std::uint32_t kAdlerMod = 65521;

// Eight bytes at a time, as the AVX2 code does 32: over a block, s2 gains 8 x s1 per word
// (s1 taken at each word's start: `prefix`) plus 8 x b0 + 7 x b1 + ... + b7. The sums of the
// even and the odd bytes in 16-bit lanes, each lane times its weight, added up into the top lane
// by one multiply; no lane carries (at most 255 x 20).
std::uint32_t Adler32Scalar(std::uint32_t adler, const std::uint8_t* p, std::size_t n) {
  constexpr std::uint64_t kEven = 0x00FF00FF00FF00FFull;
  std::uint64_t s1 = adler & 0xffff, s2 = adler >> 16;
  while (n >= 8) {
    // 4096 words: every sum stays far below 2^64 before the modulo.
    const std::size_t words = std::min<std::size_t>(n / 8, 4096);
    n -= 8 * words;
    std::uint64_t sum = 0, prefix = 0, weighted = 0;
    for (std::size_t k = 0; k < words; ++k, p += 8) {
      const std::uint64_t x = LoadLE64(p), even = x & kEven, odd = (x >> 8) & kEven;
      prefix += sum;
      sum += ((even + odd) * 0x0001000100010001ull) >> 48;
      weighted += (even * 0x0008000600040002ull) >> 48;
      weighted += (odd * 0x0007000500030001ull) >> 48;
    }
    s2 = (s2 + 8 * words * s1 + 8 * prefix + weighted) % kAdlerMod;
    s1 = (s1 + sum) % kAdlerMod;
  }
  for (std::size_t i = 0; i < n; ++i) {
    s1 += p[i];
    s2 += s1;
  }
  return static_cast<std::uint32_t>(((s2 % kAdlerMod) << 16) | (s1 % kAdlerMod));
}

// Bits 0 to d - 1 and from n on are 0 (d <= 8).
void ClearEdges(std::size_t n, std::size_t d, std::uint64_t* eq) {
  const std::size_t words = (n + 63) / 64;
  if (words == 0) return;
  eq[0] &= ~((std::uint64_t{1} << d) - 1);
  if (n % 64 != 0) eq[words - 1] &= (std::uint64_t{1} << (n % 64)) - 1;
}

// Bit i of eq (d <= i < n): row[i] == row[i - d]. Eight bytes at a time: equal bytes are the
// zero bytes of a XOR, found without carries and gathered by a multiply.
void EqBitsScalar(const std::uint8_t* row, std::size_t n, std::size_t d, std::uint64_t* eq) {
  constexpr std::uint64_t kLow7 = 0x7F7F7F7F7F7F7F7Full;
  const std::size_t words = (n + 63) / 64;
  for (std::size_t w = 0; w < words; ++w) {
    std::uint64_t bits = 0;
    for (int k = 0; k < 8; ++k) {
      const std::uint8_t* p = row + 64 * w + 8 * k;
      const std::uint64_t x = LoadLE64(p) ^ LoadLE64(p - d);
      const std::uint64_t zero = ~(((x & kLow7) + kLow7) | x | kLow7);  // 0x80 where x's byte is 0
      bits |= (((zero >> 7) * 0x0102040810204080ull) >> 56) << (8 * k);
    }
    eq[w] = bits;
  }
  ClearEdges(n, d, eq);
}

#ifdef FORMSIM_PNG_X86
// (Lambdas would not inherit the target attribute: the helpers are functions.)
__attribute__((target("avx2"))) inline std::uint64_t HSum32(__m256i v) {
  const __m128i s = _mm_add_epi32(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
  const __m128i t = _mm_add_epi32(s, _mm_shuffle_epi32(s, 0x4E));
  return static_cast<std::uint32_t>(
      _mm_cvtsi128_si32(_mm_add_epi32(t, _mm_shuffle_epi32(t, 0xB1))));
}

// Bit j: q[j] == q[j - d], j < 32.
__attribute__((target("avx2"))) inline std::uint64_t EqBits32(const std::uint8_t* q,
                                                              std::size_t d) {
  const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q));
  const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q - d));
  return static_cast<std::uint32_t>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(a, b)));
}

__attribute__((target("avx2"))) std::uint32_t Adler32Avx2(std::uint32_t adler,
                                                          const std::uint8_t* p, std::size_t n) {
  std::uint64_t s1 = adler & 0xffff, s2 = adler >> 16;
  const __m256i weights =
      _mm256_setr_epi8(32, 31, 30, 29, 28, 27, 26, 25, 24, 23, 22, 21, 20, 19, 18, 17, 16, 15, 14,
                       13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1);
  const __m256i ones = _mm256_set1_epi16(1);
  const __m256i zero = _mm256_setzero_si256();
  while (n >= 32) {
    // 173 vectors (5536 bytes) keep every 32-bit lane from overflowing; s1 and s2 are 64-bit.
    const std::size_t vecs = std::min<std::size_t>(n / 32, 173);
    n -= vecs * 32;
    __m256i v1 = zero, v2 = zero, prefix = zero;
    for (std::size_t k = 0; k < vecs; ++k, p += 32) {
      const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
      prefix = _mm256_add_epi32(prefix, v1);  // s1 at each vector's start, summed
      v1 = _mm256_add_epi32(v1, _mm256_sad_epu8(v, zero));
      v2 = _mm256_add_epi32(v2, _mm256_madd_epi16(_mm256_maddubs_epi16(v, weights), ones));
    }
    // Byte j of a vector adds (32 - j) times to s2, and s2 gains 32 x s1 per vector.
    s2 += 32 * vecs * s1 + 32 * HSum32(prefix) + HSum32(v2);
    s1 += HSum32(v1);
    s1 %= kAdlerMod;
    s2 %= kAdlerMod;
  }
  for (std::size_t i = 0; i < n; ++i) {
    s1 += p[i];
    s2 += s1;
  }
  return static_cast<std::uint32_t>(((s2 % kAdlerMod) << 16) | (s1 % kAdlerMod));
}

__attribute__((target("avx2"))) void EqBitsAvx2(const std::uint8_t* row, std::size_t n,
                                                std::size_t d, std::uint64_t* eq) {
  const std::size_t words = (n + 63) / 64;
  for (std::size_t w = 0; w < words; ++w) {
    const std::uint8_t* p = row + 64 * w;
    eq[w] = EqBits32(p, d) | (EqBits32(p + 32, d) << 32);
  }
  ClearEdges(n, d, eq);
}
#endif

// Deflate's length codes (RFC 1951 3.2.5): symbol 257 + c covers kLenBase[c] on, with
// kLenExtra[c] extra bits. 258 has its own symbol (285), without extra bits.
constexpr std::uint16_t kLenBase[29] = {3,  4,  5,  6,   7,   8,   9,   10,  11, 13,
                                        15, 17, 19, 23,  27,  31,  35,  43,  51, 59,
                                        67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::uint8_t kLenExtra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                        2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};

struct LenCodes {
  std::uint8_t code[259] = {};  ///< length 3..258 -> 0..28
  LenCodes() {
    for (int l = 3, c = 0; l <= 258; ++l) {
      while (c < 28 && kLenBase[c + 1] <= l) ++c;
      code[l] = static_cast<std::uint8_t>(c);
    }
  }
};
const LenCodes kLenCodes;

int LenCode(std::size_t len) {
  return kLenCodes.code[len];
}

// The matches a run of `run` (>= 3) copies is sent as: 258 at a time, never leaving 1 or 2.
template <class F>
void SplitRun(std::size_t run, F&& match) {
  for (; run >= 258 + 3; run -= 258) match(258);
  if (run > 258) {
    match(run - 3);
    run = 3;
  }
  match(run);
}

// Huffman code lengths of at most `limit` bits for the symbols with freq > 0 (others get 0).
// Two-queue construction over leaves sorted by (count, symbol), so the result is the same on
// every machine; when a length exceeds the limit, the counts are halved (rounded up) and the
// tree rebuilt, which flattens it. One used symbol gets a second (unused) one for a full code.
void BuildLengths(const std::uint32_t* freq, int n, int limit, std::uint8_t* len) {
  std::fill(len, len + n, 0);
  std::vector<int> sym;
  for (int i = 0; i < n; ++i)
    if (freq[i] > 0) sym.push_back(i);
  const int m = static_cast<int>(sym.size());
  if (m == 0) return;
  if (m == 1) {
    len[sym[0]] = 1;
    len[sym[0] == 0 ? 1 : 0] = 1;
    return;
  }
  std::vector<std::uint64_t> f(m), w(2 * m - 1);
  for (int k = 0; k < m; ++k) f[k] = freq[sym[k]];
  std::vector<int> order(m), parent(2 * m - 1), depth(2 * m - 1);
  for (;;) {
    for (int k = 0; k < m; ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return f[a] < f[b]; });
    for (int k = 0; k < m; ++k) w[k] = f[order[k]];
    int leaf = 0, inner = m;
    for (int k = m; k < 2 * m - 1; ++k) {
      auto pick = [&] {
        return leaf < m && (inner >= k || w[leaf] <= w[inner]) ? leaf++ : inner++;
      };
      const int a = pick(), b = pick();
      w[k] = w[a] + w[b];
      parent[a] = parent[b] = k;
    }
    depth[2 * m - 2] = 0;
    int deepest = 0;
    for (int k = 2 * m - 3; k >= 0; --k) {
      depth[k] = depth[parent[k]] + 1;
      deepest = std::max(deepest, depth[k]);
    }
    if (deepest <= limit) {
      for (int k = 0; k < m; ++k) len[sym[order[k]]] = static_cast<std::uint8_t>(depth[k]);
      return;
    }
    for (auto& c : f) c = (c + 1) / 2;
  }
}

// Canonical codes (RFC 1951 3.2.2), bit-reversed: deflate sends Huffman codes first bit first
// into a stream that is filled from the least significant bit.
void BuildCodes(const std::uint8_t* len, int n, std::uint16_t* code) {
  int count[16] = {}, next[16] = {};
  for (int i = 0; i < n; ++i) ++count[len[i]];
  count[0] = 0;
  for (int b = 1, c = 0; b < 16; ++b) {
    c = (c + count[b - 1]) << 1;
    next[b] = c;
  }
  for (int i = 0; i < n; ++i) {
    if (len[i] == 0) continue;
    int c = next[len[i]]++, r = 0;
    for (int b = 0; b < len[i]; ++b, c >>= 1) r = (r << 1) | (c & 1);
    code[i] = static_cast<std::uint16_t>(r);
  }
}

// Bits into bytes, least significant first. Add may be called for up to 56 bits between
// Flushes; Flush stores 8 bytes (the output has that much slack) and advances by the whole ones.
struct BitWriter {
  std::uint8_t* out;
  std::uint64_t buf = 0;
  int n = 0;
  void Add(std::uint64_t bits, int count) {
    buf |= bits << n;
    n += count;
  }
  void Flush() {
    StoreLE64(out, buf);
    out += n >> 3;
    buf >>= n & ~7;
    n &= 7;
  }
  std::uint8_t* Finish() {  // to a byte boundary
    Flush();
    if (n > 0) *out++ = static_cast<std::uint8_t>(buf);
    buf = 0;
    n = 0;
    return out;
  }
};

// One item of the code lengths' run-length code: a length 0-15, or 16 (repeat the last 3-6
// times), 17 (3-10 zeros) or 18 (11-138 zeros) with its extra bits.
struct ClItem {
  std::uint8_t sym, extra;
};

// Order in which the code-length code's lengths are sent, and its symbols' extra bits.
constexpr std::uint8_t kClOrder[19] = {16, 17, 18, 0, 8,  7, 9,  6, 10, 5,
                                       11, 4,  12, 3, 13, 2, 14, 1, 15};
constexpr std::uint8_t kClExtra[19] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 3, 7};

// The Huffman codes of RunDeflater's one block: literal/length and distance codes, and the
// code-length code that sends their lengths in the block's header (RFC 1951 3.2.7).
class BlockCodes {
 public:
  BlockCodes(const std::uint32_t* freq, std::size_t distance) {
    ChooseLengths(freq, distance);
    CodeTheLengths();
    BuildCodes(len_, hlit_, code_);
  }
  // The exact size of the block in bits: the header's from the items, the body's from `freq`.
  std::uint64_t BlockBits(const std::uint32_t* freq) const;
  // Block header: final block, dynamic codes, the counts and the code lengths.
  void WriteHeader(BitWriter& bw) const;
  // Literal byte (or 256, end of block) `sym`.
  void AddLiteral(BitWriter& bw, int sym) const { bw.Add(code_[sym], len_[sym]); }

 private:
  friend struct MatchCodes;
  void ChooseLengths(const std::uint32_t* freq, std::size_t distance);
  void CodeTheLengths();

  std::uint8_t len_[286 + 4] = {};  // literal/length code lengths, then the distance code's
  std::uint16_t code_[286] = {};
  int hlit_ = 286, hdist_ = 0, hclen_ = 19;
  std::uint32_t dist_bits_ = 0;  // the distance code sent (1 bit)
  std::vector<ClItem> items_;
  std::uint8_t cl_len_[19] = {};
  std::uint16_t cl_code_[19] = {};
};

// The literal/length code, then the distance code: distances 1 to 4 are codes 0 to 3 without
// extra bits; ours and code 0 (or 1) get one bit each, a complete code (decoders need not
// accept the one-code, one-bit case of RFC 1951 3.2.7), the one sent being ours.
void BlockCodes::ChooseLengths(const std::uint32_t* freq, std::size_t distance) {
  BuildLengths(freq, 286, 15, len_);
  while (hlit_ > 257 && len_[hlit_ - 1] == 0) --hlit_;
  const int dist_code = static_cast<int>(distance) - 1, other = dist_code == 0 ? 1 : 0;
  hdist_ = std::max(dist_code, other) + 1;
  std::fill(len_ + hlit_, len_ + hlit_ + hdist_, 0);
  len_[hlit_ + dist_code] = len_[hlit_ + other] = 1;
  dist_bits_ = dist_code > other ? 1 : 0;  // the longer code is 1
}

// The code lengths, run-length coded with symbols 16, 17 and 18, and the code that sends them.
void BlockCodes::CodeTheLengths() {
  const int n_lengths = hlit_ + hdist_;
  for (int i = 0; i < n_lengths;) {
    const std::uint8_t v = len_[i];
    int run = 1;
    while (i + run < n_lengths && len_[i + run] == v) ++run;
    i += run;
    if (v == 0) {
      for (; run >= 11; run -= std::min(run, 138))
        items_.push_back({18, static_cast<std::uint8_t>(std::min(run, 138) - 11)});
      if (run >= 3) {
        items_.push_back({17, static_cast<std::uint8_t>(run - 3)});
        run = 0;
      }
    } else {
      items_.push_back({v, 0});
      --run;
      for (; run >= 3; run -= std::min(run, 6))
        items_.push_back({16, static_cast<std::uint8_t>(std::min(run, 6) - 3)});
    }
    for (; run > 0; --run) items_.push_back({v, 0});
  }
  std::uint32_t cl_freq[19] = {};
  for (const ClItem& it : items_) ++cl_freq[it.sym];
  BuildLengths(cl_freq, 19, 7, cl_len_);
  BuildCodes(cl_len_, 19, cl_code_);
  while (hclen_ > 4 && cl_len_[kClOrder[hclen_ - 1]] == 0) --hclen_;
}

std::uint64_t BlockCodes::BlockBits(const std::uint32_t* freq) const {
  std::uint64_t bits = 3 + 14 + 3 * static_cast<std::uint64_t>(hclen_);
  for (const ClItem& it : items_) bits += cl_len_[it.sym] + kClExtra[it.sym];
  for (int s = 0; s < 257; ++s) bits += static_cast<std::uint64_t>(freq[s]) * len_[s];
  for (int c = 0; c < 29 && 257 + c < hlit_; ++c)
    bits += static_cast<std::uint64_t>(freq[257 + c]) * (len_[257 + c] + kLenExtra[c] + 1);
  return bits;
}

void BlockCodes::WriteHeader(BitWriter& bw) const {
  bw.Add(1 | (2 << 1), 3);  // final block, dynamic Huffman codes
  bw.Add(static_cast<std::uint64_t>(hlit_ - 257) | ((hdist_ - 1u) << 5) | ((hclen_ - 4u) << 10),
         14);
  bw.Flush();
  for (int k = 0; k < hclen_; ++k) {
    bw.Add(cl_len_[kClOrder[k]], 3);
    bw.Flush();
  }
  for (const ClItem& it : items_) {
    bw.Add(cl_code_[it.sym], cl_len_[it.sym]);
    bw.Add(it.extra, kClExtra[it.sym]);
    bw.Flush();
  }
}

// A match of each length 3-258: its code, extra bits and the distance code in one word.
struct MatchCodes {
  std::uint32_t bits[259] = {};
  std::uint8_t n[259] = {};
  explicit MatchCodes(const BlockCodes& c) {
    for (std::size_t l = 3; l <= 258; ++l) {
      const int code = LenCode(l);
      const int s = 257 + code;
      if (c.len_[s] == 0) continue;  // never sent
      bits[l] = c.code_[s] | static_cast<std::uint32_t>(l - kLenBase[code]) << c.len_[s] |
                c.dist_bits_ << (c.len_[s] + kLenExtra[code]);
      n[l] = static_cast<std::uint8_t>(c.len_[s] + kLenExtra[code] + 1);
    }
  }
};

}  // namespace pngz
}  // namespace

std::uint32_t Adler32(std::uint32_t adler, const std::uint8_t* data, std::size_t n) {
#ifdef FORMSIM_PNG_X86
  if (PngUsesAvx2()) return pngz::Adler32Avx2(adler, data, n);
#endif
  return pngz::Adler32Scalar(adler, data, n);
}

bool PngUsesAvx2() {
  return control::CpuHasAvx2() && !pngz::force_scalar.load(std::memory_order_relaxed);
}

void ForcePngScalar(bool scalar) {
  pngz::force_scalar.store(scalar);
}

void RunDeflater::Reset(std::size_t distance) {
  if (distance < 1 || distance > 4) throw std::invalid_argument("RunDeflater: distance not 1-4");
  distance_ = distance;
  n_lits_ = 0;
  n_tokens_ = 0;
  pending_lits_ = 0;
  std::fill(std::begin(freq_), std::end(freq_), 0);
  freq_[256] = 1;  // end of block
  adler_ = 1;
}

void RunDeflater::Trim(std::size_t bytes) {
  if (lits_.capacity() > bytes) std::vector<std::uint8_t>().swap(lits_);
  if (tokens_.capacity() * sizeof(Token) > bytes) std::vector<Token>().swap(tokens_);
  if (eq_.capacity() * 8 > bytes) std::vector<std::uint64_t>().swap(eq_);
  n_lits_ = n_tokens_ = 0;
}

void RunDeflater::AddLiterals(const std::uint8_t* p, std::size_t n) {
  std::memcpy(lits_.data() + n_lits_, p, n);
  n_lits_ += n;
  for (std::size_t i = 0; i < n; ++i) ++freq_[p[i]];
  pending_lits_ += static_cast<std::uint32_t>(n);
  if (pending_lits_ >= (1u << 30)) {  // keeps Token::lits in range on huge noisy images
    tokens_[n_tokens_++] = {pending_lits_, 0};
    pending_lits_ = 0;
  }
}

void RunDeflater::AddRun(std::size_t run) {
  tokens_[n_tokens_++] = {pending_lits_, static_cast<std::uint32_t>(run)};
  pending_lits_ = 0;
  pngz::SplitRun(run, [&](std::size_t len) { ++freq_[257 + pngz::LenCode(len)]; });
}

void RunDeflater::AddRow(const std::uint8_t* row, std::size_t n) {
  if (n == 0) return;
  // Room for the worst case: every byte a literal, a run every kMinRun + 1 bytes.
  if (lits_.size() < n_lits_ + n) lits_.resize(std::max(2 * lits_.size(), n_lits_ + n));
  const std::size_t max_tokens = n / (kMinRun + 1) + 2;
  if (tokens_.size() < n_tokens_ + max_tokens)
    tokens_.resize(std::max(2 * tokens_.size(), n_tokens_ + max_tokens));
  const std::size_t words = (n + 63) / 64;
  if (eq_.size() < words) eq_.resize(words);

  std::uint64_t* eq = eq_.data();
#ifdef FORMSIM_PNG_X86
  if (PngUsesAvx2()) {
    adler_ = pngz::Adler32Avx2(adler_, row, n);
    pngz::EqBitsAvx2(row, n, distance_, eq);
  } else
#endif
  {
    adler_ = pngz::Adler32Scalar(adler_, row, n);
    pngz::EqBitsScalar(row, n, distance_, eq);
  }
  // The first index from i on whose bit is `set`, or n.
  auto next = [&](std::size_t i, bool set) {
    std::size_t w = i >> 6;
    std::uint64_t word = (set ? eq[w] : ~eq[w]) & (~std::uint64_t{0} << (i & 63));
    while (word == 0) {
      if (++w >= words) return n;
      word = set ? eq[w] : ~eq[w];
    }
    return std::min(n, 64 * w + static_cast<std::size_t>(__builtin_ctzll(word)));
  };
  std::size_t lit_start = 0;  // the first byte not yet added
  for (std::size_t i = 1; i < n;) {
    const std::size_t start = next(i, true);
    if (start >= n) break;
    const std::size_t end = next(start, false);
    // row[start .. end - 1] repeats the bytes `distance_` before: a match.
    if (end - start >= kMinRun) {
      AddLiterals(row + lit_start, start - lit_start);
      AddRun(end - start);
      lit_start = end;
    }
    i = end;
  }
  AddLiterals(row + lit_start, n - lit_start);
}

void RunDeflater::Finish(std::vector<std::uint8_t>& out) {
  using pngz::BitWriter;
  if (pending_lits_ > 0) {
    tokens_.resize(std::max(tokens_.size(), n_tokens_ + 1));
    tokens_[n_tokens_++] = {pending_lits_, 0};
    pending_lits_ = 0;
  }
  const pngz::BlockCodes codes(freq_, distance_);
  const std::size_t start = out.size();
  const std::size_t bound = 2 + (codes.BlockBits(freq_) + 7) / 8 + 4;
  out.resize(start + bound + 8);  // + 8: BitWriter stores whole 64-bit words

  std::uint8_t* p = out.data() + start;
  *p++ = 0x78;  // deflate, 32 kB window
  *p++ = 0x01;  // no dictionary, "fastest" (0x7801 is a multiple of 31)
  BitWriter bw{p};
  codes.WriteHeader(bw);
  const pngz::MatchCodes matches(codes);
  const std::uint8_t* lit = lits_.data();
  for (std::size_t t = 0; t < n_tokens_; ++t) {
    std::uint32_t k = tokens_[t].lits;
    for (; k >= 3; k -= 3, lit += 3) {  // 3 x 15 bits fit between Flushes
      codes.AddLiteral(bw, lit[0]);
      codes.AddLiteral(bw, lit[1]);
      codes.AddLiteral(bw, lit[2]);
      bw.Flush();
    }
    for (; k > 0; --k, ++lit) {
      codes.AddLiteral(bw, *lit);
      bw.Flush();
    }
    if (tokens_[t].run > 0)
      pngz::SplitRun(tokens_[t].run, [&](std::size_t l) {
        bw.Add(matches.bits[l], matches.n[l]);
        bw.Flush();
      });
  }
  codes.AddLiteral(bw, 256);  // end of block
  p = bw.Finish();
  for (int k = 3; k >= 0; --k) *p++ = static_cast<std::uint8_t>(adler_ >> (8 * k));
  const std::size_t written = static_cast<std::size_t>(p - (out.data() + start));
  if (written > bound) throw std::logic_error("RunDeflater: stream larger than counted");
  out.resize(start + written);
}

}  // namespace formsim::app
