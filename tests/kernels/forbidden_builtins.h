/*
 * forbidden_builtins.h — force-included into every kernel program by the builtin_rule tests
 * (tests/kernels/CMakeLists.txt): a use of any identifier below is a compile error.
 *
 * The rule (docs/design.md, "Same operations everywhere"): on every path that decides a hit,
 * a spawn point or a sampling branch, no built-in whose precision the OpenCL specification
 * leaves to the implementation. Those give different bits on different devices, and one
 * differing bit is enough to send a path elsewhere. The kernels use the spelled-out helpers
 * of kernels/shared instead: gc_vecmath.h (dot, cross, length, normalize), gc_trig.h (sine,
 * cosine, arc functions), gc_pow.h (powers). sqrt and division stay: the program builder asks
 * for -cl-fp32-correctly-rounded-divide-sqrt, which makes them IEEE-exact.
 *
 * #pragma clang poison applies after the default header has declared the built-ins, and to
 * tokens only, so comments may still name them.
 */
#pragma clang poison dot cross length normalize distance fast_length fast_normalize fast_distance
#pragma clang poison fma mad mad24 mad_hi mad_sat rsqrt cbrt hypot
#pragma clang poison pow pown powr rootn exp exp2 exp10 expm1 log log2 log10 log1p
#pragma clang poison sin cos tan sincos sinpi cospi tanpi asin acos atan atan2 asinpi acospi atanpi atan2pi
#pragma clang poison sinh cosh tanh asinh acosh atanh erf erfc tgamma lgamma
#pragma clang poison native_sqrt native_rsqrt native_recip native_divide native_powr
#pragma clang poison native_exp native_exp2 native_exp10 native_log native_log2 native_log10
#pragma clang poison native_sin native_cos native_tan
#pragma clang poison half_sqrt half_rsqrt half_recip half_divide half_powr half_exp half_exp2 half_exp10
#pragma clang poison half_log half_log2 half_log10 half_sin half_cos half_tan
