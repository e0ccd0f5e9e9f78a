#pragma once
/// Which kernels the BLAS under CHOLMOD, UMFPACK and MUMPS took. Debian 12's OpenBLAS (0.3.21) does not know
/// processors newer than itself and falls back to its generic "Prescott" (SSE3) kernels: a factorisation of a
/// 27-fibre bundle's tangent then took twice as long on an Intel Xeon with AVX-512 (docs/performance.md).
/// OpenBLAS reads OPENBLAS_CORETYPE once, when it is loaded, so only the user (or a script) can choose other
/// kernels, before the process starts; nodus says when that would pay.

#include <string>

namespace nodus::solver {

struct BlasKernels {
  std::string loaded;  ///< OpenBLAS's name of the kernels it took; empty if the BLAS is not OpenBLAS
  /// The OPENBLAS_CORETYPE this processor could run instead of OpenBLAS's generic kernels ("SkylakeX" with
  /// AVX-512 F, CD, BW, DQ and VL; "Haswell" with AVX2 and FMA); empty if OpenBLAS did not fall back to them.
  std::string better;
};

BlasKernels blas_kernels();

}  // namespace nodus::solver
