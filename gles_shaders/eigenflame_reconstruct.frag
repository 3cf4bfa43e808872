#version 300 es
// EigenFires reconstruction at the model's resolution: mean + sum_i w_i * eigen_i.
// The stack holds raw quantised values (mean first, then each eigen-image);
// value_i = offset_i + scale_i * q_i, so the CPU folds scale and weight into
// u_coef (one float per stack entry) and every offset into u_bias.
// Default (packed): four entries per RGBA texel, one layer per four entries.
// Otherwise (LAYERED): one entry per layer in the red channel.
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
out vec4 o_gray;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - u_origin;
  float v = u_bias;
#ifndef LAYERED
  for (int l = 0; l < u_layers; ++l)
    v += dot(vec4(texelFetch(u_stack, ivec3(p, l), 0)), u_coef[l]);
#else
  for (int l = 0; l < u_layers; ++l)
    v += float(texelFetch(u_stack, ivec3(p, l), 0).r) * u_coef[l >> 2][l & 3];
#endif
  o_gray = vec4(v * (1.0 / 255.0), 0.0, 0.0, 1.0);
}
