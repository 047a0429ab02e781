// Exits 0 when the processor running it has AVX2 (cmake/simd.cmake).
int main() { return __builtin_cpu_supports("avx2") ? 0 : 1; }
