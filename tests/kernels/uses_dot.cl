/* A program that breaks the cross-device rule: KernelBuiltinRule.catches_a_builtin expects
 * it not to compile with forbidden_builtins.h force-included. */
__kernel void breaks_the_rule(__global float* out)
{
    const float3 a = (float3)(1.0f, 2.0f, 3.0f);
    out[0] = dot(a, a);
}
