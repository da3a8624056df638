#pragma once

// Private to the library's sources (built with -ffp-contract=off): the AVX-512 target enables FMA, so code
// compiled elsewhere with this attribute could contract a * b + c and lose the generic path's bits.
/// Function attributes of the kAvx512 clones: AVX-512F/BW, 512-bit auto-vectorisation (GCC prefers 256 bits
/// otherwise), every call inlined into the clone (flatten) so that the callees' loops use the same target.
#define BIOVISION_STEREO_AVX512_CLONE __attribute__((target("avx2,avx512f,avx512bw,prefer-vector-width=512"), flatten))
