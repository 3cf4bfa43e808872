#version 300 es
// EigenFires reconstruction at the model's resolution: mean + sum_i w_i * eigen_i.
// The stack holds raw quantised values (mean first, then each eigen-image);
// value_i = offset_i + scale_i * q_i, so the CPU folds scale and weight into
// u_coef (one float per stack entry) and every offset into u_bias.
// Default (packed): four entries per RGBA texel, one layer per four entries.
// Otherwise (LAYERED): one entry per layer in the red channel.
// PIXEL_MAJOR: the stack's "layer" l of pixel (x, y) is at texel (l, x) of
// array layer y, so that a pixel's entries lie side by side in memory.
precision highp float;
precision highp int;
precision highp usampler2DArray;

#ifndef MAX_VEC4
#define MAX_VEC4 65
#endif

uniform usampler2DArray u_stack;
uniform int u_layers;
uniform vec4 u_coef[MAX_VEC4];
uniform float u_bias;
uniform ivec2 u_origin;  // where the image starts in the target
#ifdef FROM_CACHE
// A model frame's reconstruction kept earlier (the frame cache: the
// unclamped sum in 1/64 gray levels, offset by 256); u_coef and u_bias then
// hold only the difference of the weights from that frame's.
uniform highp usampler2DArray u_cache;
uniform int u_frame;
#endif
#ifdef TO_CACHE
out uvec4 o_gray;
#else
out vec4 o_gray;
#endif

#ifdef PIXEL_MAJOR
#define STACK_AT(l) ivec3(l, p.x, p.y)
#else
#define STACK_AT(l) ivec3(p, l)
#endif

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - u_origin;
  float v = u_bias;
#ifdef FROM_CACHE
  v += float(texelFetch(u_cache, ivec3(p, u_frame), 0).r) * (1.0 / 64.0) - 256.0;
#endif
#ifndef LAYERED
  for (int l = 0; l < u_layers; ++l)
    v += dot(vec4(texelFetch(u_stack, STACK_AT(l), 0)), u_coef[l]);
#else
  for (int l = 0; l < u_layers; ++l)
    v += float(texelFetch(u_stack, STACK_AT(l), 0).r) * u_coef[l >> 2][l & 3];
#endif
#ifdef TO_CACHE
  o_gray = uvec4(uint(clamp(floor((v + 256.0) * 64.0 + 0.5), 0.0, 65535.0)), 0u, 0u, 1u);
#else
  o_gray = vec4(v * (1.0 / 255.0), 0.0, 0.0, 1.0);
#endif
}
