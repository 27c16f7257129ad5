// Ends the functions compiled for AVX2 alone that avx2_functions_begin.h began.
#ifdef __clang__
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
