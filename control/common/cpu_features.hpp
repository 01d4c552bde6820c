#pragma once
/// \file What the CPU running formsim can do, asked once (the SIMD kernels that give the same
/// bits on every path choose their width by it).

namespace formsim::control {

/// Whether this CPU has AVX2 (__builtin_cpu_supports; false off x86, e.g. in the browser build).
bool CpuHasAvx2();

}  // namespace formsim::control
