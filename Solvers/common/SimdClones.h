// Function multi-versioning for the solvers' vectorised loops (the SPH neighbour list's
// candidate test and force loop's pair sums, the DEM contact table's contact law, the bonded
// force pass): cloned for x86-64-v4 (AVX-512) and chosen at run time where the processor has it
// (GCC's target_clones); elsewhere the generic code runs. The two differ only by rounding.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#define CK_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v4", "default")))
#else
#define CK_SIMD_CLONES
#endif
