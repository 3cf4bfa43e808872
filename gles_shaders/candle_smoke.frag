#version 300 es
// A thin grey line that curls and fades as it rises and ages.
precision mediump float;

in vec2 v_p;
in float v_age;
in float v_phase;
out vec4 o_color;

void main() {
  float y = v_p.y;
  float wave = sin(y * 9.0 + v_phase * 6.2831 + v_age * 6.0) * 0.4 * y;
  float width = 0.06 + 0.3 * y;
  float line = exp(-pow((v_p.x - wave) / width, 2.0));
  float fade = (1.0 - v_age) * smoothstep(0.0, 0.08, v_age + 0.02) * (1.0 - y) * smoothstep(0.0, 0.1, y);
  float a = line * fade * 0.45;
  o_color = vec4(vec3(0.6) * a, a);
}
