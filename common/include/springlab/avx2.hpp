// Where the kit's hot loops also come as AVX2 versions (issue 36). On x86-64 with ELF objects
// (Linux, the BSDs) under GCC or Clang, a loop marked SPRINGLAB_AVX2_CLONES is compiled twice, for
// AVX2 and for the processor's baseline, and the loader picks one (target_clones); XPBD's explicit
// four-at-a-time projection exists only there too. Everywhere else (arm64 such as Apple Silicon,
// macOS's Mach-O and Windows' PE objects, which have no load-time choice) the same loops compile
// once for the baseline: the portable path, which gives the same bits as the AVX2 one
// (tests/CMakeLists.txt, label portable). -DSPRINGLAB_PORTABLE_ONLY builds only the portable path
// on any machine, for comparing speed (tests/benchmarks/README.md).
#pragma once

#if defined(__x86_64__) && defined(__ELF__) && defined(__GNUC__) && \
    !defined(SPRINGLAB_PORTABLE_ONLY)
#define SPRINGLAB_AVX2_PATHS 1
#define SPRINGLAB_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SPRINGLAB_AVX2_PATHS 0
#define SPRINGLAB_AVX2_CLONES
#endif
