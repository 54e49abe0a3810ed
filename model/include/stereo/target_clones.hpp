// STEREO_TARGET_CLONES: compile a hot loop for AVX-512, AVX2 and the x86-64 baseline and let the
// loader pick the best the CPU runs (GCC's target_clones, an ifunc on Linux). The library stays
// portable (the default build is not -march=native) and each clone is the same C++: integer code
// gives the same bits on every path. Elsewhere (clang, other CPUs) it expands to nothing.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 11 && defined(__x86_64__) && \
    defined(__linux__)
#define STEREO_TARGET_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define STEREO_TARGET_CLONES
#endif
