#version 300 es
// Soft radial glow, added to what is behind it.
precision mediump float;

in vec2 v_p;
in vec4 v_color;
out vec4 o_color;

void main() {
  float r2 = dot(v_p, v_p);
  if (r2 >= 1.0) discard;
  float g = exp(-r2 * 5.0) * (1.0 - r2) + 0.25 * exp(-r2 * 40.0);
  o_color = vec4(v_color.rgb * (g * v_color.a), 0.0);
}
