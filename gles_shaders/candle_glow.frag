#version 300 es
// Soft radial glow, added to what is behind it.
precision mediump float;

in vec2 v_p;
in vec4 v_color;
out vec4 o_color;

void main() {
  float r2 = dot(v_p, v_p);
  if (r2 >= 1.0) discard;
  // Bell-shaped, cheaper than exp: (1 - r^2)^4, plus a tighter inner part.
  float q = 1.0 - r2;
  q *= q;
  float g = q * q + 0.3 * max(1.0 - r2 * 6.0, 0.0);
  o_color = vec4(v_color.rgb * (g * v_color.a), 0.0);
}
