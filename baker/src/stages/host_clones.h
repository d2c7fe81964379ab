// IBL_HOST_CLONES before a CPU backend item: the item with everything it calls inlined (flatten), compiled
// for AVX-512, AVX2 and portable x86-64, the one the machine runs chosen at load time. Its file is built with
// the options of baker/CMakeLists.txt's clone list. GCC only: clang refuses multiversioning with flatten, and
// builds with clang (the sanitizer build) need no speed here.
#ifndef IBLBAKE_STAGES_HOST_CLONES_H
#define IBLBAKE_STAGES_HOST_CLONES_H

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define IBL_HOST_CLONES __attribute__((flatten, target_clones("avx512f", "avx2", "default")))
#else
#define IBL_HOST_CLONES
#endif

#endif
