// Included where the functions that follow, up to avx2_functions_end.h, are compiled for AVX2
// alone (GCC's pragma; clang's), in a file the rest of which is built for any x86-64: the caller
// checks __builtin_cpu_supports("avx2") before it calls one. No include guard: each use pushes once.
#ifdef __clang__
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
