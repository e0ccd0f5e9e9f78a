#include "nodus/solver/blas_kernels.hpp"

#include <dlfcn.h>

namespace nodus::solver {

BlasKernels blas_kernels() {
  BlasKernels k;
  // Looked up rather than linked: the BLAS is whichever libblas.so.3 Debian's alternatives point at.
  using CoreName = char* (*)();
  const auto core_name = reinterpret_cast<CoreName>(::dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  if (core_name == nullptr) return k;
  const char* name = core_name();
  k.loaded = name ? name : "";
  if (k.loaded != "Prescott" && k.loaded != "prescott") return k;
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl"))
    k.better = "SkylakeX";
  else if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    k.better = "Haswell";
  return k;
}

}  // namespace nodus::solver
