// Evaluates libm's functions on the same pseudo-random arguments and prints each result in hex,
// one line each: built with gcc (glibc) and with emcc (emscripten's musl), the two outputs show
// which functions round differently (tests/web/libm_probe.sh compares them). Issue 29, item 3.
#include <math.h>
#include <stdint.h>
#include <stdio.h>

static uint64_t state;
static double Uniform(void) {  // xorshift64: the same sequence on both builds
  state ^= state << 13;
  state ^= state >> 7;
  state ^= state << 17;
  return (double)(state >> 11) * (1.0 / 9007199254740992.0);
}

int main(void) {
  static const char* const kNames[] = {"sin",  "cos",  "tan",  "atan2", "exp",  "log",
                                       "pow",  "atan", "asin", "acos",  "hypot", "sinf",
                                       "cosf", "expm1", "log1p", "sqrt", "cbrt", "tanh"};
  const int n = (int)(sizeof kNames / sizeof kNames[0]);
  for (int k = 0; k < n; ++k) {
    state = 88172645463325252ull + (uint64_t)k;
    for (int i = 0; i < 2000; ++i) {
      const double a = (Uniform() - 0.5) * 20, b = (Uniform() - 0.5) * 20;
      double r = 0;
      switch (k) {
        case 0: r = sin(a); break;
        case 1: r = cos(a); break;
        case 2: r = tan(a); break;
        case 3: r = atan2(a, b); break;
        case 4: r = exp(a); break;
        case 5: r = log(fabs(a) + 1e-3); break;
        case 6: r = pow(fabs(a), b / 4); break;
        case 7: r = atan(a); break;
        case 8: r = asin(a / 10); break;
        case 9: r = acos(a / 10); break;
        case 10: r = hypot(a, b); break;
        case 11: r = sinf((float)a); break;
        case 12: r = cosf((float)a); break;
        case 13: r = expm1(a / 10); break;
        case 14: r = log1p(fabs(a)); break;
        case 15: r = sqrt(fabs(a)); break;
        case 16: r = cbrt(a); break;
        default: r = tanh(a); break;
      }
      printf("%s %a\n", kNames[k], r);
    }
  }
  return 0;
}
